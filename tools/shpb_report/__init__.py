"""Figures and a one-page HTML report from any shpb output folder (`shpb report DIR`,
docs/commands.md, docs/outputs.md).

Modules: reading (the files of an output folder: Table, Source, ReportError), drawing (units, the
figure collector, axes style), one module of figures per producer — simulate, process, compare,
study (the Pareto chart of `--sweep pareto`), sweeps (the stability maps of `--sweep stability`),
fit —, page (the HTML page) and main (which figures a folder gets, the atomic write, exit codes).
A new figure goes into its producer's module and is called from main.build. Importing the
package imports nothing (reading needs numpy only; the figures need matplotlib).
"""

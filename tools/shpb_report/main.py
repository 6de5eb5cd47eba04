"""`shpb report DIR`: reads the folder, draws every figure its files allow, writes the page.

Figures are drawn into a temporary folder and moved into place at the end, so a failure leaves
any previous report intact (docs/outputs.md, conventions). Exit codes: 0 report written; 2 a bad
input (DIR holds no output file this package knows, a file or folder is malformed or unreadable —
message "error: <file>: <line/column>: <value>: <what was expected>" —, or DIR holds a figures/
folder or a report.html this package did not write: they are never replaced); 3 the report
cannot be written (read-only folder or figures/, full disk); 4 a bug of this package (one line
naming the exception and where); 130 interrupted by SIGINT or SIGTERM (nothing printed: shpb
says it), the previous report intact.

Ownership: figures/ is this package's only if it holds the marker file .shpb-report and nothing
its digest lines do not list, report.html only if it carries the page's generator line; the
output folder's own marker (.shpb-output, see core/output_folder.hpp) is told about both, with
each file's digest, so that shpb may later replace the folder whole, and neither shpb nor this
package replaces a file the user edited since.
"""
import contextlib
import errno
import os
import re
import shutil
import signal
import socket
import sys
import tempfile
import traceback
import warnings
from typing import Callable, Optional

from . import calibrate, compare, dispersion, fit, plan, process, simulate, study, sweeps
from .drawing import Figures, close_all
from .page import GENERATOR, write_html
# OUTPUT_SIGNATURE: the tests write markers through this module, as it reads them.
from .reading import (DIGEST_LINE, OUTPUT_MARKER, OUTPUT_SIGNATURE, ReportError, Source,
                      find_sources, marker_lines, output_marker_lines, read_text, recorded_file)

USAGE = """usage: shpb report DIR

DIR is an output folder of `shpb simulate`, `process`, `compare`, `study`, `fit`, `calibrate` or
`plan`, a folder holding a table of `shpb dispersion -o FILE`, or a folder whose immediate
sub-folders are such outputs (e.g. `make run` writes simulate/ and
process/ side by side). Writes DIR/figures/*.png and DIR/report.html; nothing else in DIR is touched."""

FIGURES_MARKER = ".shpb-report"
FIGURES_SIGNATURE = "figures written by shpb report; replaced only by shpb report\n"
FNV_OFFSET_BASIS = 14695981039346656037
FNV_PRIME = 1099511628211


def figures_marker_lines(fig_dir: str) -> list[str]:
    """The lines of this package's marker in `fig_dir`, none if it is not this package's."""
    return marker_lines(os.path.join(fig_dir, FIGURES_MARKER), FIGURES_SIGNATURE)


def fnv1a64(path: str) -> str:
    h = FNV_OFFSET_BASIS
    with open(path, "rb") as f:
        for byte in f.read():
            h = ((h ^ byte) * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def digest_lines(staged: str, name: str) -> list[str]:
    """The marker's digest lines of the file or folder `staged`, to be put in place as `name`:
    each regular file under it, by its path in the output folder."""
    if os.path.isfile(staged) and not os.path.islink(staged):
        return [f"{DIGEST_LINE}{fnv1a64(staged)} {name}"]
    lines = []
    for root, _, files in os.walk(staged):
        for f in sorted(files):
            path = os.path.join(root, f)
            if not os.path.islink(path):
                rel = os.path.relpath(path, staged).replace(os.sep, "/")
                lines.append(f"{DIGEST_LINE}{fnv1a64(path)} {name}/{rel}")
    return sorted(lines, key=lambda line: line.split(" ", 2)[2])


def under(path: str, names: list[str]) -> bool:
    return any(path == n or path.startswith(n + "/") for n in names)


def edited_since_written(folder: str, names: list[str]) -> Optional[str]:
    """The first file under `names` whose digest a marker records (the folder's .shpb-output if
    it is shpb's, figures/.shpb-report if it is this package's) and which no longer has it (the
    user edited it), else None. A file gone since is nothing lost."""
    lines = output_marker_lines(folder) + figures_marker_lines(os.path.join(folder, "figures"))
    # A file both markers record is read once.
    for digest, path in dict.fromkeys(r for r in map(recorded_file, lines) if r):
        full = os.path.join(folder, *path.split("/"))
        if under(path, names) and os.path.lexists(full) and (
                os.path.islink(full) or not os.path.isfile(full) or fnv1a64(full) != digest):
            return full
    return None


def added_since_written(folder: str) -> Optional[str]:
    """The first entry of figures/ that its marker's digest lines do not list (a file or folder
    the user put there: the report writes files alone), else None. A marker without digest lines
    (an older report's) lists none: its figures/ is judged by the marker alone, as before."""
    fig_dir = os.path.join(folder, "figures")
    listed = {r[1] for r in map(recorded_file, figures_marker_lines(fig_dir)) if r}
    if not listed:
        return None
    for root, dirs, files in os.walk(fig_dir):
        if dirs:
            return os.path.join(root, sorted(dirs)[0])
        rel = os.path.relpath(root, folder).replace(os.sep, "/")
        for name in sorted(files):
            if f"{rel}/{name}" not in listed and (root, name) != (fig_dir, FIGURES_MARKER):
                return os.path.join(root, name)
    return None


def check_ownership(folder: str) -> None:
    """Refuses to replace a figures/ or report.html that this script did not write, or that the
    user edited since."""
    edited = edited_since_written(folder, ["figures", "report.html"])
    if edited:
        raise ReportError(f"{edited}: was changed since shpb report wrote it: refusing to "
                          "replace it (move it away, then run the report again)")
    added = added_since_written(folder)
    if added:
        raise ReportError(f"{added}: was not written by shpb report: refusing to replace the "
                          "figures folder that holds it (move it away, then run the report again)")
    fig_dir = os.path.join(folder, "figures")
    if os.path.lexists(fig_dir) and (
            os.path.islink(fig_dir) or not os.path.isdir(fig_dir)
            or not figures_marker_lines(fig_dir)):
        raise ReportError(f"{fig_dir}: exists and was not written by shpb report: refusing to "
                          "replace it (move it away, then run the report again)")
    page = os.path.join(folder, "report.html")
    if os.path.lexists(page) and (os.path.islink(page) or GENERATOR not in read_text(page)):
        raise ReportError(f"{page}: exists and was not written by shpb report: refusing to "
                          "replace it (move it away, then run the report again)")


def sync(path: str) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def tell_output_marker(folder: str, names: list[str], digests: list[str], tmp: str) -> None:
    """Lists `names` in the folder's .shpb-output marker (if it is shpb's) with the digest lines
    of their files, `digests` (digest_lines), replacing those of the files they replace,
    atomically (through the temporary file `tmp`)."""
    marker = output_marker_lines(folder)  # whole: every line not about these names is kept
    if not marker:
        return
    lines = [line for line in marker
             if not ((r := recorded_file(line)) and under(r[1], names))]
    added = [f"file: {n}" for n in names if f"file: {n}" not in lines] + digests
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(lines + added) + "\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, os.path.join(folder, OUTPUT_MARKER))


# This run's temporaries in DIR: ".report-<host>-<pid>-<random>" (the figures), and beside it the
# same name + ".html" (the page), ".marker" (the new .shpb-output) and ".old" (the previous
# figures while they are replaced). A run killed outright leaves them, and DIR, holding files its
# marker does not list, could no longer be replaced by shpb: the next report removes those of
# runs that are gone (this host, no such pid), as core/output_folder.cpp does for shpb's own.
def temporary_prefix() -> str:
    return f".report-{socket.gethostname()}-{os.getpid()}-"


def remove_stale_temporaries(folder: str) -> None:
    pattern = re.compile(r"\.report-" + re.escape(socket.gethostname()) +
                         r"-(\d{1,9})-[A-Za-z0-9_]{8}(\.html|\.marker|\.old)?")
    for name in os.listdir(folder):
        match = pattern.fullmatch(name)
        if not match:
            continue
        try:
            os.kill(int(match.group(1)), 0)
            continue  # a report running now
        except ProcessLookupError:
            pass
        except OSError:
            continue
        path = os.path.join(folder, name)
        if os.path.islink(path):
            continue
        if not os.path.isdir(path):
            os.remove(path)
        elif (not os.listdir(path)
              or figures_marker_lines(path)
              or marker_cut_short(path)):
            shutil.rmtree(path, ignore_errors=True)


# This run's temporaries, found by their prefix rather than by the names it holds: a signal can
# land between a temporary's creation and the assignment of its name (inside mkdtemp).
def remove_own_temporaries(folder: str) -> None:
    prefix = temporary_prefix()
    with contextlib.suppress(OSError):  # in a `finally`: the error being raised is the one to tell
        for name in os.listdir(folder):
            path = os.path.join(folder, name)
            if not name.startswith(prefix) or os.path.islink(path):
                continue
            if os.path.isdir(path):
                shutil.rmtree(path, ignore_errors=True)
            else:
                os.remove(path)


# A run killed between making its folder and finishing the marker's line leaves the marker alone
# in it, cut short (empty when killed at its opening): the folder is that run's all the same.
def marker_cut_short(path: str) -> bool:
    return (os.listdir(path) == [FIGURES_MARKER]
            and FIGURES_SIGNATURE.startswith(read_text(os.path.join(path, FIGURES_MARKER))))


# SIGINT and SIGTERM stop the drawing at once (KeyboardInterrupt; the temporaries are removed),
# but not the few renames that put the report in place: a signal then is too late and ignored.
# Only the first one is raised: a Ctrl-C reaches this script and shpb, which passes it on again,
# and a second exception would cut the removal of the temporaries short.
_committing = False
_stopping = False


def _on_signal(signum, frame):
    global _stopping
    if not _committing and not _stopping:
        _stopping = True
        raise KeyboardInterrupt


def _pulses_with(column: str) -> Callable[[Source], bool]:
    return lambda src: src.has("pulses.csv") and column in src.table("pulses.csv")


def _simulated(name: str) -> Callable[[Source], bool]:
    """A simulation's file, drawn unless nothing moves in the run (six empty figures: the page
    says so instead, simulate.NOTHING_MOVES)."""
    return lambda src: src.has(name) and not simulate.nothing_moves(src)


# The figures of one output folder: (what the folder must hold, the figure). In each group the
# first figure whose condition holds is drawn (a fit's signals.csv is not a compare's).
FigureDrawer = Callable[[Source, Figures, Optional[dict]], None]
FIGURE_TABLE: list[list[tuple[Callable[[Source], bool], FigureDrawer]]] = [
    [(lambda s: s.has("path.csv"), lambda s, f, t: plan.fig_plan(s, f))],
    [(lambda s: s.has("fit.json") and s.has("signals.csv"), lambda s, f, t: fit.fig_fit(s, f)),
     (lambda s: s.has("signals.csv"), lambda s, f, t: compare.fig_compare_signals(s, f)),
     (_simulated("gauges.csv"), lambda s, f, t: simulate.fig_gauges(s, f))],
    [(_simulated("field.csv"), lambda s, f, t: simulate.fig_wave_diagram(s, f))],
    [(lambda s: s.has("calibration.json"), lambda s, f, t: calibrate.fig_calibration(s, f))],
    [(lambda s: s.has("raw_signals.csv"), lambda s, f, t: process.fig_raw_signals(s, f))],
    [(_pulses_with(process.PULSES.incident), lambda s, f, t: process.fig_pulses(s, f)),
     (_pulses_with(process.BAR_CHECK.far_measured), lambda s, f, t: process.fig_bar_check(s, f))],
    [(lambda s: s.has("curve.csv"), process.fig_curve)],
    [(lambda s: s.value("uncertainty", "figures") is not None,
      lambda s, f, t: process.fig_uncertainty(s, f))],
    [(_simulated("specimen.csv"), lambda s, f, t: simulate.fig_specimen(s, f))],
    [(_simulated("interfaces.csv"), lambda s, f, t: simulate.fig_interfaces(s, f))],
    [(_simulated("energy.csv"), lambda s, f, t: simulate.fig_energy(s, f))],
    [(lambda s: s.has("pareto.csv"), lambda s, f, t: study.fig_pareto(s, f))],
    [(lambda s: s.has("stability.csv"), lambda s, f, t: sweeps.fig_stability(s, f))],
    [(lambda s: s.has("gauge_bands.csv"), lambda s, f, t: study.fig_monte_carlo(s, f))],
    [(lambda s: bool(s.dispersion), lambda s, f, t: dispersion.fig_dispersion(s, f))],
    [(lambda s: s.has("gauge_bands.csv") and s.value("quantities") is not None,
      lambda s, f, t: study.fig_monte_carlo_contributions(s, f))],
]


def figures_of(src: Source) -> list[FigureDrawer]:
    """The figures an output folder's files allow, in the page's order."""
    drawers = []
    for group in FIGURE_TABLE:
        drawer = next((draw for holds, draw in group if holds(src)), None)
        if drawer is not None:
            drawers.append(drawer)
    return drawers


def build(folder: str) -> tuple[str, int]:
    if not os.path.isdir(folder):
        raise ReportError(f"{folder}: not a folder: an output folder of shpb was expected")
    sources = find_sources(folder)
    if not sources:
        raise ReportError(f"{folder}: no gauges.csv, curve.csv, signals.csv, pareto.csv or "
                          "other shpb output: an output folder of simulate, process, compare, "
                          "study, fit, calibrate or plan, or a dispersion table, was expected")
    check_ownership(folder)
    for src in sources:
        for missing in src.missing:
            print(f"warning: {missing}", file=sys.stderr)
        if simulate.nothing_moves(src):
            src.notes.append(simulate.NOTHING_MOVES)
    # The previous figures are set aside and removed: in a figures/ the user made read-only they
    # could not be, and would stay in DIR as a temporary its marker does not list.
    fig_dir = os.path.join(folder, "figures")
    if os.path.isdir(fig_dir) and not os.access(fig_dir, os.W_OK | os.X_OK):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), fig_dir)
    remove_stale_temporaries(folder)
    # Figures are drawn into a temporary folder and moved into place at the end, so a failure
    # leaves any previous report intact (docs/outputs.md (conventions)).
    global _committing
    try:
        try:
            tmp = tempfile.mkdtemp(prefix=temporary_prefix(), dir=folder)
        except OSError as e:  # the user's folder is named, not the temporary they never saw
            raise OSError(e.errno, e.strerror, folder) from e
        os.chmod(tmp, 0o755)
        with open(os.path.join(tmp, FIGURES_MARKER), "w", encoding="utf-8") as f:
            f.write(FIGURES_SIGNATURE)
        figs = Figures(tmp)
        truth = next((s.table("specimen.csv") for s in sources if s.has("specimen.csv")), None)
        for src in sources:
            for draw in figures_of(src):
                draw(src, figs, truth)
        if os.path.isfile(os.path.join(folder, "campaign.csv")):
            process.fig_campaign(folder, sources, figs)
        html_tmp = os.path.join(tmp, "report.html")
        write_html(html_tmp, folder, sources, figs, "figures")
        for name in os.listdir(tmp):
            sync(os.path.join(tmp, name))
        sync(tmp)
        final_html = os.path.join(folder, "report.html")
        _committing = True
        os.replace(html_tmp, tmp + ".html")
        # The figures' own marker records what the report put in place, so that a folder without
        # shpb's marker (make run's, holding simulate/ and process/) keeps the user's edits too;
        # shpb's marker records the same files, and the figures' marker itself. Each file is
        # read once.
        figures_marker = os.path.join(tmp, FIGURES_MARKER)
        placed = digest_lines(tmp + ".html", "report.html") + [
            line for line in digest_lines(tmp, "figures")
            if recorded_file(line)[1] != "figures/" + FIGURES_MARKER]
        with open(figures_marker, "a", encoding="utf-8") as f:
            f.write("".join(line + "\n" for line in placed))
            f.flush()
            os.fsync(f.fileno())
        tell_output_marker(folder, ["figures", "report.html"],
                           placed + digest_lines(figures_marker, "figures/" + FIGURES_MARKER),
                           tmp + ".marker")
        if os.path.isdir(fig_dir):  # ours (check_ownership): set aside, removed below
            os.replace(fig_dir, tmp + ".old")
        os.replace(tmp, fig_dir)
        os.replace(tmp + ".html", final_html)
        sync(folder)
        return final_html, len(figs.items)
    finally:
        # A signal now is too late: raised here it would cut the removal short, or say
        # "interrupted" of a report that was put in place.
        _committing = True
        close_all()
        remove_own_temporaries(folder)


def main(argv: list[str]) -> int:
    # No numpy or matplotlib warning on stderr (a layout that does not fit, a comparison numpy
    # will change; matplotlib's log is quieted in drawing.py), where only the one result or
    # error line goes.
    warnings.simplefilter("ignore")
    # shpb runs this after the script was killed outright (src/app/report.cpp): its temporaries
    # would keep DIR from being replaced.
    if len(argv) == 3 and argv[1] == "--remove-temporaries":
        remove_stale_temporaries(argv[2])
        return 0
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(USAGE, file=sys.stderr if len(argv) != 2 else sys.stdout)
        return 0 if len(argv) == 2 else 2
    signal.signal(signal.SIGINT, _on_signal)
    signal.signal(signal.SIGTERM, _on_signal)
    try:
        path, count = build(argv[1])
    except KeyboardInterrupt:  # shpb says so (exit 130), the previous report is left intact
        return 130
    except ReportError as e:  # a file of the folder is not what its producer writes
        print(f"error: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # read-only folder, full disk: the report cannot be written
        where = e.filename or argv[1]
        print(f"error: {where}: cannot be written: {e.strerror or e}", file=sys.stderr)
        return 3
    except Exception as e:  # noqa: BLE001 - a bug of this package, not a bad input
        frames = traceback.extract_tb(e.__traceback__)
        here = os.path.dirname(os.path.abspath(__file__))
        ours = [f for f in frames if os.path.dirname(os.path.abspath(f.filename)) == here]
        frame = (ours or frames)[-1]  # the line of this package that failed
        print(f"error: internal: shpb report: {type(e).__name__}: {e} (at "
              f"{os.path.basename(frame.filename)}:{frame.lineno}): please report it",
              file=sys.stderr)
        return 4
    print(f"report: {count} figure{'' if count == 1 else 's'}, {os.path.abspath(path)}")
    return 0

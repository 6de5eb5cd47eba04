"""Figures of `shpb study` (docs/outputs.md, study): `--sweep pareto`, accuracy against cost of
every run, with the Pareto front of pareto.csv's `pareto_front_wall_time` column; `--sweep
monte-carlo`, the bands of the gauges and of the processed curve."""
import textwrap

import numpy as np

from .drawing import new_figure
from .process import draw_contributions


def fig_pareto(src, figs):
    t = src.table("pareto.csv")
    cost = t.numeric("wall_time_s")
    error = t.numeric("error")
    stable = t.numeric("stable") > 0.5 if "stable" in t else np.ones(len(t), bool)
    ok = stable & np.isfinite(error) & np.isfinite(cost) & (error > 0) & (cost > 0)
    bad = ~stable & np.isfinite(cost) & (cost > 0)  # an unstable run, drawn at its cost
    if not (ok | bad).any():  # no run with a positive cost and error: nothing on log axes
        return
    method_of = t.text("method") if "method" in t else None
    stepping_of = t.text("stepping") if "stepping" in t else None
    methods = list(dict.fromkeys(method_of)) if method_of is not None else ["run"]
    steppings = list(dict.fromkeys(stepping_of)) if stepping_of is not None else [""]
    markers = {s: m for s, m in zip(steppings, ("o", "s", "^", "D"))}
    fig, axes = new_figure(height=5.0)
    ax = axes[0, 0]
    for k, method in enumerate(methods):
        for stepping in steppings:
            sel = ok.copy()
            if method_of is not None:
                sel &= method_of == method
            if stepping_of is not None:
                sel &= stepping_of == stepping
            if not sel.any():
                continue
            filled = stepping != "global"
            ax.scatter(cost[sel], error[sel], marker=markers.get(stepping, "o"), s=36,
                       facecolors=f"C{k}" if filled else "none", edgecolors=f"C{k}",
                       label=f"{method}, {stepping}".strip(", "))
            if "resolution" in t:
                for x, y, r in zip(cost[sel], error[sel], t.numeric("resolution")[sel]):
                    if not np.isfinite(r):  # an undefined resolution: no number to show
                        continue
                    ax.annotate(f"{r:g}", (x, y), textcoords="offset points", xytext=(4, 3),
                                fontsize=6, color="0.35")
    # The front as `shpb study` computed it (study/pareto_front.hpp), one column of pareto.csv.
    if "pareto_front_wall_time" in t:
        front = np.flatnonzero(ok & (t.numeric("pareto_front_wall_time") > 0.5))
        front = front[np.argsort(cost[front], kind="stable")]
        ax.plot(cost[front], error[front], color="k", linewidth=1.0, drawstyle="steps-post",
                label="Pareto front", zorder=0)
    if bad.any():
        y = np.nanmax(error[ok]) * 2 if ok.any() else 1.0
        ax.scatter(cost[bad], np.full(bad.sum(), y), marker="x", color="C3", label="unstable")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the solve (s)")
    reference = src.value("reference", kind=str)
    ax.set_ylabel("relative L2 error against the reference"
                  + (f"\n({textwrap.shorten(reference, 55)})" if reference else ""))
    ax.set_title(src.title("Accuracy against cost"))
    ax.legend(loc="best", fontsize=7)
    figs.save(fig, src.png("pareto"), src.title("Accuracy against cost"),
              "Error against wall time for every run of the sweep (pareto.csv): filled markers "
              "asynchronous stepping, open markers global stepping, numbers the mesh resolution "
              "factor; the black staircase is the Pareto front (no run is both faster and more "
              "accurate).")


def fig_monte_carlo(src, figs):
    """`--sweep monte-carlo`: the 95 % band of every gauge (gauge_bands.csv) and, with a reduced
    test, of the 3-wave stress against strain (curve_bands.csv), each around its nominal run."""
    g = src.table("gauge_bands.csv")
    gauges = [n for n in g.names if n != "time_s" and not n.endswith(("_p2.5", "_p50", "_p97.5"))]
    curve = src.has("curve_bands.csv")
    fig, axes = new_figure(cols=2 if curve else 1, height=4.0)
    ax = axes[0, 0]
    t = g.numeric("time_s") * 1e6
    for k, name in enumerate(gauges):
        ax.fill_between(t, g.numeric(name + "_p2.5") * 1e6, g.numeric(name + "_p97.5") * 1e6,
                        color=f"C{k}", alpha=0.3, linewidth=0)
        ax.plot(t, g.numeric(name) * 1e6, color=f"C{k}", linewidth=0.8, label=name)
    ax.set_xlabel("time (µs)")
    ax.set_ylabel("strain (µε, tension positive)")
    ax.legend(loc="best", fontsize=7)
    if curve:
        c = src.table("curve_bands.csv")
        ax = axes[0, 1]
        e = c.numeric("strain") * 100  # in %, as every other stress–strain figure
        ax.fill_between(e, c.numeric("stress_3wave_p2.5_Pa") / 1e6,
                        c.numeric("stress_3wave_p97.5_Pa") / 1e6, color="C0", alpha=0.3,
                        linewidth=0, label="95 % band")
        ax.plot(e, c.numeric("stress_3wave_Pa") / 1e6, color="C0", linewidth=1.0, label="nominal")
        ax.set_xlabel("engineering strain (%)")
        ax.set_ylabel("3-wave stress (MPa)")
        ax.legend(loc="best", fontsize=7)
    draws = src.value("draws")
    figs.save(fig, src.png("monte_carlo"), src.title("Monte Carlo bands"),
              f"The 2.5–97.5 % band over {draws} draws of the distributions "
              "(summary.json) around the nominal run: every gauge's strain against time"
              + (" and the processed 3-wave stress against strain." if curve else "."))


def fig_monte_carlo_contributions(src, figs):
    """`--sweep monte-carlo`: each drawn value's share of the variance of the headline figures
    (summary.json quantities), as bars: a table cell of records could not be read at a glance."""
    draw_contributions(src, figs, ("quantities",), "monte_carlo_contributions",
                       "Each drawn scene value's share of the variance of the headline figures "
                       "(squared correlation over the draws, summary.json quantities), the "
                       "largest eight; the title gives the 95 % interval.")

"""Figures of `shpb study --sweep pareto` (docs/outputs.md, study): accuracy against cost of
every run, with the Pareto front of pareto.csv's `pareto_front_wall_time` column."""
import textwrap

import numpy as np

from .drawing import new_figure


def fig_pareto(src, figs):
    t = src.table("pareto.csv")
    cost = t.numeric("wall_time_s")
    error = t.numeric("error")
    stable = t.numeric("stable") > 0.5 if "stable" in t else np.ones(len(t), bool)
    ok = stable & np.isfinite(error) & np.isfinite(cost) & (error > 0) & (cost > 0)
    methods = list(dict.fromkeys(t["method"])) if "method" in t else ["run"]
    steppings = list(dict.fromkeys(t["stepping"])) if "stepping" in t else [""]
    markers = {s: m for s, m in zip(steppings, ("o", "s", "^", "D"))}
    fig, axes = new_figure(height=5.0)
    ax = axes[0, 0]
    for k, method in enumerate(methods):
        for stepping in steppings:
            sel = ok.copy()
            if "method" in t:
                sel &= t["method"] == method
            if "stepping" in t:
                sel &= t["stepping"] == stepping
            if not sel.any():
                continue
            filled = stepping != "global"
            ax.scatter(cost[sel], error[sel], marker=markers.get(stepping, "o"), s=36,
                       facecolors=f"C{k}" if filled else "none", edgecolors=f"C{k}",
                       label=f"{method}, {stepping}".strip(", "))
            if "resolution" in t:
                for x, y, r in zip(cost[sel], error[sel], t.numeric("resolution")[sel]):
                    ax.annotate(f"{r:g}", (x, y), textcoords="offset points", xytext=(4, 3),
                                fontsize=6, color="0.35")
    # The front as `shpb study` computed it (study/pareto_front.hpp), one column of pareto.csv.
    if "pareto_front_wall_time" in t:
        front = np.flatnonzero(ok & (t.numeric("pareto_front_wall_time") > 0.5))
        front = front[np.argsort(cost[front], kind="stable")]
        ax.plot(cost[front], error[front], color="k", linewidth=1.0, drawstyle="steps-post",
                label="Pareto front", zorder=0)
    bad = ~stable
    if bad.any():
        y = np.nanmax(error[ok]) * 2 if ok.any() else 1.0
        ax.scatter(cost[bad & np.isfinite(cost) & (cost > 0)],
                   np.full((bad & np.isfinite(cost) & (cost > 0)).sum(), y), marker="x",
                   color="C3", label="unstable")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the solve (s)")
    reference = src.value("reference", kind=str)
    ax.set_ylabel("error against the reference"
                  + (f"\n({textwrap.shorten(reference, 55)})" if reference else ""))
    ax.set_title(src.title("Accuracy against cost"))
    ax.legend(loc="best", fontsize=7)
    figs.save(fig, src.png("pareto"), src.title("Accuracy against cost"),
              "Error against wall time for every run of the sweep (pareto.csv): filled markers "
              "asynchronous stepping, open markers global stepping, numbers the mesh resolution "
              "factor; the black staircase is the Pareto front (no run is both faster and more "
              "accurate).")

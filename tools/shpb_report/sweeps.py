"""Figures of `shpb study --sweep stability` (docs/outputs.md, study): the stability maps of the
contact methods over penalty stiffness and Courant number, with the measured boundary of
stability_boundary.csv and its closed form (docs/methods.md §2)."""
import math

import numpy as np

from .drawing import new_figure, panel_rows
from .reading import slug

# A re-closing after the release that carries more than this share of the impact's peak force is
# charted as a rattle: twice a good lab's record noise (about 0.5 % of the peak) and above
# the 0.1-1 % that the converged model's grazing contact carries after a specimen's
# unloading (docs/methods.md §3.7), so what is marked is the method's, not the physics'.
RATTLE_SHARE = 0.01


def boundary(ax, b, rows, rigid):
    """The measured boundary of each link and its closed form (stability_boundary.csv's `rows`):
    lines over the stiffness, or a level across a rigid-link panel, which has no stiffness."""
    bx = b.numeric("stiffness_factor")
    lines = [(b.numeric("critical_courant"), rows & (b.text("link") == link),
              {"color": color, "linestyle": dash}, f"measured boundary ({link})")
             for link, color, dash in (("unilateral", "k", "-"), ("tied", "b", "--"))]
    lines.append((b.numeric("closed_form_courant"), rows, {"color": "C4", "linestyle": ":"},
                  "closed form"))
    for values, on, style, label in lines:
        m = np.flatnonzero(on)
        if m.size and rigid:
            ax.axhline(values[m[0]], linewidth=1.0, label=label, **style)
        elif m.size:
            m = m[np.argsort(bx[m])]
            ax.plot(bx[m], values[m], linewidth=1.0, label=label, **style)


def one_legend(panels):
    """One legend of every panel's entries, above the first: inside each panel it lay over the
    stable runs at low stiffness and Courant number, the same nine times over."""
    entries = {}
    for ax in panels:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
    if not entries:
        return
    first = panels[0]
    first.legend(list(entries.values()), list(entries), loc="lower left",
                 bbox_to_anchor=(0.0, 1.0), ncol=2, fontsize=7, frameon=False)
    rows = math.ceil(len(entries) / 2)
    first.set_title(first.get_title(), fontsize=9, pad=12 * rows + 8)  # above the legend


def fig_stability(src, figs):
    t = src.table("stability.csv")
    xcol, ycol = "stiffness_factor", "courant"
    rcol = "mass_ratio" if "mass_ratio" in t else None
    keys = t.text("method") if "method" in t else None
    if keys is not None and "step_ratio" in t:
        # Localized bipenalty is mapped at several step ratios (asynchronous): one figure each.
        keys = np.array([m if not (np.isfinite(q) and q != 1) else f"{m} step ratio {q:.3g}"
                         for m, q in zip(keys, t.numeric("step_ratio"))])
    methods = list(dict.fromkeys(keys)) if keys is not None else [""]
    stable = t.numeric("stable") > 0.5
    # Where a method rattles: a stable run whose link closes again after its release with a
    # force a gauge would read (maps written before the column existed have none).
    charted_rattle = "force_after_unloading_share" in t
    rattles = stable & (t.numeric("force_after_unloading_share") > RATTLE_SHARE
                        if charted_rattle else np.zeros(len(t), bool))
    x, y = t.numeric(xcol), t.numeric(ycol)
    positive = x[x > 0]
    finite_range = ((positive.min() / 2, positive.max() * 2) if positive.size else (1e-2, 1e6))
    # The measured boundary and its closed form (stability_boundary.csv), keyed as the map is.
    b = src.table("stability_boundary.csv") if src.has("stability_boundary.csv") else None
    if b is not None and len(b):
        bkeys = np.array([m if not (np.isfinite(q) and q != 1) else f"{m} step ratio {q:.3g}"
                          for m, q in zip(b.text("method"), b.numeric("step_ratio"))])
    for method in methods:
        sel = (keys == method) if keys is not None else np.ones(len(t), bool)
        ratios = [None]
        if rcol is not None:
            values = t.numeric(rcol)[sel]
            ratios = sorted(set(v for v in values if np.isfinite(v))) or [None]
        n = len(ratios)
        cols = min(n, 3)
        rows = panel_rows(math.ceil(n / cols), t.path, f"rows of mass ratios ({n}, 3 a row)")
        # Not sharex: the rigid-link limit (ε_s/k 0) has no place on the stiffness's log axis.
        fig, axes = new_figure(rows, cols, height=3.6 * rows + 0.4, width=4.2 * cols + 1.0,
                               sharey=True)
        for k, r in enumerate(ratios):
            ax = axes.flat[k]
            s = sel.copy()
            if r is not None:
                s &= t.numeric(rcol) == r
            rigid = bool(s.any()) and not np.any(x[s] > 0)
            ax.scatter(x[s & stable & ~rattles], y[s & stable & ~rattles], marker="s", s=28,
                       color="C2", label="stable")
            if charted_rattle:  # in the legend even when empty: none rattles
                ax.scatter(x[s & rattles], y[s & rattles], marker="^", s=30, color="C1",
                           label=f"stable, closes again after its release with > "
                                 f"{RATTLE_SHARE:.0%} of the peak force")
            ax.scatter(x[s & ~stable], y[s & ~stable], marker="x", s=28, color="C3",
                       label="unstable")
            if b is not None and len(b):
                bs = bkeys == method
                if r is not None:
                    bs &= b.numeric("mass_ratio") == r
                boundary(ax, b, bs, rigid)
            if method == "penalty":
                k_ratio = np.logspace(np.log10(max(np.nanmin(x), 1e-12)),
                                      np.log10(np.nanmax(x)), 200)
                ax.plot(k_ratio, np.minimum(1.0, np.sqrt(2.0 / k_ratio)), color="k",
                        linestyle="--", linewidth=1.0, label="≈ √(2k/ε_s) (docs/methods.md §2)")
            if rigid:
                ax.set_xlim(-1.0, 1.0)
                ax.set_xticks([0.0], ["rigid-link limit"])
                ax.set_title("rigid-link limit (no ε_s, R)", fontsize=9)
                ax.set_ylabel("Courant number c·Δt/h")
                continue
            ax.set_xscale("log")
            ax.set_xlim(*finite_range)
            ax.set_title((f"R/R_crit = {r:g}" if r is not None else method), fontsize=9)
            ax.set_xlabel("penalty stiffness ε_s / (EA/h)")
            ax.set_ylabel("Courant number c·Δt/h")
        for ax in list(axes.flat)[n:]:
            ax.set_visible(False)
        one_legend(list(axes.flat)[:n])
        fig.suptitle(src.title(f"Stability map: {method}".rstrip(": ")))
        figs.save(fig, src.png(f"stability_{slug(method or 'all')}"),
                  src.title(f"Stability map {method}".strip()),
                  "Stable (green), rattling (orange: stable, but closing again after the release "
                  f"with more than {RATTLE_SHARE:.0%} of the peak force) and unstable (red: "
                  "energy growth or NaN) runs over penalty stiffness and Courant number "
                  "(stability.csv)"
                  + (", one panel per mass-penalty ratio R/R_crit." if rcol else "."))

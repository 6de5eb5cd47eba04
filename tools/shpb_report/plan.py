"""Figures of `shpb plan` (docs/outputs.md, plan: summary.json, path.csv, loading.csv and the
verification run in simulation/): the predicted gauge signals against the recommended scope
settings, the specimen's rate against the ±10 % band and the equilibrium ratio against 5 % with the
quarter-of-the-loading mark, the shaper's gain (the chosen set-up beside the best unshaped one)
and the search's path."""
import os

import numpy as np

from .drawing import MICRO, US, new_figure, outside_legend
from .reading import NUMBER, Table
from .schema import columns

PATH = columns("plan_path")
LOADING = columns("plan_loading")


def _targets(src):
    return (src.value("targets", "strain_rate_1_s", kind=NUMBER) or 0.0,
            src.value("targets", "rate_band", kind=NUMBER) or 0.1,
            src.value("targets", "equilibrium_ratio_max", kind=NUMBER) or 0.05,
            src.value("targets", "equilibrium_before_fraction", kind=NUMBER) or 0.25)


def fig_loading(src, figs):
    """The verification run's specimen rate and equilibrium ratio against the criteria."""
    t = src.table(LOADING.FILE)
    rate_target, band, ratio_max, before = _targets(src)
    time = t.numeric(LOADING.time_s) * US
    loading = (t.numeric(LOADING.loading) > 0.5) & np.isfinite(time)  # undefined times: no span
    fig, axes = new_figure(2, 1, height=6.4, sharex=True)
    ax = axes[0, 0]
    ax.plot(time, t.numeric(LOADING.strain_rate_1_s), color="C0", linewidth=1.0,
            label="specimen strain rate")
    if rate_target > 0:
        ax.axhspan((1 - band) * rate_target, (1 + band) * rate_target, color="C2", alpha=0.15,
                   label=f"target ±{100 * band:.0f} %")
        ax.axhline(rate_target, color="C2", linewidth=0.8)
    ax.set_ylabel("strain rate (1/s)")
    ax2 = axes[1, 0]
    # R over the loading alone, the span the criteria judge: after it the specimen unloads, the
    # face forces ring about small values and their ratio filled the panel with noise.
    ratio = t.numeric(LOADING.equilibrium_ratio)
    if loading.any():
        ratio = np.where(loading, ratio, np.nan)
    ax2.plot(time, 100 * np.minimum(ratio, 2.0), color="C3", linewidth=1.0,
             label="R = 2|P1 − P2|/|P1 + P2| of the bars' face forces, over the loading")
    ax2.axhline(100 * ratio_max, color="k", linestyle="--", linewidth=0.8,
                label=f"R = {100 * ratio_max:.0f} %")
    ax2.set_ylabel("R (%)")
    ax2.set_xlabel("time (µs)")
    if loading.any():
        t0, t1 = time[loading][0], time[loading][-1]
        mark = t0 + before * (t1 - t0)
        for a in (ax, ax2):
            a.axvspan(t0, t1, color="0.9", zorder=0)
            a.axvline(mark, color="C1", linewidth=1.0,
                      label=f"{100 * before:.0f} % of the loading")
        margin = 0.5 * (t1 - t0)
        ax.set_xlim(t0 - margin, t1 + margin)
        ax2.set_ylim(0, 4 * 100 * ratio_max)  # R near the criterion; the onset spike is off scale
        ax.set_ylim(0, 1.6 * max(rate_target, float(np.max(t.numeric(LOADING.strain_rate_1_s)
                                                            [loading]))))
    outside_legend(ax)
    outside_legend(ax2)
    figs.save(fig, src.png("plan_loading"), src.title("Planned test: rate and equilibrium"),
              "The planned set-up's verification run: the specimen's strain rate against the "
              "target band, and the equilibrium ratio of the forces the bars put on its faces "
              "(what the gauges measure) against 5 %, drawn over the loading the criteria judge "
              "(grey); orange: a quarter of it, before which R must come below 5 % to stay.")


def fig_scope(src, figs):
    """The predicted gauge signals in volts with the recommended range and trigger level."""
    gauges_csv = os.path.join(src.folder, "simulation", "gauges.csv")
    gauges = src.value("gauges", kind=list) or []
    if not os.path.isfile(gauges_csv) or not gauges:
        return
    t = Table(gauges_csv)
    time = t.numeric("time_s") * US
    fig, axes = new_figure(1, 2, width=11)
    ax, axv = axes[0, 0], axes[0, 1]
    for i, g in enumerate(gauges):
        if not isinstance(g, dict) or not isinstance(g.get("gauge"), str):
            continue
        strain = t.numeric(g["gauge"])
        peak, volts = g.get("peak_strain"), g.get("peak_V")
        ax.plot(time, strain * MICRO, color=f"C{i}", linewidth=1.0, label=g["gauge"])
        if isinstance(peak, (int, float)) and isinstance(volts, (int, float)) and peak != 0:
            axv.plot(time, strain * volts / peak, color=f"C{i}", linewidth=1.0, label=g["gauge"])
    scope_range = src.value("scope", "range_V", kind=NUMBER)
    trigger = src.value("scope", "trigger_level_V", kind=NUMBER)
    if scope_range:
        for y in (-scope_range, scope_range):
            axv.axhline(y, color="k", linestyle="--", linewidth=0.8)
    if trigger:
        axv.axhline(trigger, color="C1", linestyle=":", linewidth=1.0, label="trigger level")
    ax.set_xlabel("time (µs)")
    ax.set_ylabel("strain (µε)")
    axv.set_xlabel("time (µs)")
    axv.set_ylabel("bridge output (V)")
    outside_legend(ax)
    outside_legend(axv)
    figs.save(fig, src.png("plan_gauges"), src.title("Planned test: predicted gauge signals"),
              "The gauges' predicted strains (left) and their bridge outputs (right) with the "
              "recommended scope range (dashed, ±range_V) and trigger level (dotted), "
              "summary.json `scope`.")


def fig_gain(src, figs):
    """The chosen set-up's rate flatness and equilibrium beside the best unshaped and shaped
    ones' (the shaper's gain)."""
    chosen = src.value("predicted", kind=dict)
    sides = [(label, src.value(key, "predicted", kind=dict), colour)
             for key, label, colour in (("unshaped", "best unshaped", "C7"),
                                        ("shaped", "best shaped", "C1"))]
    sides = [s for s in sides if s[1]]
    if not chosen or not sides:
        return
    rate_target, band, ratio_max, before = _targets(src)
    keys = [("band_fraction", "rate in band\n(of the loading)", 0.5),
            ("rate_spread", "rate spread\n(std / target)", None),
            ("equilibrium_fraction", "equilibrium at\n(of the loading)", before)]
    fig, axes = new_figure(1, 1, height=3.8, width=8)
    ax = axes[0, 0]
    x = np.arange(len(keys))
    bars = [("chosen" + (" (shaped)" if src.value("chosen", "shaper") else ""), chosen, "C0")]
    bars += sides
    width = 0.8 / len(bars)
    for i, (label, p, colour) in enumerate(bars):
        values = [p.get(k) if isinstance(p.get(k), (int, float)) else np.nan for k, _, _ in keys]
        ax.bar(x - 0.4 + width * (i + 0.5), values, width=width * 0.9, color=colour, label=label)
    for i, (_, _, limit) in enumerate(keys):
        if limit is not None:
            ax.plot([i - 0.45, i + 0.45], [limit, limit], color="k", linestyle="--",
                    linewidth=0.8)
    ax.set_xticks(x)
    ax.set_xticklabels([name for _, name, _ in keys])
    outside_legend(ax)
    figs.save(fig, src.png("plan_shaper_gain"), src.title("Planned test: the shaper's gain"),
              "The chosen set-up beside the best one of the search without a pulse shaper and "
              "the best one with one, each verified on the same meshes: the fraction of the "
              "loading with the rate within the band (at least 50 %), the rate's spread, and "
              "when equilibrium is reached (before 25 %); dashed: the criteria.")


def fig_path(src, figs):
    """Each set-up the search evaluated: its velocity and the criteria it reached."""
    t = src.table(PATH.FILE)
    if len(t) == 0:
        return
    step = t.numeric(PATH.step)
    meets = t.numeric(PATH.meets) > 0.5
    shaped = t.numeric(PATH.shaper) >= 0
    rate_target, band, ratio_max, before = _targets(src)
    fig, axes = new_figure(3, 1, height=8.0, sharex=True)
    panels = [(PATH.striker_velocity_m_s, "striker velocity (m/s)", None),
              (PATH.band_fraction, "rate in band\n(of the loading)", 0.5),
              (PATH.equilibrium_fraction, "equilibrium at\n(of the loading)", before)]
    for ax, (name, label, limit) in zip(axes[:, 0], panels):
        y = t.numeric(name)
        for sel, marker, text in ((~shaped, "o", "no shaper"), (shaped, "s", "shaper")):
            for ok, face in ((meets, None), (~meets, "none")):
                pick = sel & ok
                if pick.any():
                    ax.scatter(step[pick], y[pick], marker=marker, s=18, edgecolors="C0",
                               facecolors=face or "C0",
                               label=f"{text}, {'meets' if face is None else 'misses'}")
        if limit is not None:
            ax.axhline(limit, color="k", linestyle="--", linewidth=0.8)
        ax.set_ylabel(label)
    axes[-1, 0].set_xlabel("step of the search (grid, then compass search)")
    outside_legend(axes[0, 0])
    figs.save(fig, src.png("plan_path"), src.title("Planned test: the search's path"),
              "Every set-up the search evaluated (path.csv), its velocity solved for the target "
              "rate on the search's coarse meshes: filled, it met every criterion there; "
              "squares carry a pulse shaper; dashed: the criteria.")


def fig_plan(src, figs):
    fig_scope(src, figs)
    if src.has(LOADING.FILE):
        fig_loading(src, figs)
    fig_gain(src, figs)
    fig_path(src, figs)

"""Figures of `shpb compare` (docs/outputs.md, compare): simulated over measured gauge signals,
with the compared pulse windows of comparison.csv."""
import re

from .drawing import MICRO, US, new_figure, outside_legend, panel_rows
from .schema import columns, suffix

COMPARISON = columns("comparison")
SIGNALS = columns("compare_signals")
MEASURED = suffix("compare_signals", "<gauge>_measured_strain")
SIMULATED = suffix("compare_signals", "<gauge>_simulated_strain")
SIMULATED_RAW = suffix("compare_signals", "<gauge>_simulated_raw_strain")


def fig_compare_signals(src, figs):
    t = src.table(SIGNALS.FILE)
    time = t.numeric(SIGNALS.time_s) * US
    gauges = []
    for n in t.names:
        m = re.fullmatch("(.+)" + re.escape(MEASURED), n)
        if m:
            gauges.append(m.group(1))
    if not gauges:
        return
    windows = []
    if src.has(COMPARISON.FILE):
        c = src.table(COMPARISON.FILE)
        k = COMPARISON
        if all(n in c for n in (k.gauge, k.pulse, k.window_start_s, k.window_end_s)):
            for row in zip(c.text(k.gauge), c.text(k.pulse), c.numeric(k.window_start_s),
                           c.numeric(k.window_end_s)):
                windows.append(row)
    rows = panel_rows(len(gauges), t.path, "gauges")
    fig, axes = new_figure(rows, 1, height=2.9 * rows + 0.6, sharex=True)
    for ax, g in zip(axes[:, 0], gauges):
        ax.plot(time, t.numeric(g + MEASURED) * MICRO, color="k", linewidth=1.2,
                label="measured")
        dispersed = src.value("dispersion")
        # Without dispersion (--no-dispersion) the raw column is the simulated one: drawn once.
        if g + SIMULATED_RAW in t and (dispersed or g + SIMULATED not in t):
            ax.plot(time, t.numeric(g + SIMULATED_RAW) * MICRO, color="C0",
                    linewidth=0.8, alpha=0.6, label="simulated (1D, no dispersion)")
        if g + SIMULATED in t:
            label = "simulated + Pochhammer–Chree" if dispersed else "simulated"
            ax.plot(time, t.numeric(g + SIMULATED) * MICRO, color="C3",
                    linewidth=1.0, linestyle="--", label=label)
        for gauge, pulse, t0, t1 in windows:
            if gauge == g:
                ax.axvspan(t0 * US, t1 * US, color="C1", alpha=0.08)
                ax.text((t0 + t1) / 2 * US, 0.97, pulse, transform=ax.get_xaxis_transform(),
                        ha="center", va="top", fontsize=8, color="C1")
        ax.set_ylabel(f"{g}\nstrain (µε, tension +)")
        outside_legend(ax)
    fig.suptitle(src.title("Simulated over measured gauge signals"))  # above the legends
    axes[-1, 0].set_xlabel("time on the measurement's clock (µs)")
    figs.save(fig, src.png("signals"),
              src.title("Gauge signals: simulated over measured"),
              "Measured strain (black) and the simulation of the same scene (dashed), on the "
              "measurement's clock; shaded: the pulse windows compared in comparison.csv.")

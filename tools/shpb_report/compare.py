"""Figures of `shpb compare` (docs/outputs.md, compare): simulated over measured gauge signals,
with the compared pulse windows of comparison.csv."""
import re

from .drawing import MICRO, US, new_figure, outside_legend


def fig_compare_signals(src, figs):
    t = src.table("signals.csv")
    time = t.numeric("time_s") * US
    gauges = []
    for n in t.names:
        m = re.fullmatch(r"(.+)_measured_strain", n)
        if m:
            gauges.append(m.group(1))
    if not gauges:
        return
    windows = []
    if src.has("comparison.csv"):
        c = src.table("comparison.csv")
        if all(k in c for k in ("gauge", "pulse", "window_start_s", "window_end_s")):
            for row in zip(c["gauge"], c["pulse"], c.numeric("window_start_s"),
                           c.numeric("window_end_s")):
                windows.append(row)
    fig, axes = new_figure(len(gauges), 1, height=2.9 * len(gauges) + 0.6, sharex=True)
    for ax, g in zip(axes[:, 0], gauges):
        ax.plot(time, t.numeric(f"{g}_measured_strain") * MICRO, color="k", linewidth=1.2,
                label="measured")
        if f"{g}_simulated_raw_strain" in t:
            ax.plot(time, t.numeric(f"{g}_simulated_raw_strain") * MICRO, color="C0",
                    linewidth=0.8, alpha=0.6, label="simulated (1D, no dispersion)")
        if f"{g}_simulated_strain" in t:
            dispersed = src.value("dispersion")
            label = "simulated + Pochhammer–Chree" if dispersed else "simulated"
            ax.plot(time, t.numeric(f"{g}_simulated_strain") * MICRO, color="C3",
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

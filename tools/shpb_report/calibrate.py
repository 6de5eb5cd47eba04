"""Figures of `shpb calibrate` (docs/outputs.md, calibrate: calibration.json, summary.json and one
shot-K.csv per shot): each shot's measured returning pulses against the model at the nominal and
the fitted values, and the residuals of the fit over the compared samples."""
import os

import numpy as np

from .drawing import MICRO, US, new_figure, outside_legend, panel_rows
from .reading import ReportError, Table


def fig_calibration(src, figs):
    """Per shot: measured, nominal and fitted signals of each gauge, and the fit's residuals."""
    shots = src.value("scenes", kind=list) or []
    for k, shot in enumerate(shots, start=1):
        if not isinstance(shot, dict) or not isinstance(shot.get("signals"), str):
            raise ReportError(f"{src.files['summary.json']}: scenes[{k - 1}]: {shot!r}: an "
                              "object with \"signals\" (a shot-K.csv) was expected")
        name = os.path.basename(shot["signals"])
        path = os.path.join(src.folder, name)
        if not os.path.isfile(path):
            raise ReportError(f"{path}: missing: the shot's signals named in summary.json "
                              "were expected")
        t = Table(path)
        gauges = [g for g in src.value("scenes", k - 1, "gauges", kind=list) or []
                  if isinstance(g, str)]
        if not gauges:
            continue
        time = t.numeric("time_s") * US
        rows = panel_rows(len(gauges), src.files["summary.json"], f"gauges of scenes[{k - 1}]")
        fig, axes = new_figure(rows, 2, height=2.9 * rows + 0.6, width=11)
        for i, g in enumerate(gauges):
            measured = t.numeric(f"{g}_measured")
            fitted = t.numeric(f"{g}_fitted")
            compared = t.numeric(f"{g}_compared") > 0.5
            ax = axes[i, 0]
            ax.plot(time, measured * MICRO, color="k", linewidth=1.0, label="measured")
            ax.plot(time, t.numeric(f"{g}_nominal") * MICRO, color="C0", linewidth=0.8,
                    alpha=0.7, label="nominal")
            ax.plot(time, fitted * MICRO, color="C3", linewidth=1.0, linestyle="--",
                    label="fitted")
            ax.set_title(f"{shot.get('kind', '')}: gauge {g}", fontsize=9, pad=20)
            ax.set_xlabel("time (µs)")
            ax.set_ylabel("strain (µε, tension +)")
            outside_legend(ax)  # inside, it hid the last returning pulse
            ax = axes[i, 1]
            residual = np.where(compared, measured - fitted, np.nan)
            ax.plot(time, residual * MICRO, color="C3", linewidth=0.8)
            rms = shot.get("rms_of_peak", {})
            title = f"residual, gauge {g}"
            if isinstance(rms, dict) and all(isinstance(rms.get(x), (int, float))
                                             for x in ("nominal", "fitted")):
                title += (f" (RMS {100 * rms['nominal']:.2f} % → {100 * rms['fitted']:.2f} % "
                          "of peak)")
            ax.set_title(title, fontsize=9, pad=20)  # level with the left one
            ax.set_xlabel("time (µs)")
            ax.set_ylabel("measured − fitted (µε)")
        figs.save(fig, src.png(f"calibration_shot{k}"),
                  src.title(f"Calibration shot {k}: {shot.get('scene', '')}"),
                  "The returning pulses of each gauge: measured (black), the source pulse moved "
                  "with the nominal constants (blue) and with the fitted ones (dashed); right, "
                  "measured − fitted over the compared samples.")

"""Figures of `shpb fit` (docs/outputs.md, fit: fit.json, curves.csv and the long-format
signals.csv): measured, starting and fitted pulses per test, the processed curves against the law,
and the parameter correlations."""
import numpy as np

from .drawing import MICRO, MPA, US, new_figure
from .reading import ReportError
from .schema import columns

CURVES = columns("fit_curves")
SIGNALS = columns("fit_signals")


def fig_fit(src, figs):
    """Measured against start and fitted pulses per test, curves with the law, correlations."""
    t, k = src.table(SIGNALS.FILE), SIGNALS
    for name in (k.test, k.pulse, k.time_s, k.measured_strain, k.start_strain, k.fitted_strain):
        if name not in t:
            raise ReportError(f"{t.path}: header: {','.join(t.names)}: a column {name} "
                              "was expected (shpb fit's signals.csv)")
    tests = list(dict.fromkeys(t[k.test]))
    pulses = list(dict.fromkeys(t[k.pulse]))
    if not tests or not pulses:
        return
    nrmse = {x["name"]: x for x in src.value("tests", kind=list) or []
             if isinstance(x, dict) and isinstance(x.get("name"), str)}
    fig, axes = new_figure(len(tests), len(pulses), height=2.8 * len(tests) + 0.6,
                           width=4.2 * len(pulses) + 1)
    for i, test in enumerate(tests):
        for j, pulse in enumerate(pulses):
            ax = axes[i, j]
            m = (t[k.test] == test) & (t[k.pulse] == pulse)
            time = t.numeric(k.time_s)[m] * US
            ax.plot(time, t.numeric(k.measured_strain)[m] * MICRO, color="k", linewidth=1.1,
                    label="measured")
            ax.plot(time, t.numeric(k.start_strain)[m] * MICRO, color="C0", linewidth=0.8,
                    alpha=0.7, label="start")
            ax.plot(time, t.numeric(k.fitted_strain)[m] * MICRO, color="C3", linewidth=1.0,
                    linestyle="--", label="fitted")
            r = nrmse.get(test, {})
            before, after = r.get(f"nrmse_{pulse}_before"), r.get(f"nrmse_{pulse}_after")
            title = f"{test}: {pulse}"
            if all(isinstance(v, (int, float)) and not isinstance(v, bool)
                   for v in (before, after)):
                title += f" (NRMSE {before:.3f} → {after:.3f})"
            ax.set_title(title, fontsize=9)
            ax.set_xlabel("time (µs)")
            ax.set_ylabel("strain (µε)")
            ax.legend(loc="lower right", fontsize=7)
    figs.save(fig, src.png("fit_signals"), src.title("Fit: measured and simulated pulses"),
              "Each compared window of each test: measured (black), simulated with the starting "
              "law (blue) and with the fitted one (dashed); NRMSE as in summary.json.")

    if src.has(CURVES.FILE):
        c = src.table(CURVES.FILE)
        fig, axes = new_figure()
        ax = axes[0, 0]
        for n, test in enumerate(dict.fromkeys(c[CURVES.test])):
            m = c[CURVES.test] == test
            ep = c.numeric(CURVES.true_plastic_strain)[m]
            ax.plot(ep, c.numeric(CURVES.stress_measured_Pa)[m] * MPA, color=f"C{n}", linewidth=1.0,
                    label=f"{test} processed")
            ax.plot(ep, c.numeric(CURVES.stress_fitted_Pa)[m] * MPA, color=f"C{n}", linewidth=1.0,
                    linestyle="--", label=f"{test} fitted law")
            ax.plot(ep, c.numeric(CURVES.stress_start_Pa)[m] * MPA, color=f"C{n}", linewidth=0.7,
                    linestyle=":", alpha=0.8)
        ax.set_xlabel("true plastic strain")
        ax.set_ylabel("true stress (MPa)")
        ax.set_title(src.title("Processed curves after equilibrium and the law"))
        ax.legend(fontsize=7)
        figs.save(fig, src.png("fit_curves"), src.title("Fit: curves and the law"),
                  "Processed true stress after equilibrium (solid), the fitted law at the same "
                  "plastic strain, rate and temperature (dashed) and the starting law (dotted).")

    names = src.value("correlation", "parameters", kind=list) or []
    matrix = src.value("correlation", "matrix", kind=list) or []
    a = None
    try:
        a = np.array(matrix, dtype=float)
    except (TypeError, ValueError):  # not a matrix of numbers: no correlation figure
        pass
    if names and a is not None and a.shape == (len(names), len(names)):
        names = [str(n) for n in names]
        fig, axes = new_figure(height=0.5 * len(names) + 2.5, width=0.6 * len(names) + 3.5)
        ax = axes[0, 0]
        im = ax.imshow(a, vmin=-1, vmax=1, cmap="RdBu_r")
        ax.set_xticks(range(len(names)), names, rotation=45, ha="right", fontsize=8)
        ax.set_yticks(range(len(names)), names, fontsize=8)
        for i in range(len(names)):
            for j in range(len(names)):
                ax.text(j, i, f"{a[i, j]:.2f}", ha="center", va="center", fontsize=7)
        fig.colorbar(im, ax=ax)
        ax.set_title(src.title("Parameter correlations"))
        figs.save(fig, src.png("fit_correlation"), src.title("Fit: parameter correlations"),
                  "Correlations of the fitted parameters from the covariance of the last stage; "
                  "|r| > 0.98 means two parameters are not separately identifiable.")

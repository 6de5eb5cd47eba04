"""Figures of `shpb fit` (docs/outputs.md, fit: fit.json, curves.csv and the long-format
signals.csv): measured, starting and fitted pulses per test, the processed curves against the law,
and the parameter correlations."""
import numpy as np

from .drawing import MICRO, MPA, US, new_figure, outside_legend, panel_rows
from .reading import ReportError, number_pair
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
    test_of, pulse_of = t.text(k.test), t.text(k.pulse)
    tests = list(dict.fromkeys(test_of))
    pulses = list(dict.fromkeys(pulse_of))
    if not tests or not pulses:
        return
    nrmse = {x["name"]: x for x in src.value("tests", kind=list) or []
             if isinstance(x, dict) and isinstance(x.get("name"), str)}
    rows, cols = panel_rows(len(tests), t.path, "tests"), panel_rows(len(pulses), t.path, "pulses")
    fig, axes = new_figure(rows, cols, height=2.8 * rows + 0.6, width=4.2 * cols + 1)
    for i, test in enumerate(tests):
        for j, pulse in enumerate(pulses):
            ax = axes[i, j]
            m = (test_of == test) & (pulse_of == pulse)
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
            ax.set_title(title, fontsize=9, pad=20)
            ax.set_xlabel("time (µs)")
            ax.set_ylabel("strain (µε, tension +)")
            outside_legend(ax)  # inside, it hid the pulse's tail
    figs.save(fig, src.png("fit_signals"), src.title("Fit: measured and simulated pulses"),
              "Each compared window of each test: measured (black), simulated with the starting "
              "law (blue) and with the fitted one (dashed); NRMSE as in summary.json.")

    if src.has(CURVES.FILE):
        c = src.table(CURVES.FILE)
        fig, axes = new_figure()
        ax = axes[0, 0]
        # A viscoelastic law has no flow stress: curves.csv gives its response along the test's
        # strain history, drawn against the true strain (its plastic strain means nothing).
        viscous = src.value("model", kind=str) == "viscoelastic"
        curve_of = c.text(CURVES.test)
        for n, test in enumerate(dict.fromkeys(curve_of)):
            m = curve_of == test
            ep = c.numeric(CURVES.true_strain if viscous else CURVES.true_plastic_strain)[m]
            ax.plot(ep, c.numeric(CURVES.stress_measured_Pa)[m] * MPA, color=f"C{n}", linewidth=1.0,
                    label=f"{test} processed")
            ax.plot(ep, c.numeric(CURVES.stress_fitted_Pa)[m] * MPA, color=f"C{n}", linewidth=1.0,
                    linestyle="--", label=f"{test} fitted law")
            ax.plot(ep, c.numeric(CURVES.stress_start_Pa)[m] * MPA, color=f"C{n}", linewidth=0.7,
                    linestyle=":", alpha=0.8, label=f"{test} starting law")
        ax.set_xlabel("true strain" if viscous else "true plastic strain")
        ax.set_ylabel("true stress (MPa)")
        ax.set_title(src.title("Processed curves after equilibrium and the law"))
        ax.legend(fontsize=7)
        figs.save(fig, src.png("fit_curves"), src.title("Fit: curves and the law"),
                  "Processed true stress after equilibrium (solid), the fitted law at the same "
                  "plastic strain, rate and temperature (dashed) and the starting law (dotted); "
                  "a viscoelastic law: its stress along the test's processed strain history.")

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
        ax.grid(False)  # the grid's lines crossed the cells' numbers
        ax.set_xticks(range(len(names)), names, rotation=45, ha="right", fontsize=8)
        ax.set_yticks(range(len(names)), names, fontsize=8)
        for i in range(len(names)):
            for j in range(len(names)):
                # White on the dark cells of strong correlations, where black could not be read.
                ax.text(j, i, f"{a[i, j]:.2f}", ha="center", va="center", fontsize=7,
                        color="w" if abs(a[i, j]) > 0.6 else "k")
        fig.colorbar(im, ax=ax)
        ax.set_title(src.title("Parameter correlations"))
        figs.save(fig, src.png("fit_correlation"), src.title("Fit: parameter correlations"),
                  "Correlations of the fitted parameters from the covariance of the last stage; "
                  "|r| > 0.98 means two parameters are not separately identifiable.")

    draw_intervals(src, figs)


def draw_intervals(src, figs):
    """Each parameter's 95 % intervals relative to its value: linearised, bootstrap and reported
    (docs/outputs.md, fit: summary.json parameters; docs/methods.md §9, "Intervals")."""
    params = src.value("parameters", kind=dict) or {}
    rows = []
    for name, p in params.items():
        if not isinstance(p, dict) or not isinstance(p.get("value"), (int, float)):
            continue
        value = float(p["value"])
        reported = number_pair(p.get("interval_95"))
        if reported is None or value == 0:
            continue
        boot = p.get("bootstrap") if isinstance(p.get("bootstrap"), dict) else {}
        rows.append((str(name), value, reported, number_pair(p.get("linearised_interval_95")),
                     number_pair(boot.get("interval_95")), str(p.get("interval_method", "")),
                     bool(p.get("weakly_identified"))))
    if not rows:
        return
    fig, axes = new_figure(height=0.55 * len(rows) + 2.2, width=7)
    ax = axes[0, 0]
    rel = lambda iv, v: (100 * (iv[0] / v - 1), 100 * (iv[1] / v - 1))  # noqa: E731
    for i, (name, value, reported, linear, boot, method, weak) in enumerate(rows):
        y = len(rows) - 1 - i
        lo, hi = rel(reported, value)
        ax.plot([lo, hi], [y, y], color="C3" if weak else "k", linewidth=4, alpha=0.35,
                solid_capstyle="butt", label="reported" if i == 0 else None)
        if linear:
            a, b = rel(linear, value)
            ax.plot([a, b], [y + 0.15, y + 0.15], color="C0", linewidth=1.5,
                    label="linearised" if i == 0 else None)
        if boot:
            a, b = rel(boot, value)
            ax.plot([a, b], [y - 0.15, y - 0.15], color="C2", linewidth=1.5,
                    label="bootstrap" if i == 0 else None)
        ax.text(hi, y, f"  {method}{' (weak)' if weak else ''}", va="center", fontsize=7)
    ax.axvline(0, color="0.5", linewidth=0.8)
    ax.set_yticks(range(len(rows)), [r[0] for r in reversed(rows)], fontsize=8)
    ax.set_xlabel("95 % interval relative to the fitted value (%)")
    ax.set_title(src.title("Parameter intervals"))
    ax.legend(fontsize=7, loc="lower right")
    figs.save(fig, src.png("fit_intervals"), src.title("Fit: parameter intervals"),
              "Each parameter's 95 % interval relative to its value: linearised (blue), the "
              "parametric bootstrap's (green) and the one reported (grey; red when the parameter "
              "is weakly identified), with the method that gave it.")

"""Figures of `shpb process` (docs/outputs.md, process): raw signals with their pulse windows,
the pulses at the specimen faces, the stress–strain curves with strain rate and equilibrium, the
bars-together check, and a campaign's curves on one plot."""
import numpy as np

from .drawing import (MICRO, MPA, US, gauge_columns, new_figure, outside_legend, panel_rows,
                      ratio_finite)
from .reading import NUMBER, number, number_pair
from .schema import columns

BAR_CHECK = columns("bar_check_pulses")
CURVE = columns("curve")
PULSES = columns("pulses")
RAW_SIGNALS = columns("raw_signals")
SPECIMEN = columns("specimen")


def fig_pulses(src, figs):
    t = src.table(PULSES.FILE)
    time = t.numeric(PULSES.time_s) * US
    fig, axes = new_figure()
    ax = axes[0, 0]
    for name, color in ((PULSES.incident, "C0"), (PULSES.reflected, "C3"),
                        (PULSES.transmitted, "C2")):
        if name in t:
            ax.plot(time, t.numeric(name) * MICRO, color=color, linewidth=1.0, label=name)
    if all(n in t for n in (PULSES.incident, PULSES.reflected, PULSES.transmitted)):
        front = t.numeric(PULSES.incident) + t.numeric(PULSES.reflected)
        ax.plot(time, front * MICRO, color="k", linewidth=0.8, linestyle="--",
                label="incident + reflected (front face)")
    ax.set_xlabel("time at the specimen faces (µs)")
    ax.set_ylabel("bar strain (µε, tension +)")
    ax.set_title(src.title("Pulses shifted to the specimen faces"), pad=24)
    outside_legend(ax)
    figs.save(fig, src.png("pulses"), src.title("Aligned pulses"),
              "Incident, reflected and transmitted pulses moved to the specimen faces "
              "(pulses.csv). In equilibrium incident + reflected follows the transmitted pulse.")


def loaded_sense(src):
    """What curve.csv counts positive: the test's own loading, compression unless summary.json
    says "test": "tension" (docs/outputs.md, curve.csv)."""
    return "tension" if src.value("test", kind=str) == "tension" else "compression"


def truth_in_sense(truth, sense):
    """specimen.csv's signed columns as the curve counts them: specimen.csv is compression
    positive whatever the test (docs/outputs.md, Conventions), a tension test's curve tension
    positive. Its time is read as it is."""
    sign = -1.0 if sense == "tension" else 1.0
    return lambda name: truth.numeric(name) * (1.0 if name == SPECIMEN.time_s else sign)


def fig_curve(src, figs, truth=None):
    t = src.table(CURVE.FILE)
    sense = loaded_sense(src)
    # The primary reduction (summary.json primary) is drawn first and heaviest.
    one_wave = src.value("primary", "reduction", kind=str) == "1-wave" and CURVE.strain_1wave in t
    primary = "1-wave" if one_wave else "3-wave"
    strain = t.numeric(CURVE.strain_1wave if one_wave else CURVE.strain)
    truth_of = truth_in_sense(truth, sense) if truth is not None else None
    # The ring-up (docs/methods.md §6): the rows before the face forces first agree within 5 %
    # (summary.json equilibrium.first_s) hold the front face's transient, a tensile stress in a
    # compression test among it, not the specimen's stress: the curves are drawn from there, the
    # primary's ring-up thin and dotted.
    first = src.value("equilibrium", "first_s", kind=NUMBER)
    ring = (t.numeric(CURVE.time_s) < first if first is not None and CURVE.time_s in t
            else np.zeros(len(strain), dtype=bool))

    def past(values):
        return np.where(ring, np.nan, values)

    fig, axes = new_figure(1, 2, height=4.6, width=11.0)
    ax = axes[0, 0]
    primary_stress = t.numeric(CURVE.stress_1wave_Pa if one_wave else CURVE.stress_3wave_Pa)
    if ring.any():
        upto = min(int(np.count_nonzero(ring)) + 1, len(strain))  # joined to the curve
        ax.plot(strain[:upto] * 100, primary_stress[:upto] * MPA, color="0.5", linewidth=0.8,
                linestyle=":", label="ring-up: the face forces not yet in equilibrium")
    if one_wave:
        ax.plot(strain * 100, past(primary_stress) * MPA, color="k", linewidth=1.6,
                label="1-wave (transmitted) against the reflected-pulse strain (primary)")
        if CURVE.strain in t and CURVE.stress_3wave_Pa in t:
            ax.plot(t.numeric(CURVE.strain) * 100, past(t.numeric(CURVE.stress_3wave_Pa)) * MPA,
                    color="0.5", linewidth=1.0, label="3-wave against the 3-wave strain")
    else:
        for col, label, color in ((CURVE.stress_1wave_Pa, "1-wave (transmitted)", "C2"),
                                  (CURVE.stress_2wave_Pa, "2-wave (incident + reflected)", "C1"),
                                  (CURVE.stress_3wave_Pa, "3-wave (average)", "k")):
            if col in t:
                ax.plot(strain * 100, past(t.numeric(col)) * MPA, color=color,
                        linewidth=1.6 if color == "k" else 1.0, label=label)
    if truth_of is not None:
        ax.plot(truth_of(SPECIMEN.strain) * 100, truth_of(SPECIMEN.stress_Pa) * MPA,
                color="C4", linestyle=":", linewidth=1.4, label="model truth (specimen.csv)")
    # The bands are quantiles at the row's primary strain (docs/outputs.md, curve.csv): each is
    # drawn around the curve drawn against that strain. With a 1-wave primary the 3-wave band
    # belongs to no drawn curve (the 3-wave curve is against its own strain): left out.
    bands = [(f"stress_{n}wave", f"{n}-wave 95 % band", c) for n, c in (("3", "0.3"), ("1", "C2"))
             if f"stress_{n}wave_p2.5_Pa" in t and not (one_wave and n == "3")]
    for base, label, color in bands:
        ax.fill_between(strain * 100, t.numeric(base + "_p2.5_Pa") * MPA,
                        t.numeric(base + "_p97.5_Pa") * MPA, color=color, alpha=0.25,
                        linewidth=0, label=label)
    ax.set_xlabel(f"engineering strain (%, {sense} +)")
    ax.set_ylabel(f"engineering stress (MPa, {sense} +)")
    ax.set_title(src.title("Engineering stress–strain"))
    ax.legend(loc="best", fontsize=8)
    ax = axes[0, 1]
    if CURVE.true_strain in t and CURVE.true_stress_Pa in t:
        ax.plot(t.numeric(CURVE.true_strain) * 100, past(t.numeric(CURVE.true_stress_Pa)) * MPA,
                color="k", linewidth=1.4, label=f"true ({primary})")
    ax.plot(strain * 100, past(primary_stress) * MPA, color="0.6", linewidth=1.0, linestyle="--",
            label=f"engineering ({primary})")
    if truth_of is not None and SPECIMEN.true_strain in truth and SPECIMEN.true_stress_Pa in truth:
        # The law as the specimen followed it: true stress at true strain (specimen.csv).
        ax.plot(truth_of(SPECIMEN.true_strain) * 100, truth_of(SPECIMEN.true_stress_Pa) * MPA,
                color="C4", linestyle=":", linewidth=1.4, label="law, model truth (true)")
    ax.set_xlabel(f"true strain (%, {sense} +)")
    ax.set_ylabel(f"true stress (MPa, {sense} +)")
    ax.set_title(src.title("True stress–strain"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("stress_strain"), src.title("Stress–strain curves"),
              ("1-wave stress against the reflected-pulse strain (the primary reduction) and "
               "the 3-wave curve" if one_wave else
               "1-, 2- and 3-wave engineering stress against the 3-wave strain")
              + ", and true stress against true strain (curve.csv, docs/methods.md §6), "
              + ("from where the face forces first agree within 5 % (dotted before: the "
                 "ring-up, the front face's transient), " if ring.any() else "")
              + 
              f"{sense} positive"
              + ("; shaded: the 95 % bands of measurement.uncertainty (Monte Carlo, "
                 "docs/methods.md §10)" if bands else "")
              + ("; dotted: the simulation's own specimen truth." if truth is not None else "."))
    fig_rate(src, figs, t, one_wave, sense, truth_of)


def fig_rate(src, figs, t, one_wave, sense, truth_of):
    """The primary reduction's strain rate (its band around it) and the equilibrium ratio."""
    primary = "1-wave" if one_wave else "3-wave"
    time = t.numeric(CURVE.time_s) * US
    fig, axes = new_figure(2, 1, height=6.0, sharex=True)
    ax = axes[0, 0]
    primary_rate = (CURVE.strain_rate_1wave_1_s if one_wave and CURVE.strain_rate_1wave_1_s in t
                    else CURVE.strain_rate_1_s)
    if primary_rate != CURVE.strain_rate_1_s:
        ax.plot(time, t.numeric(CURVE.strain_rate_1_s), color="0.6", linewidth=1.0,
                linestyle="--", label="3-wave")
    ax.plot(time, t.numeric(primary_rate), color="k", linewidth=1.0,
            label=f"{primary} (primary)" if one_wave else "3-wave")
    if CURVE.strain_rate_p2_5_1_s in t and CURVE.strain_rate_p97_5_1_s in t:
        # The primary reduction's rate band (docs/outputs.md, curve.csv), around its own rate.
        ax.fill_between(time, t.numeric(CURVE.strain_rate_p2_5_1_s),
                        t.numeric(CURVE.strain_rate_p97_5_1_s), color="0.3", alpha=0.25,
                        linewidth=0, label=f"95 % band ({primary})")
    if truth_of is not None:
        ax.plot(truth_of(SPECIMEN.time_s) * US,
                truth_of(SPECIMEN.strain_rate_1_s), color="C4", linestyle=":", linewidth=1.2,
                label="model truth")
    if len(ax.get_lines()) + len(ax.collections) > 1:
        ax.legend(loc="best", fontsize=8)
    ax.set_ylabel(f"strain rate (1/s, {sense} +)")
    ax.set_title(src.title("Strain rate and equilibrium against time"))
    if CURVE.equilibrium_ratio in t:
        axes[1, 0].plot(time, ratio_finite(t.numeric(CURVE.equilibrium_ratio)), color="C0",
                        linewidth=1.0, label="2|P1 − P2| / |P1 + P2|")
        axes[1, 0].axhline(0.05, color="C3", linestyle=":", linewidth=1.0, label="5 %")
        axes[1, 0].set_ylim(0, 1)
        axes[1, 0].legend(loc="upper right", fontsize=8)
    axes[1, 0].set_ylabel("equilibrium ratio")
    axes[1, 0].set_xlabel("time at the specimen faces (µs)")
    figs.save(fig, src.png("rate_equilibrium"),
              src.title("Strain rate and equilibrium"),
              f"{primary} strain rate"
              + (" (dashed: the 3-wave rate)" if primary_rate != CURVE.strain_rate_1_s else "")
              + " and the equilibrium ratio R(t) = 2|P1 − P2|/|P1 + P2| of the "
              "front and back face forces (curve.csv); below the dotted 5 % line the specimen "
              "is taken as in equilibrium.")


HEADLINE_FIGURES = ("flow_stress_Pa_at_strain_0.1", "peak_stress_Pa", "plateau_strain_rate_1_s",
                    "mean_strain_rate_1_s")


# summary.json's quantity keys end in their unit, which a title gives after the interval.
UNIT_SUFFIXES = ("_Pa", "_1_s", "_m_s", "_m", "_s", "_J", "_N", "_K")


def quantity_name(key):
    """A summary.json quantity key as words: its unit suffix dropped, underscores as spaces
    ("peak_stress_Pa": "peak stress", "flow_stress_Pa_at_strain_0.05": "flow stress at strain
    0.05")."""
    words = key
    for unit in UNIT_SUFFIXES:
        if words.endswith(unit) and len(words) > len(unit):
            words = words[:-len(unit)]
            break
    words = words.replace("_Pa_at_", "_at_")
    return words.replace("_", " ")


def draw_contributions(src, figs, where, name, caption):
    """Each drawn input's share of the variance of the headline figures held under the
    summary.json keys `where` (records by figure name, each with interval_95, unit and
    contributions [{input or value, share}], largest first), as bars: the first three."""
    figures = src.value(*where, kind=dict) or {}
    names = [n for n in HEADLINE_FIGURES if isinstance(figures.get(n), dict)][:3]
    if not names:
        return
    fig, axes = new_figure(1, len(names), height=4.2, width=4.2 * len(names) + 1.5)
    for ax, figure in zip(axes[0], names):
        entry = (*where, figure)
        shares = [c for c in src.value(*entry, "contributions", kind=list) or []
                  if isinstance(c, dict)][:8]
        # process names the input "input", study --sweep monte-carlo "value".
        labels = [str(c.get("input", c.get("value"))) for c in shares][::-1]
        values = [100 * (number(c.get("share")) or 0.0) for c in shares][::-1]
        ax.barh(range(len(values)), values, color="C0")
        ax.set_yticks(range(len(values)), labels, fontsize=7)
        ax.set_xlabel("share of the variance (%)")
        interval = number_pair(src.value(*entry, "interval_95"))
        scale, unit = ((MPA, "MPa") if figure.endswith("Pa") or "_Pa_" in figure
                       else (1.0, src.value(*entry, "unit", kind=str) or ""))
        title = quantity_name(figure)
        if interval is not None:
            title += f"\n95 %: {interval[0] * scale:.4g} to {interval[1] * scale:.4g} {unit}"
        ax.set_title(title, fontsize=9)
    figs.save(fig, src.png(name), src.title("Uncertainty contributions"), caption)


def fig_uncertainty(src, figs):
    """Each input's share of the variance of the headline figures (summary.json uncertainty)."""
    draw_contributions(src, figs, ("uncertainty", "figures"), "uncertainty",
                       "Each uncertain input's share of the variance of the headline figures "
                       "(squared correlation over the Monte Carlo draws, summary.json "
                       "uncertainty, docs/methods.md §10), the largest eight; the title gives "
                       "the 95 % interval.")


def primary_columns(src, table):
    """The strain and stress columns of a test's primary reduction (summary.json primary),
    the 3-wave ones if it names none curve.csv holds."""
    strain = src.value("primary", "strain", kind=str)
    stress = src.value("primary", "stress", kind=str)
    if strain in table and stress in table:
        return strain, stress
    return CURVE.strain, CURVE.stress_3wave_Pa


def fig_campaign(folder, sources, figs):
    """All tests of a campaign (`shpb process` over several scenes) on one stress–strain plot,
    each test's primary reduction, positive in its own loading."""
    tests = [s for s in sources if s.label != "." and s.has(CURVE.FILE)]
    if not tests:
        return
    fig, axes = new_figure(1, 1, height=5.0)
    ax = axes[0, 0]
    reductions = set()
    for i, src in enumerate(tests):
        t = src.table(CURVE.FILE)
        strain, stress = primary_columns(src, t)
        reduction = "1-wave" if stress == CURVE.stress_1wave_Pa else "3-wave"
        reductions.add(reduction)
        tension = loaded_sense(src) == "tension"
        ax.plot(t.numeric(strain) * 100, t.numeric(stress) * MPA, color=f"C{i % 10}",
                linewidth=1.2, label=src.label + (" (tension)" if tension else "")
                + (f" ({reduction})" if reduction != "3-wave" else ""))
    senses = {loaded_sense(src) for src in tests}
    sense = senses.pop() if len(senses) == 1 else "each test's loading"
    what = "3-wave" if reductions == {"3-wave"} else "primary"
    ax.set_xlabel(f"engineering strain (%, {sense} +)")
    ax.set_ylabel(f"{what} engineering stress (MPa, {sense} +)")
    ax.set_title(f"Campaign: {len(tests)} tests")
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, "campaign_stress_strain.png", "Campaign: stress–strain curves of all tests",
              "Engineering stress against strain of every test's primary reduction (each test's "
              "curve.csv and summary.json primary), positive in the test's own loading; "
              "campaign.csv gives their plateau strain rates, peak and flow stresses.")


def fig_raw_signals(src, figs):
    t = src.table(RAW_SIGNALS.FILE)
    time = t.numeric(RAW_SIGNALS.time_s) * US
    gauges = gauge_columns(t)
    if not gauges:  # a time column alone: no signal to draw
        return
    rows = panel_rows(len(gauges), t.path, "gauge columns")
    fig, axes = new_figure(rows, 1, height=2.6 * rows + 0.8, sharex=True)
    colors = {"incident": "C0", "reflected": "C3", "transmitted": "C2"}
    for ax, g in zip(axes[:, 0], gauges):
        ax.plot(time, t.numeric(g) * MICRO, color="k", linewidth=0.9, label=f"{g} (as read)")
        for pulse, color in colors.items():
            start = src.value("windows", pulse, "start_s", kind=NUMBER)
            end = src.value("windows", pulse, "end_s", kind=NUMBER)
            if src.value("windows", pulse, "gauge") == g and start is not None and end is not None:
                source = src.value("windows", pulse, "source", kind=str) or ""
                ax.axvspan(start * US, end * US, color=color, alpha=0.15,
                           label=f"{pulse} window ({source})")
        ax.set_ylabel(f"{g}\nstrain (µε, tension +)")
        outside_legend(ax)
    axes[-1, 0].set_xlabel("time on the signals' clock (µs)")
    figs.save(fig, src.png("raw_signals"), src.title("Raw signals and the pulse windows"),
              "The gauge signals as read and converted to strain (raw_signals.csv), with the "
              "incident, reflected and transmitted windows found on them (summary.json windows; "
              "source: detected or set in the scene).")


def fig_bar_check(src, figs):
    t = src.table(BAR_CHECK.FILE)
    time = t.numeric(BAR_CHECK.time_s) * US
    fig, axes = new_figure()
    ax = axes[0, 0]
    ax.plot(time, t.numeric(BAR_CHECK.far_measured) * MICRO, color="k", linewidth=1.4,
            label="measured")
    ax.plot(time, t.numeric(BAR_CHECK.far_pochhammer_chree) * MICRO, color="C3", linewidth=1.0,
            linestyle="--", label="near pulse + Pochhammer–Chree")
    ax.plot(time, t.numeric(BAR_CHECK.far_time_shift) * MICRO, color="C0", linewidth=0.9,
            label="near pulse, time shift only")
    ax.set_xlabel("time on the signals' clock (µs)")
    ax.set_ylabel("far gauge strain (µε, tension +)")
    outside_legend(ax)
    near, far = src.value("near_gauge", kind=str), src.value("far_gauge", kind=str)
    distance = src.value("distance_m", kind=NUMBER)
    title = "Bars together: the near gauge's pulse moved to the far gauge"
    if near and far:
        title = f"Bars together: {near} moved to {far}" + (
            f" over {distance:.4g} m" if distance is not None else "")
    rms = [f"{100 * v:.3g} % with {how}" for v, how in (
        (src.value("rms_of_peak", "pochhammer_chree", kind=NUMBER), "Pochhammer–Chree"),
        (src.value("rms_of_peak", "time_shift", kind=NUMBER), "a time shift")) if v is not None]
    if rms:
        title += "\nRMS of peak: " + ", ".join(rms)
    fig.suptitle(src.title(title))  # above the legend
    figs.save(fig, src.png("bars_together"), src.title("Bars together: the far gauge"),
              "The near gauge's pulse moved to the far gauge with Pochhammer–Chree dispersion "
              "and by a plain time shift, over the measured far pulse (pulses.csv; RMS in "
              "summary.json).")

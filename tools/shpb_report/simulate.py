"""Figures of `shpb simulate` (docs/outputs.md, simulate): gauge signals, interface forces, the
x–t wave diagram, the energy history and the specimen's own truth."""
import numpy as np

from .drawing import MICRO, MPA, US, gauge_columns, new_figure, outside_legend
from .reading import ReportError
from .schema import columns, suffix

ENERGY = columns("energy")
FIELD = columns("field")
GAUGES = columns("gauges")
INTERFACES = columns("interfaces")
SPECIMEN = columns("specimen")
FORCE = suffix("interfaces", "<left>-<right>_force_N")
FIELD_CELLS = 10**7  # a wave diagram's cells always drawn: 80 MB of doubles
NOTHING_MOVES = ("nothing moves in this simulation: every gauge strain, contact force and energy "
                 "it recorded is zero (no bar has a velocity), so its gauge, wave-diagram, "
                 "specimen, interface and energy figures would be empty and are not drawn")


def nothing_moves(src):
    """A simulation folder whose records are all zero (a scene whose bars all rest): its
    figures would be six empty axes. Judged on gauges.csv, interfaces.csv and energy.csv, every
    column but time_s; field.csv and specimen.csv follow from them."""
    if not src.has(GAUGES.FILE):
        return False
    read = 0  # values judged: a file of times alone shows nothing either way
    for name, time in ((GAUGES.FILE, GAUGES.time_s), (INTERFACES.FILE, INTERFACES.time_s),
                       (ENERGY.FILE, ENERGY.time_s)):
        if src.has(name):
            t = src.table(name)
            t.numeric(time)  # a file the figures would refuse is refused as they would
            for column in t.names[1:]:
                values = t.numeric(column)
                if np.any(values[np.isfinite(values)] != 0):
                    return False
                read += values.size
    return read > 0


def fig_gauges(src, figs):
    t = src.table(GAUGES.FILE)
    time = t.numeric(GAUGES.time_s) * US
    fig, axes = new_figure()
    ax = axes[0, 0]
    for name in gauge_columns(t):
        ax.plot(time, t.numeric(name) * MICRO, linewidth=1.0, label=name)
    ax.axhline(0, color="0.4", linewidth=0.6)
    ax.set_xlabel("time since impact (µs)")
    ax.set_ylabel("axial strain (µε, tension +)")
    ax.set_title(src.title("Simulated strain-gauge signals"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("signals"), src.title("Gauge signals"),
              "Simulated gauge strains as recorded (gauges.csv), tension positive: the incident "
              "gauge shows the incident pulse (compression, negative) and later the reflected "
              "pulse; the transmitter gauge the transmitted pulse.")


def fig_interfaces(src, figs):
    t = src.table(INTERFACES.FILE)
    time = t.numeric(INTERFACES.time_s) * US
    forces = [n for n in t.names if n.endswith(FORCE)]
    if not forces:
        return
    fig, axes = new_figure()
    ax = axes[0, 0]
    for name in forces:
        ax.plot(time, t.numeric(name) * 1e-3, linewidth=1.0, label=name[:-len(FORCE)])
    ax.set_xlabel("time since impact (µs)")
    ax.set_ylabel("contact force (kN, compression +)")
    ax.set_title(src.title("Interface forces"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("interfaces"), src.title("Interface forces"),
              "Contact force at every interface (interfaces.csv), compression positive.")


def read_field(src):
    """field.csv (long format time_s,x_m,stress_Pa) as (x_m, t_s, stress[t, x])."""
    t = src.table(FIELD.FILE)
    time, x, s = t.numeric(FIELD.time_s), t.numeric(FIELD.x_m), t.numeric(FIELD.stress_Pa)
    ts = np.unique(time)
    xs = np.unique(x)
    # A time × position grid (docs/outputs.md, simulate), parts of it absent where the causal
    # economy cut a bar. Scattered points would ask for times × positions cells (49 GB for 81000
    # rows, a bug's MemoryError): beyond 10^7 cells a quarter of them must hold a row.
    if ts.size * xs.size > max(4 * len(t), FIELD_CELLS):
        raise ReportError(f"{t.path}: {ts.size} times × {xs.size} positions for {len(t)} rows: "
                          "a time × position grid was expected")
    field = np.full((ts.size, xs.size), np.nan)
    field[np.searchsorted(ts, time), np.searchsorted(xs, x)] = s
    return xs, ts, field


def fig_wave_diagram(src, figs):
    xs, ts, field = read_field(src)
    if xs.size < 2 or ts.size < 2:
        return
    fig, axes = new_figure(height=6.0)
    ax = axes[0, 0]
    ax.grid(False)
    finite = np.isfinite(field)
    limit = np.max(np.abs(field[finite])) * MPA if finite.any() else 0.0
    limit = limit if limit > 0 else 1.0
    mesh = ax.pcolormesh(xs, ts * US, field * MPA, cmap="RdBu_r", vmin=-limit, vmax=limit,
                         shading="nearest", rasterized=True)
    cb = fig.colorbar(mesh, ax=ax)
    cb.set_label("axial stress (MPa, tension +)")
    ax.set_xlabel("position along the chain (m)")
    ax.set_ylabel("time since impact (µs)")
    ax.set_title(src.title("x–t wave diagram of the whole chain"))
    figs.save(fig, src.png("wave_diagram"), src.title("x–t wave diagram"),
              "Axial stress along the whole chain against time (field.csv): compression (blue) "
              "leaves the striker, travels down the incident bar, partly reflects at the specimen "
              "as tension (red) and partly enters the transmitter bar. Slopes are wave speeds.")


def fig_energy(src, figs):
    t = src.table(ENERGY.FILE)
    time = t.numeric(ENERGY.time_s) * US
    fig, axes = new_figure(2, 1, height=6.0, sharex=True,
                           gridspec_kw={"height_ratios": [3, 1]})
    ax = axes[0, 0]
    labels = {ENERGY.kinetic_J: "kinetic", ENERGY.strain_J: "strain",
              ENERGY.contact_J: "contact (penalty)",
              ENERGY.dissipated_J: "dissipated (plastic, contact)", ENERGY.total_J: "total"}
    for name in t.names[1:]:
        style = {"color": "k", "linewidth": 1.6} if name == ENERGY.total_J else {"linewidth": 1.0}
        ax.plot(time, t.numeric(name), label=labels.get(name, name), **style)
    ax.set_ylabel("energy (J)")
    # Above the axes: inside, it sat over the total, which is flat near the top of the panel.
    outside_legend(ax)
    if ENERGY.total_J in t and len(t):
        total = t.numeric(ENERGY.total_J)
        e0 = total[0] if total[0] != 0 else (np.max(np.abs(total)) or 1.0)
        axes[1, 0].plot(time, (total - total[0]) / abs(e0) * 100, color="k", linewidth=1.0)
        axes[1, 0].set_ylabel("(total − initial)\n/ initial (%)")
    axes[1, 0].set_xlabel("time since impact (µs)")
    figs.save(fig, src.png("energy"), src.title("Energy history"),
              "Kinetic, strain, contact and dissipated energy of the whole chain (energy.csv); "
              "the lower panel is the balance error of the total.")


def fig_specimen(src, figs):
    """The model's own specimen truth: stress-strain and strain rate/equilibrium."""
    t = src.table(SPECIMEN.FILE)
    time = t.numeric(SPECIMEN.time_s) * US
    strain = t.numeric(SPECIMEN.strain)
    stress = t.numeric(SPECIMEN.stress_Pa)
    fig, axes = new_figure()
    ax = axes[0, 0]
    ax.plot(strain * 100, stress * MPA, color="k", linewidth=1.4, label="engineering (model)")
    if SPECIMEN.true_strain in t and SPECIMEN.true_stress_Pa in t:
        ax.plot(t.numeric(SPECIMEN.true_strain) * 100, t.numeric(SPECIMEN.true_stress_Pa) * MPA,
                color="C3", linewidth=1.0, linestyle="--",
                label="true (model: force over current area)")
    else:
        ok = strain < 1
        ax.plot(-np.log(1 - strain[ok]) * 100, stress[ok] * (1 - strain[ok]) * MPA, color="C3",
                linewidth=1.0, linestyle="--", label="true (constant volume)")
    ax.set_xlabel("specimen strain (%, compression +)")
    ax.set_ylabel("specimen stress (MPa, compression +)")
    ax.set_title(src.title("Specimen stress–strain: the model's own truth"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("specimen_stress_strain"),
              src.title("Specimen stress–strain (model truth)"),
              "Length-averaged engineering stress against strain of the specimen as the "
              "simulation computed it (specimen.csv), and true stress against logarithmic strain "
              "(docs/methods.md §6, §8). Compression positive.")

    fig, axes = new_figure(2, 1, height=6.0, sharex=True)
    axes[0, 0].plot(time, t.numeric(SPECIMEN.strain_rate_1_s), color="k", linewidth=1.0)
    axes[0, 0].set_ylabel("strain rate (1/s, compression +)")
    axes[0, 0].set_title(src.title("Specimen strain rate and equilibrium (model truth)"))
    if SPECIMEN.front_stress_Pa in t and SPECIMEN.back_stress_Pa in t:
        f, b = t.numeric(SPECIMEN.front_stress_Pa), t.numeric(SPECIMEN.back_stress_Pa)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = 2 * np.abs(f - b) / np.abs(f + b)
        peak = np.max(np.abs(f + b)) if len(f) else 0
        r[np.abs(f + b) < 0.02 * peak] = np.nan  # ratio meaningless before the pulse arrives
        # R over the loading alone, as process judges it and plan's panel draws it: the loading
        # ends at the specimen's largest strain (docs/methods.md §6; specimen.csv is compression
        # positive whatever the test, so a tension test's is its most negative). After it both
        # face stresses ring about zero and their ratio spiked to the top of the panel.
        if len(strain):
            r[int(np.argmax(np.abs(strain))) + 1:] = np.nan
        axes[1, 0].plot(time, r, color="C0", linewidth=1.0)
        axes[1, 0].axhline(0.05, color="C3", linestyle=":", linewidth=1.0, label="5 %")
        axes[1, 0].set_ylim(0, 1)
        axes[1, 0].legend(loc="upper right", fontsize=8)
    axes[1, 0].set_ylabel("equilibrium ratio\n2|σf − σb| / |σf + σb|")
    axes[1, 0].set_xlabel("time since impact (µs)")
    figs.save(fig, src.png("specimen_rate_equilibrium"),
              src.title("Specimen strain rate and equilibrium (model truth)"),
              "Strain rate of the specimen and the equilibrium ratio of its front and back "
              "face stresses (specimen.csv), shown over the loading (to the specimen's largest "
              "strain) where the stresses exceed 2 % of their peak.")

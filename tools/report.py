#!/usr/bin/python3
"""Figures and a one-page HTML report from any shpb output folder (docs/outputs.md).

usage: report.py DIR

DIR is an output folder of `shpb simulate`, `process`, `compare` or `study`, or a folder whose
immediate sub-folders are such outputs (e.g. `make run` writes simulate/ and process/ side by
side). Writes DIR/figures/*.png and DIR/report.html; report.html embeds every figure (base64, so
the page is self-contained) and links the PNG beside it. Nothing else in DIR is touched.

Conventions: signals are axial strain, tension positive (as recorded); stress-strain curves,
strain rate and specimen stresses are compression positive (as `process` and `specimen.csv`
write them); the wave diagram shows axial stress, tension positive. Times in µs, strains in µε
for bar signals and in % for the specimen, stresses in MPa.

Exit codes: 0 report written; 2 DIR holds no output file this script knows (or a file is
malformed: message "error: <file>: <line/column>: <value>: <what was expected>"), or DIR holds a
figures/ folder or a report.html this script did not write (they are never replaced); 3 the report
cannot be written (read-only folder, full disk).

Ownership: figures/ is this script's only if it holds the marker file .shpb-report, report.html
only if it carries the generator line below; the output folder's own marker (.shpb-output, see
core/output_folder.hpp) is told about both so that shpb may later replace the folder whole.
"""
import base64
import csv
import datetime
import html
import json
import math
import os
import re
import shutil
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

DPI = 100
US = 1e6  # s -> µs
MICRO = 1e6  # strain -> µε
MPA = 1e-6  # Pa -> MPa

# Files this script understands, by producer (docs/outputs.md and the compare/study outputs).
KNOWN_FILES = ("gauges.csv", "interfaces.csv", "specimen.csv", "energy.csv", "field.csv",
               "pulses.csv", "curve.csv", "signals.csv", "comparison.csv", "pareto.csv",
               "stability.csv", "summary.json", "raw_signals.csv", "stability_boundary.csv")


class ReportError(Exception):
    """Bad input: printed as one `error:` line, exit code 2."""


FIGURES_MARKER = ".shpb-report"
FIGURES_SIGNATURE = "figures written by shpb report; replaced only by shpb report\n"
GENERATOR = "<meta name='generator' content='shpb report'>"
OUTPUT_MARKER = ".shpb-output"
OUTPUT_SIGNATURE = "shpb output folder: written by shpb, replaced only by shpb"


def read_text(path, limit=1 << 16):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read(limit)
    except OSError:
        return ""


def check_ownership(folder):
    """Refuses to replace a figures/ or report.html that this script did not write."""
    fig_dir = os.path.join(folder, "figures")
    if os.path.lexists(fig_dir) and (
            os.path.islink(fig_dir) or not os.path.isdir(fig_dir)
            or read_text(os.path.join(fig_dir, FIGURES_MARKER)) != FIGURES_SIGNATURE):
        raise ReportError(f"{fig_dir}: exists and was not written by shpb report: refusing to "
                          "replace it (move it away, then run the report again)")
    page = os.path.join(folder, "report.html")
    if os.path.lexists(page) and (os.path.islink(page) or GENERATOR not in read_text(page)):
        raise ReportError(f"{page}: exists and was not written by shpb report: refusing to "
                          "replace it (move it away, then run the report again)")


def sync(path):
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def tell_output_marker(folder, names):
    """Lists `names` in the folder's .shpb-output marker (if it is shpb's), atomically."""
    marker = os.path.join(folder, OUTPUT_MARKER)
    text = read_text(marker)
    if not text.startswith(OUTPUT_SIGNATURE + "\n"):
        return
    lines = text.splitlines()
    added = [f"file: {n}" for n in names if f"file: {n}" not in lines]
    if not added:
        return
    tmp = marker + f".tmp-{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(lines + added) + "\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, marker)


# ---- reading ---------------------------------------------------------------------------------

class Table:
    """A numeric CSV with one header row: columns by name as numpy arrays."""

    def __init__(self, path):
        self.path = path
        self.columns = {}
        self.names = []
        try:
            with open(path, newline="", encoding="utf-8", errors="replace") as f:
                rows = list(csv.reader(f))
        except csv.Error as e:  # an unclosed quote, a NUL byte: not a CSV this script reads
            raise ReportError(f"{path}: {e}: comma-separated numbers were expected")
        if not rows:
            raise ReportError(f"{path}: line 1: empty file: a header row was expected")
        self.names = [n.strip() for n in rows[0]]
        data = []
        for i, row in enumerate(rows[1:], start=2):
            if not row:
                continue
            if len(row) != len(self.names):
                raise ReportError(f"{path}: line {i}: {len(row)} fields: "
                                  f"{len(self.names)} expected (as in the header)")
            values = []
            for j, text in enumerate(row):
                try:
                    values.append(float(text) if text.strip() else math.nan)
                except ValueError:
                    values.append(text.strip())
            data.append(values)
        self.rows = data
        for j, name in enumerate(self.names):
            col = [r[j] for r in data]
            if all(isinstance(v, float) for v in col):
                self.columns[name] = np.array(col, dtype=float)
            else:
                self.columns[name] = np.array([str(v) for v in col], dtype=object)

    def __contains__(self, name):
        return name in self.columns

    def __getitem__(self, name):
        return self.columns[name]

    def __len__(self):
        return len(self.rows)

    def numeric(self, name):
        if name not in self.columns:
            raise ReportError(f"{self.path}: header: {','.join(self.names)}: a column "
                              f"{name} was expected")
        col = self.columns[name]
        if col.dtype == object:
            raise ReportError(f"{self.path}: column {name}: text: numbers were expected")
        return col


class Source:
    """One output folder: the known files it holds."""

    def __init__(self, folder, label):
        self.folder = folder
        self.label = label
        self.files = {n: os.path.join(folder, n) for n in KNOWN_FILES
                      if os.path.isfile(os.path.join(folder, n))}
        self._tables = {}
        self.summary = {}
        if "summary.json" in self.files:
            try:
                with open(self.files["summary.json"], encoding="utf-8") as f:
                    self.summary = json.load(f)
            except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as e:
                raise ReportError(f"{self.files['summary.json']}: {e}: valid JSON was expected")

    def has(self, name):
        return name in self.files

    def table(self, name):
        if name not in self._tables:
            self._tables[name] = Table(self.files[name])
        return self._tables[name]

    def png(self, base):
        """Figure file name: `base.png` for DIR itself, `base_<sub-folder>.png` otherwise."""
        return f"{base}.png" if self.label == "." else f"{base}_{slug(self.label)}.png"

    def title(self, text):
        return text if self.label == "." else f"{text} — {self.label}"


def find_sources(folder):
    """The folder itself and its immediate sub-folders, those holding a known output file."""
    candidates = [Source(folder, ".")]
    for name in sorted(os.listdir(folder)):
        sub = os.path.join(folder, name)
        if os.path.isdir(sub) and name != "figures" and not name.startswith("."):
            candidates.append(Source(sub, name))
    return [s for s in candidates if any(n != "summary.json" for n in s.files)]


# ---- figure helpers --------------------------------------------------------------------------

class Figures:
    """Collects figures: saves each PNG in figures/ and remembers its caption."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self.items = []  # (file name, title, caption)

    def save(self, fig, name, title, caption):
        path = os.path.join(self.out_dir, name)
        fig.savefig(path, dpi=DPI)
        plt.close(fig)
        self.items.append((name, title, caption))


def grid(ax):
    ax.grid(True, color="0.88", linewidth=0.6)
    ax.set_axisbelow(True)


def new_figure(rows=1, cols=1, height=4.2, width=9.0, **kw):
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False,
                             constrained_layout=True, **kw)
    for ax in axes.flat:
        grid(ax)
    return fig, axes


def outside_legend(ax):
    """A legend above the axes, in one row: it never hides a trace."""
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=min(len(handles), 4),
                  fontsize=8, frameon=False)


def gauge_columns(table):
    return [n for n in table.names if n != "time_s"]


def ratio_finite(values):
    return np.where(np.isfinite(values), values, np.nan)


# ---- figures of `simulate` -------------------------------------------------------------------

def fig_gauges(src, figs):
    t = src.table("gauges.csv")
    time = t.numeric("time_s") * US
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
    t = src.table("interfaces.csv")
    time = t.numeric("time_s") * US
    forces = [n for n in t.names if n.endswith("_force_N")]
    if not forces:
        return
    fig, axes = new_figure()
    ax = axes[0, 0]
    for name in forces:
        ax.plot(time, t.numeric(name) * 1e-3, linewidth=1.0, label=name[:-len("_force_N")])
    ax.set_xlabel("time since impact (µs)")
    ax.set_ylabel("contact force (kN, compression +)")
    ax.set_title(src.title("Interface forces"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("interfaces"), src.title("Interface forces"),
              "Contact force at every interface (interfaces.csv), compression positive.")


def read_field(src):
    """field.csv as (x_m, t_s, stress[t, x]). Accepts the long form (time_s, x_m, stress_Pa) or
    the wide form (time_s, then one column per position whose name holds the position in m)."""
    t = src.table("field.csv")
    names = t.names
    lower = [n.lower() for n in names]
    xcol = next((n for n, l in zip(names, lower) if l in ("x_m", "position_m")), None)
    scol = next((n for n, l in zip(names, lower) if l.startswith("stress")), None)
    if "time_s" in names and xcol and scol:
        time = t.numeric("time_s")
        x = t.numeric(xcol)
        s = t.numeric(scol)
        ts = np.unique(time)
        xs = np.unique(x)
        field = np.full((ts.size, xs.size), np.nan)
        field[np.searchsorted(ts, time), np.searchsorted(xs, x)] = s
        return xs, ts, field
    if names and names[0] == "time_s":
        xs = []
        for n in names[1:]:
            m = re.search(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", n)
            if not m:
                raise ReportError(f"{t.path}: header: {n}: a column name holding the position "
                                  "in m was expected")
            xs.append(float(m.group(0)))
        data = np.column_stack([t.numeric(n) for n in names[1:]])
        xs = np.array(xs)
        order = np.argsort(xs, kind="stable")
        return xs[order], t.numeric("time_s"), data[:, order]
    raise ReportError(f"{t.path}: header: {','.join(names)}: time_s,x_m,stress_Pa or time_s "
                      "followed by one column per position was expected")


def fig_wave_diagram(src, figs):
    xs, ts, field = read_field(src)
    if xs.size < 2 or ts.size < 2:
        return
    fig, axes = new_figure(height=6.0)
    ax = axes[0, 0]
    ax.grid(False)
    limit = np.nanmax(np.abs(field)) * MPA
    limit = limit if limit > 0 else 1.0
    mesh = ax.pcolormesh(xs, ts * US, field * MPA, cmap="RdBu_r", vmin=-limit, vmax=limit,
                         shading="nearest", rasterized=True)
    bars = src.summary.get("bars") if isinstance(src.summary, dict) else None
    if isinstance(bars, list):
        edges = [b.get("x_left_m") for b in bars if isinstance(b, dict)]
        for e in edges:
            if isinstance(e, (int, float)):
                ax.axvline(e, color="0.2", linewidth=0.6)
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
    t = src.table("energy.csv")
    time = t.numeric("time_s") * US
    fig, axes = new_figure(2, 1, height=6.0, sharex=True,
                           gridspec_kw={"height_ratios": [3, 1]})
    ax = axes[0, 0]
    labels = {"kinetic_J": "kinetic", "strain_J": "strain", "contact_J": "contact (penalty)",
              "dissipated_J": "dissipated (plastic, contact)", "total_J": "total"}
    for name in t.names[1:]:
        style = {"color": "k", "linewidth": 1.6} if name == "total_J" else {"linewidth": 1.0}
        ax.plot(time, t.numeric(name), label=labels.get(name, name), **style)
    ax.set_ylabel("energy (J)")
    ax.set_title(src.title("Energy history"))
    ax.legend(loc="best", fontsize=8)
    if "total_J" in t and len(t):
        total = t.numeric("total_J")
        e0 = total[0] if total[0] != 0 else (np.max(np.abs(total)) or 1.0)
        axes[1, 0].plot(time, (total - total[0]) / abs(e0) * 100, color="k", linewidth=1.0)
        axes[1, 0].set_ylabel("(total − initial)\n/ initial (%)")
    axes[1, 0].set_xlabel("time since impact (µs)")
    figs.save(fig, src.png("energy"), src.title("Energy history"),
              "Kinetic, strain, contact and dissipated energy of the whole chain (energy.csv); "
              "the lower panel is the balance error of the total.")


def fig_specimen(src, figs):
    """The model's own specimen truth: stress-strain and strain rate/equilibrium."""
    t = src.table("specimen.csv")
    time = t.numeric("time_s") * US
    strain = t.numeric("strain")
    stress = t.numeric("stress_Pa")
    fig, axes = new_figure()
    ax = axes[0, 0]
    ax.plot(strain * 100, stress * MPA, color="k", linewidth=1.4, label="engineering (model)")
    if "true_strain" in t and "true_stress_Pa" in t:
        ax.plot(t.numeric("true_strain") * 100, t.numeric("true_stress_Pa") * MPA, color="C3",
                linewidth=1.0, linestyle="--", label="true (model: force over current area)")
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
    axes[0, 0].plot(time, t.numeric("strain_rate_1_s"), color="k", linewidth=1.0)
    axes[0, 0].set_ylabel("strain rate (1/s, compression +)")
    axes[0, 0].set_title(src.title("Specimen strain rate and equilibrium (model truth)"))
    if "front_stress_Pa" in t and "back_stress_Pa" in t:
        f, b = t.numeric("front_stress_Pa"), t.numeric("back_stress_Pa")
        with np.errstate(divide="ignore", invalid="ignore"):
            r = 2 * np.abs(f - b) / np.abs(f + b)
        peak = np.max(np.abs(f + b)) if len(f) else 0
        r[np.abs(f + b) < 0.02 * peak] = np.nan  # ratio meaningless before the pulse arrives
        axes[1, 0].plot(time, r, color="C0", linewidth=1.0)
        axes[1, 0].axhline(0.05, color="C3", linestyle=":", linewidth=1.0, label="5 %")
        axes[1, 0].set_ylim(0, 1)
        axes[1, 0].legend(loc="upper right", fontsize=8)
    axes[1, 0].set_ylabel("equilibrium ratio\n2|σf − σb| / |σf + σb|")
    axes[1, 0].set_xlabel("time since impact (µs)")
    figs.save(fig, src.png("specimen_rate_equilibrium"),
              src.title("Specimen strain rate and equilibrium (model truth)"),
              "Strain rate of the specimen and the equilibrium ratio of its front and back "
              "face stresses (specimen.csv), shown where the stresses exceed 2 % of their peak.")


# ---- figures of `process` --------------------------------------------------------------------

def fig_pulses(src, figs):
    t = src.table("pulses.csv")
    time = t.numeric("time_s") * US
    fig, axes = new_figure()
    ax = axes[0, 0]
    for name, color in (("incident", "C0"), ("reflected", "C3"), ("transmitted", "C2")):
        if name in t:
            ax.plot(time, t.numeric(name) * MICRO, color=color, linewidth=1.0, label=name)
    if all(n in t for n in ("incident", "reflected", "transmitted")):
        ax.plot(time, (t.numeric("incident") + t.numeric("reflected")) * MICRO, color="k",
                linewidth=0.8, linestyle="--", label="incident + reflected (front face)")
    ax.set_xlabel("time at the specimen faces (µs)")
    ax.set_ylabel("bar strain (µε, tension +)")
    ax.set_title(src.title("Pulses shifted to the specimen faces"), pad=24)
    outside_legend(ax)
    figs.save(fig, src.png("pulses"), src.title("Aligned pulses"),
              "Incident, reflected and transmitted pulses moved to the specimen faces "
              "(pulses.csv). In equilibrium incident + reflected follows the transmitted pulse.")


def fig_curve(src, figs, truth=None):
    t = src.table("curve.csv")
    strain = t.numeric("strain")
    fig, axes = new_figure(1, 2, height=4.6, width=11.0)
    ax = axes[0, 0]
    for col, label, color in (("stress_1wave_Pa", "1-wave (transmitted)", "C2"),
                              ("stress_2wave_Pa", "2-wave (incident + reflected)", "C1"),
                              ("stress_3wave_Pa", "3-wave (average)", "k")):
        if col in t:
            ax.plot(strain * 100, t.numeric(col) * MPA, color=color,
                    linewidth=1.6 if color == "k" else 1.0, label=label)
    if truth is not None:
        ax.plot(truth.numeric("strain") * 100, truth.numeric("stress_Pa") * MPA, color="C4",
                linestyle=":", linewidth=1.4, label="model truth (specimen.csv)")
    ax.set_xlabel("engineering strain (%, compression +)")
    ax.set_ylabel("engineering stress (MPa, compression +)")
    ax.set_title(src.title("Engineering stress–strain"))
    ax.legend(loc="best", fontsize=8)
    ax = axes[0, 1]
    if "true_strain" in t and "true_stress_Pa" in t:
        ax.plot(t.numeric("true_strain") * 100, t.numeric("true_stress_Pa") * MPA, color="k",
                linewidth=1.4, label="true (3-wave)")
    ax.plot(strain * 100, t.numeric("stress_3wave_Pa") * MPA, color="0.6", linewidth=1.0,
            linestyle="--", label="engineering (3-wave)")
    if truth is not None and "true_strain" in truth and "true_stress_Pa" in truth:
        # The law as the specimen followed it: true stress at true strain (specimen.csv).
        ax.plot(truth.numeric("true_strain") * 100, truth.numeric("true_stress_Pa") * MPA,
                color="C4", linestyle=":", linewidth=1.4, label="law, model truth (true)")
    ax.set_xlabel("true strain (%, compression +)")
    ax.set_ylabel("true stress (MPa, compression +)")
    ax.set_title(src.title("True stress–strain"))
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, src.png("stress_strain"), src.title("Stress–strain curves"),
              "1-, 2- and 3-wave engineering stress against the 3-wave strain, and true stress "
              "against true strain (curve.csv, docs/methods.md §6), compression positive"
              + ("; dotted: the simulation's own specimen truth." if truth is not None else "."))

    time = t.numeric("time_s") * US
    fig, axes = new_figure(2, 1, height=6.0, sharex=True)
    axes[0, 0].plot(time, t.numeric("strain_rate_1_s"), color="k", linewidth=1.0,
                    label="3-wave")
    if truth is not None:
        axes[0, 0].plot(truth.numeric("time_s") * US, truth.numeric("strain_rate_1_s"),
                        color="C4", linestyle=":", linewidth=1.2, label="model truth")
        axes[0, 0].legend(loc="best", fontsize=8)
    axes[0, 0].set_ylabel("strain rate (1/s, compression +)")
    axes[0, 0].set_title(src.title("Strain rate and equilibrium against time"))
    if "equilibrium_ratio" in t:
        axes[1, 0].plot(time, ratio_finite(t.numeric("equilibrium_ratio")), color="C0",
                        linewidth=1.0, label="2|P1 − P2| / |P1 + P2|")
        axes[1, 0].axhline(0.05, color="C3", linestyle=":", linewidth=1.0, label="5 %")
        axes[1, 0].set_ylim(0, 1)
        axes[1, 0].legend(loc="upper right", fontsize=8)
    axes[1, 0].set_ylabel("equilibrium ratio")
    axes[1, 0].set_xlabel("time at the specimen faces (µs)")
    figs.save(fig, src.png("rate_equilibrium"),
              src.title("Strain rate and equilibrium"),
              "3-wave strain rate and the equilibrium ratio R(t) = 2|P1 − P2|/|P1 + P2| of the "
              "front and back face forces (curve.csv); below the dotted 5 % line the specimen "
              "is taken as in equilibrium.")


def fig_campaign(folder, sources, figs):
    """All tests of a campaign (`shpb process` over several scenes) on one stress–strain plot."""
    tests = [s for s in sources if s.label != "." and s.has("curve.csv")]
    if not tests:
        return
    fig, axes = new_figure(1, 1, height=5.0)
    ax = axes[0, 0]
    for i, src in enumerate(tests):
        t = src.table("curve.csv")
        ax.plot(t.numeric("strain") * 100, t.numeric("stress_3wave_Pa") * MPA,
                color=f"C{i % 10}", linewidth=1.2, label=src.label)
    ax.set_xlabel("engineering strain (%, compression +)")
    ax.set_ylabel("3-wave engineering stress (MPa, compression +)")
    ax.set_title(f"Campaign: {len(tests)} tests")
    ax.legend(loc="best", fontsize=8)
    figs.save(fig, "campaign_stress_strain.png", "Campaign: stress–strain curves of all tests",
              "3-wave engineering stress against strain of every test (each test's curve.csv); "
              "campaign.csv gives their plateau strain rates, peak and flow stresses.")


def fig_raw_signals(src, figs):
    t = src.table("raw_signals.csv")
    time = t.numeric("time_s") * US
    gauges = gauge_columns(t)
    windows = src.summary.get("windows", {}) if isinstance(src.summary, dict) else {}
    fig, axes = new_figure(len(gauges), 1, height=2.6 * len(gauges) + 0.8, sharex=True)
    colors = {"incident": "C0", "reflected": "C3", "transmitted": "C2"}
    for ax, g in zip(axes[:, 0], gauges):
        ax.plot(time, t.numeric(g) * MICRO, color="k", linewidth=0.9, label=f"{g} (as read)")
        for pulse, color in colors.items():
            w = windows.get(pulse)
            if isinstance(w, dict) and w.get("gauge") == g:
                ax.axvspan(w["start_s"] * US, w["end_s"] * US, color=color, alpha=0.15,
                           label=f"{pulse} window ({w.get('source', '')})")
        ax.set_ylabel(f"{g}\nstrain (µε, tension +)")
        outside_legend(ax)
    axes[-1, 0].set_xlabel("time on the signals' clock (µs)")
    figs.save(fig, src.png("raw_signals"), src.title("Raw signals and the pulse windows"),
              "The gauge signals as read and converted to strain (raw_signals.csv), with the "
              "incident, reflected and transmitted windows found on them (summary.json windows; "
              "source: detected or set in the scene).")


def fig_bar_check(src, figs):
    t = src.table("pulses.csv")
    time = t.numeric("time_s") * US
    fig, axes = new_figure()
    ax = axes[0, 0]
    ax.plot(time, t.numeric("far_measured") * MICRO, color="k", linewidth=1.4, label="measured")
    ax.plot(time, t.numeric("far_pochhammer_chree") * MICRO, color="C3", linewidth=1.0,
            linestyle="--", label="near pulse + Pochhammer–Chree")
    ax.plot(time, t.numeric("far_time_shift") * MICRO, color="C0", linewidth=0.9,
            label="near pulse, time shift only")
    ax.set_xlabel("time on the signals' clock (µs)")
    ax.set_ylabel("far gauge strain (µε, tension +)")
    outside_legend(ax)
    figs.save(fig, src.png("bars_together"), src.title("Bars together: the far gauge"),
              "The near gauge's pulse moved to the far gauge with Pochhammer–Chree dispersion "
              "and by a plain time shift, over the measured far pulse (pulses.csv; RMS in "
              "summary.json).")


# ---- figures of `compare` --------------------------------------------------------------------

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
            for row in zip(c["gauge"], c["pulse"], c["window_start_s"], c["window_end_s"]):
                windows.append(row)
    fig, axes = new_figure(len(gauges), 1, height=2.9 * len(gauges) + 0.6, sharex=True)
    for ax, g in zip(axes[:, 0], gauges):
        ax.plot(time, t.numeric(f"{g}_measured_strain") * MICRO, color="k", linewidth=1.2,
                label="measured")
        if f"{g}_simulated_raw_strain" in t:
            ax.plot(time, t.numeric(f"{g}_simulated_raw_strain") * MICRO, color="C0",
                    linewidth=0.8, alpha=0.6, label="simulated (1D, no dispersion)")
        if f"{g}_simulated_strain" in t:
            dispersed = src.summary.get("dispersion") if isinstance(src.summary, dict) else None
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
    axes[0, 0].set_title(src.title("Simulated over measured gauge signals"))
    axes[-1, 0].set_xlabel("time on the measurement's clock (µs)")
    figs.save(fig, src.png("signals"),
              src.title("Gauge signals: simulated over measured"),
              "Measured strain (black) and the simulation of the same scene (dashed), on the "
              "measurement's clock; shaded: the pulse windows compared in comparison.csv.")


# ---- figures of `study` ----------------------------------------------------------------------

def pareto_front(cost, error):
    """Indices of the points no other point beats in both cost and error (minimisation)."""
    order = np.lexsort((error, cost))
    front, best = [], math.inf
    for i in order:
        if error[i] < best:
            front.append(i)
            best = error[i]
    return front


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
            ax.scatter(cost[sel], error[sel], marker=markers[stepping], s=36,
                       facecolors=f"C{k}" if filled else "none", edgecolors=f"C{k}",
                       label=f"{method}, {stepping}".strip(", "))
            if "resolution" in t:
                for x, y, r in zip(cost[sel], error[sel], t["resolution"][sel]):
                    ax.annotate(f"{r:g}", (x, y), textcoords="offset points", xytext=(4, 3),
                                fontsize=6, color="0.35")
    idx = np.flatnonzero(ok)
    if idx.size:
        front = idx[pareto_front(cost[idx], error[idx])]
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
    reference = src.summary.get("reference") if isinstance(src.summary, dict) else None
    ax.set_ylabel("error against the reference" + (f"\n({reference})" if isinstance(
        reference, str) else ""))
    ax.set_title(src.title("Accuracy against cost"))
    ax.legend(loc="best", fontsize=7)
    figs.save(fig, src.png("pareto"), src.title("Accuracy against cost"),
              "Error against wall time for every run of the sweep (pareto.csv): filled markers "
              "asynchronous stepping, open markers global stepping, numbers the mesh resolution "
              "factor; the black staircase is the Pareto front (no run is both faster and more "
              "accurate).")


def fig_stability(src, figs):
    t = src.table("stability.csv")
    names = t.names
    xcol = next((n for n in names if "stiff" in n.lower()), None)
    ycol = next((n for n in names if "courant" in n.lower()), None)
    if xcol is None or ycol is None or "stable" not in t:
        raise ReportError(f"{t.path}: header: {','.join(names)}: columns for the penalty "
                          "stiffness, the Courant number and `stable` were expected")
    rcol = next((n for n in names if n.lower().startswith("mass_ratio") or n.lower() in
                 ("r_over_rcrit", "r_ratio")), None)
    keys = np.asarray(t["method"]) if "method" in t else None
    if keys is not None and "step_ratio" in t:
        # Localized bipenalty is mapped at several step ratios (asynchronous): one figure each.
        keys = np.array([m if not (np.isfinite(q) and q != 1) else f"{m} step ratio {q:.3g}"
                         for m, q in zip(keys, t.numeric("step_ratio"))])
    methods = list(dict.fromkeys(keys)) if keys is not None else [""]
    stable = t.numeric("stable") > 0.5
    x, y = t.numeric(xcol), t.numeric(ycol)
    # The measured boundary and its closed form (stability_boundary.csv), keyed as the map is.
    b = src.table("stability_boundary.csv") if src.has("stability_boundary.csv") else None
    if b is not None and len(b):
        bkeys = np.array([m if not (np.isfinite(q) and q != 1) else f"{m} step ratio {q:.3g}"
                          for m, q in zip(b["method"], b.numeric("step_ratio"))])
    for method in methods:
        sel = (keys == method) if keys is not None else np.ones(len(t), bool)
        ratios = [None]
        if rcol is not None:
            values = t.numeric(rcol)[sel]
            ratios = sorted(set(v for v in values if np.isfinite(v))) or [None]
        n = len(ratios)
        cols = min(n, 3)
        rows = math.ceil(n / cols)
        fig, axes = new_figure(rows, cols, height=3.6 * rows + 0.4, width=4.2 * cols + 1.0,
                               sharex=True, sharey=True)
        for k, r in enumerate(ratios):
            ax = axes.flat[k]
            s = sel.copy()
            if r is not None:
                s &= t.numeric(rcol) == r
            ax.scatter(x[s & stable], y[s & stable], marker="s", s=28, color="C2",
                       label="stable")
            ax.scatter(x[s & ~stable], y[s & ~stable], marker="x", s=28, color="C3",
                       label="unstable")
            if b is not None and len(b):
                bs = bkeys == method
                if r is not None:
                    bs &= b.numeric("mass_ratio") == r
                bx = b.numeric("stiffness_factor")
                for link, style in (("unilateral", "k-"), ("tied", "b--")):
                    m = np.flatnonzero(bs & (b["link"] == link))
                    m = m[np.argsort(bx[m])]
                    if m.size:
                        ax.plot(bx[m], b.numeric("critical_courant")[m], style, linewidth=1.0,
                                label=f"measured boundary ({link})")
                m = np.flatnonzero(bs)
                m = m[np.argsort(bx[m])]
                if m.size:
                    ax.plot(bx[m], b.numeric("closed_form_courant")[m], color="C4", linestyle=":",
                            linewidth=1.0, label="closed form")
            if method == "penalty":
                k_ratio = np.logspace(np.log10(max(np.nanmin(x), 1e-12)),
                                      np.log10(np.nanmax(x)), 200)
                ax.plot(k_ratio, np.minimum(1.0, np.sqrt(2.0 / k_ratio)), color="k",
                        linestyle="--", linewidth=1.0, label="≈ √(2k/ε_s) (docs/methods.md §2)")
            ax.set_xscale("log")
            ax.set_title((f"R/R_crit = {r:g}" if r is not None else method), fontsize=9)
            ax.set_xlabel("penalty stiffness ε_s / (EA/h)")
            ax.set_ylabel("Courant number c·Δt/h")
            ax.legend(loc="lower left", fontsize=7)
        for ax in list(axes.flat)[n:]:
            ax.set_visible(False)
        fig.suptitle(src.title(f"Stability map: {method}".rstrip(": ")))
        figs.save(fig, src.png(f"stability_{slug(method or 'all')}"),
                  src.title(f"Stability map {method}".strip()),
                  "Stable (green) and unstable (red: energy growth or NaN) runs over penalty "
                  "stiffness and Courant number (stability.csv)"
                  + (", one panel per mass-penalty ratio R/R_crit." if rcol else "."))


# ---- HTML ------------------------------------------------------------------------------------

def slug(text):
    s = re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()
    return s or "main"


def summary_html(src):
    s = src.summary
    if not isinstance(s, dict) or not s:
        return ""
    scalars = [(k, v) for k, v in s.items() if not isinstance(v, (dict, list))]
    out = []
    # Plausibility warnings head the results: a run can be stable and still not physical.
    warnings = s.get("warnings")
    if isinstance(warnings, list) and warnings:
        out.append("<div class='warn'><b>Warnings</b><ul>"
                   + "".join(f"<li>{html.escape(str(w))}</li>" for w in warnings) + "</ul></div>")
    if scalars:
        out.append("<table class='kv'>")
        for k, v in scalars:
            out.append(f"<tr><th>{html.escape(str(k))}</th><td>{html.escape(fmt(v))}</td></tr>")
        out.append("</table>")
    for k, v in s.items():
        if isinstance(v, list) and v and all(isinstance(r, dict) for r in v):
            keys = list(dict.fromkeys(key for r in v for key in r))
            out.append(f"<p class='cap'>{html.escape(k)}</p><table><tr>"
                       + "".join(f"<th>{html.escape(c)}</th>" for c in keys) + "</tr>")
            for r in v:
                out.append("<tr>" + "".join(f"<td>{html.escape(fmt(r.get(c, '')))}</td>"
                                            for c in keys) + "</tr>")
            out.append("</table>")
    out.append("<details><summary>summary.json</summary><pre>"
               + html.escape(json.dumps(s, indent=2)) + "</pre></details>")
    return "\n".join(out)


def headline_html(src):
    """What a reader of a processed test needs first: striker, rate, stress, equilibrium, and
    every warning."""
    s = src.summary
    if not isinstance(s, dict) or not s:
        return ""
    rows = []

    def get(*keys):
        v = s
        for k in keys:
            v = v.get(k) if isinstance(v, dict) else None
        return v

    if s.get("command") == "process":
        v = get("striker_velocity_m_s", "inferred")
        if v is not None:
            scene_v = get("striker_velocity_m_s", "scene")
            rows.append(("striker velocity (inferred)", f"{v:.4g} m/s"
                         + (f" (scene: {scene_v:.4g} m/s)" if scene_v is not None else "")))
        plateau = s.get("plateau_strain_rate_1_s")
        mean = get("strain_rate", "mean_over_loading_1_s")
        if plateau is not None:
            rows.append(("strain rate (plateau)", f"{plateau:.4g} 1/s"))
        elif mean is not None:
            rows.append(("strain rate", f"no plateau; mean over the loading {mean:.4g} 1/s"))
        if s.get("peak_stress_Pa") is not None:
            rows.append(("peak 3-wave stress", f"{s['peak_stress_Pa'] * MPA:.4g} MPa"))
        if s.get("max_strain") is not None:
            rows.append(("strain at the end of loading", f"{s['max_strain']:.4g} "
                         f"({get('end_of_loading', 'how') or ''})"))
        frac = get("equilibrium", "fraction_of_loaded_time")
        if frac is not None:
            t_eq = s.get("time_to_equilibrium_s")
            rows.append(("equilibrium (R ≤ 5 %)", f"{100 * frac:.0f} % of the loaded time; "
                         + (f"holds from {t_eq * 1e6:.3g} µs until unloading" if t_eq is not None
                            else "never holds until unloading")))
        rms = s.get("rms_of_peak")
        if isinstance(rms, dict):
            rows.append(("bars together: RMS of peak",
                         f"{100 * rms.get('pochhammer_chree', float('nan')):.3g} % with "
                         f"Pochhammer–Chree, {100 * rms.get('time_shift', float('nan')):.3g} % "
                         "with a time shift"))
        if s.get("error"):
            rows.append(("error", s["error"]))
    warnings = s.get("warnings") or []
    out = []
    if rows:
        out.append("<table class='kv headline'>" + "".join(
            f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>" for k, v in rows)
            + "</table>")
    if warnings:
        out.append("<div class='warnings'><p><b>Warnings</b></p><ul>" + "".join(
            f"<li>{html.escape(str(w))}</li>" for w in warnings) + "</ul></div>")
    return "\n".join(out)


def fmt(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, (dict, list)):
        return json.dumps(v)
    return str(v)


def csv_html(table, caption):
    out = [f"<p class='cap'>{html.escape(caption)}</p><table><tr>"
           + "".join(f"<th>{html.escape(n)}</th>" for n in table.names) + "</tr>"]
    for row in table.rows:
        out.append("<tr>" + "".join(f"<td>{html.escape(fmt(v))}</td>" for v in row) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


CSS = """
body{font-family:sans-serif;max-width:1100px;margin:1.5em auto;padding:0 1em;color:#222;
background:#fff}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;border-bottom:1px solid #ccc;
margin-top:1.6em}h3{font-size:1.05em}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.9em;color:#444;margin-top:.3em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}th{background:#f2f2f2}
.meta{color:#666;font-size:.9em}.cap{font-weight:bold;margin-bottom:0}
.warn{border:2px solid #c60;background:#fff4e5;padding:.3em .8em;margin:.5em 0}
pre{font-size:.8em;background:#f8f8f8;padding:.5em;overflow-x:auto}
.headline th{background:#e8eef8}.warnings{background:#fff4e0;border:1px solid #e0a040;
padding:.2em 1em;font-size:.9em}
"""


def write_html(path, folder, sources, figs, fig_dir_name):
    parts = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>", GENERATOR,
             f"<title>shpb report — {html.escape(os.path.basename(os.path.abspath(folder)))}"
             "</title>", f"<style>{CSS}</style></head><body>",
             f"<h1>shpb report: {html.escape(os.path.basename(os.path.abspath(folder)))}</h1>",
             f"<p class='meta'>Folder {html.escape(os.path.abspath(folder))}; generated "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC by "
             "tools/report.py. Signals tension positive; stress–strain, strain rate and "
             "specimen stress compression positive.</p>"]
    for src in sources:
        name = "this folder" if src.label == "." else src.label
        parts.append(f"<h2>Results: {html.escape(name)}</h2>")
        parts.append(f"<p class='meta'>files: {html.escape(', '.join(sorted(src.files)))}</p>")
        parts.append(headline_html(src))
        parts.append(summary_html(src))
        if src.has("comparison.csv"):
            parts.append(csv_html(src.table("comparison.csv"),
                                  "comparison.csv — pulse by pulse, simulated against measured"))
    parts.append("<h2>Figures</h2>")
    for name, title, caption in figs.items:
        with open(os.path.join(figs.out_dir, name), "rb") as f:
            data = base64.b64encode(f.read()).decode("ascii")
        ref = f"{fig_dir_name}/{name}"
        parts.append(f"<figure id='{html.escape(name)}'><h3>{html.escape(title)}</h3>"
                     f"<a href='{html.escape(ref)}'><img alt='{html.escape(title)}' "
                     f"src='data:image/png;base64,{data}'></a>"
                     f"<figcaption>{html.escape(caption)} "
                     f"<a href='{html.escape(ref)}'>{html.escape(ref)}</a></figcaption></figure>")
    parts.append("</body></html>")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(parts))


# ---- main ------------------------------------------------------------------------------------

def build(folder):
    if not os.path.isdir(folder):
        raise ReportError(f"{folder}: not a folder: an output folder of shpb was expected")
    sources = find_sources(folder)
    if not sources:
        raise ReportError(f"{folder}: no gauges.csv, curve.csv, signals.csv, pareto.csv or "
                          "other shpb output: an output folder of simulate, process, compare or "
                          "study was expected")
    check_ownership(folder)
    # Figures are drawn into a temporary folder and moved into place at the end, so a failure
    # leaves any previous report intact (docs/outputs.md (conventions)).
    tmp = tempfile.mkdtemp(prefix=".report-", dir=folder)
    os.chmod(tmp, 0o755)
    old = None
    try:
        with open(os.path.join(tmp, FIGURES_MARKER), "w", encoding="utf-8") as f:
            f.write(FIGURES_SIGNATURE)
        figs = Figures(tmp)
        truth = next((s.table("specimen.csv") for s in sources if s.has("specimen.csv")), None)
        for src in sources:
            if src.has("signals.csv"):
                fig_compare_signals(src, figs)
            elif src.has("gauges.csv"):
                fig_gauges(src, figs)
            if src.has("field.csv"):
                fig_wave_diagram(src, figs)
            if src.has("raw_signals.csv"):
                fig_raw_signals(src, figs)
            if src.has("pulses.csv") and "incident" in src.table("pulses.csv"):
                fig_pulses(src, figs)
            elif src.has("pulses.csv") and "far_measured" in src.table("pulses.csv"):
                fig_bar_check(src, figs)
            if src.has("curve.csv"):
                fig_curve(src, figs, truth)
            if src.has("specimen.csv"):
                fig_specimen(src, figs)
            if src.has("interfaces.csv"):
                fig_interfaces(src, figs)
            if src.has("energy.csv"):
                fig_energy(src, figs)
            if src.has("pareto.csv"):
                fig_pareto(src, figs)
            if src.has("stability.csv"):
                fig_stability(src, figs)
        if os.path.isfile(os.path.join(folder, "campaign.csv")):
            fig_campaign(folder, sources, figs)
        html_tmp = os.path.join(tmp, "report.html")
        write_html(html_tmp, folder, sources, figs, "figures")
        for name in os.listdir(tmp):
            sync(os.path.join(tmp, name))
        sync(tmp)
        fig_dir = os.path.join(folder, "figures")
        final_html = os.path.join(folder, "report.html")
        os.replace(html_tmp, os.path.join(folder, ".report.html.tmp"))
        tell_output_marker(folder, ["figures", "report.html"])
        if os.path.isdir(fig_dir):  # ours (check_ownership): set aside, removed below
            old = tmp + ".old"
            os.replace(fig_dir, old)
        os.replace(tmp, fig_dir)
        os.replace(os.path.join(folder, ".report.html.tmp"), final_html)
        sync(folder)
        return final_html, len(figs.items)
    finally:
        for leftover in (tmp, old):
            if leftover and os.path.isdir(leftover):
                shutil.rmtree(leftover, ignore_errors=True)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr if len(argv) != 2 else sys.stdout)
        return 0 if len(argv) == 2 else 2
    try:
        path, count = build(argv[1])
    except ReportError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except (ValueError, KeyError, IndexError) as e:
        print(f"error: {argv[1]}: {type(e).__name__}: {e}: a well-formed shpb output folder "
              "was expected", file=sys.stderr)
        return 2
    except OSError as e:  # read-only folder, full disk: the report cannot be written
        where = e.filename or argv[1]
        print(f"error: {where}: cannot be written: {e.strerror or e}", file=sys.stderr)
        return 3
    print(f"report: {count} figures, {os.path.abspath(path)}")
    return 0


# ---- figures of `fit` (a folder with fit.json, curves.csv, long-format signals.csv) ----------

def fig_fit(src, figs):
    """Measured against start and fitted pulses per test, curves with the law, correlations."""
    s = src.summary if isinstance(src.summary, dict) else {}
    t = src.table("signals.csv")
    for name in ("test", "pulse", "time_s", "measured_strain", "start_strain", "fitted_strain"):
        if name not in t:
            raise ReportError(f"{t.path}: header: {','.join(t.names)}: a column {name} "
                              "was expected (shpb fit's signals.csv)")
    tests = list(dict.fromkeys(t["test"]))
    pulses = list(dict.fromkeys(t["pulse"]))
    nrmse = {x.get("name"): x for x in s.get("tests", []) if isinstance(x, dict)}
    fig, axes = new_figure(len(tests), len(pulses), height=2.8 * len(tests) + 0.6,
                           width=4.2 * len(pulses) + 1)
    for i, test in enumerate(tests):
        for j, pulse in enumerate(pulses):
            ax = axes[i, j]
            m = (t["test"] == test) & (t["pulse"] == pulse)
            time = t.numeric("time_s")[m] * US
            ax.plot(time, t.numeric("measured_strain")[m] * MICRO, color="k", linewidth=1.1,
                    label="measured")
            ax.plot(time, t.numeric("start_strain")[m] * MICRO, color="C0", linewidth=0.8,
                    alpha=0.7, label="start")
            ax.plot(time, t.numeric("fitted_strain")[m] * MICRO, color="C3", linewidth=1.0,
                    linestyle="--", label="fitted")
            r = nrmse.get(test, {})
            before, after = r.get(f"nrmse_{pulse}_before"), r.get(f"nrmse_{pulse}_after")
            title = f"{test}: {pulse}"
            if before is not None and after is not None:
                title += f" (NRMSE {before:.3f} → {after:.3f})"
            ax.set_title(title, fontsize=9)
            ax.set_xlabel("time (µs)")
            ax.set_ylabel("strain (µε)")
            ax.legend(loc="lower right", fontsize=7)
    figs.save(fig, src.png("fit_signals"), src.title("Fit: measured and simulated pulses"),
              "Each compared window of each test: measured (black), simulated with the starting "
              "law (blue) and with the fitted one (dashed); NRMSE as in summary.json.")

    if src.has("curves.csv"):
        c = src.table("curves.csv")
        fig, axes = new_figure()
        ax = axes[0, 0]
        for k, test in enumerate(dict.fromkeys(c["test"])):
            m = c["test"] == test
            ep = c.numeric("true_plastic_strain")[m]
            ax.plot(ep, c.numeric("stress_measured_Pa")[m] * MPA, color=f"C{k}", linewidth=1.0,
                    label=f"{test} processed")
            ax.plot(ep, c.numeric("stress_fitted_Pa")[m] * MPA, color=f"C{k}", linewidth=1.0,
                    linestyle="--", label=f"{test} fitted law")
            ax.plot(ep, c.numeric("stress_start_Pa")[m] * MPA, color=f"C{k}", linewidth=0.7,
                    linestyle=":", alpha=0.8)
        ax.set_xlabel("true plastic strain")
        ax.set_ylabel("true stress (MPa)")
        ax.set_title(src.title("Processed curves after equilibrium and the law"))
        ax.legend(fontsize=7)
        figs.save(fig, src.png("fit_curves"), src.title("Fit: curves and the law"),
                  "Processed true stress after equilibrium (solid), the fitted law at the same "
                  "plastic strain, rate and temperature (dashed) and the starting law (dotted).")

    corr = s.get("correlation", {})
    names, matrix = corr.get("parameters", []), corr.get("matrix", [])
    if names and matrix:
        a = np.array(matrix, dtype=float)
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


_fig_compare_signals = fig_compare_signals


def fig_compare_signals(src, figs):  # noqa: F811 (the fit producer, kept local to this block)
    if os.path.isfile(os.path.join(src.folder, "fit.json")):
        src.files.setdefault("curves.csv", os.path.join(src.folder, "curves.csv"))
        if not os.path.isfile(src.files["curves.csv"]):
            del src.files["curves.csv"]
        return fig_fit(src, figs)
    return _fig_compare_signals(src, figs)


if __name__ == "__main__":
    sys.exit(main(sys.argv))

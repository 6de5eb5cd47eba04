#!/usr/bin/python3
"""`shpb process` and `shpb compare` on simulated records degraded as lab instruments record them,
against the simulation's own specimen and striker (docs/validation.md "Records as a coarse scope
writes them").

Usage: tools/survey_process.py SHPB [--tension | --shapers | --compare]

Set-ups, each simulated by `shpb simulate` at its defaults:
- default: the classic experiment's layout with steel, aluminium or titanium bars, an Al 6061,
  copper, Ti-6Al-4V or PMMA specimen (specimens/*.json) of 10 × 5, 16 × 2 or 6 × 6 mm, struck at
  8 or 25 m/s (72 scenes);
- --tension: experiments/tension-bonded (bonded specimen, striker pulled) with those bars, an
  Al 6061, copper, Ti-6Al-4V or the scene's bilinear metal specimen of 10 × 5 or 6 × 6 mm, pulled
  at 10 or 20 m/s (48 scenes);
- --shapers: experiments/pulse-shaper (its 3 × 16 mm copper shaper) with steel bars, the four
  specimens of the default in its three shapes, struck at 10 or 20 m/s (24 scenes);
- --compare: the default's 10 × 5 mm set-ups (24 scenes), each record then given to
  `shpb compare --no-dispersion` as the scene's measurement (the simulation's record carries no
  dispersion): the striker velocity it infers against the simulated one, and each pulse's NRMSE.
Each record (10 MS/s) is re-recorded point-sampled at 1 MS/s and 500 kS/s, by an 8-bit digitizer
of range 1.25 × the channel's peak, with white noise of 1 % of the peak, with an offset of 3 % of
the peak, and as a "scope" (1 MS/s, 8 bits, 0.5 % noise, 2 % offset; the noise seeded, the same
every run), and processed with `shpb process --signals`. Errors of a run, against the specimen's
own (specimen.csv, the sign of the test's curve), over its peak value:
Errors have a value where the specimen strains beyond 0.02 (23 of the default's 72 stay elastic):
- 3-wave: the median, over 20 strains from 0.02 to 0.9 of the smaller of the two strain maxima, of
  |3-wave true stress − the specimen's true stress at that true strain|, both on their loading
  branches (no value when the specimen strains less than 0.02);
- 1-wave, 2-wave: the median over the loading (the curve's rows before its strain maximum, from
  10 to 90 % of it) of |stress_1wave − back-face stress| and |stress_2wave − front-face stress| at
  the same time;
- rate: the same median of |strain_rate_1_s − the specimen's rate| over the specimen's median rate
  there, the specimen's as the slope of its strain over 2 µs (its end nodes ring with the contact
  interfaces);
- max strain: summary max_strain against the specimen's largest strain until the loading ends
  (curve.csv's last row);
- plateau rate: summary plateau_strain_rate_1_s (none when the rate has no plateau) against the
  specimen's median rate over its own 10 to 90 % of that strain.
Prints, per record kind and error, the median, the runs beyond 3 % and how many of those carried
no warning, and the worst of them.
"""
import itertools
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHPB = sys.argv[1]
MODE = sys.argv[2] if len(sys.argv) > 2 else "--compression"
BARS = {"steel": ("8080 kg/m3", "200 GPa", 0.29), "al": ("2700 kg/m3", "70 GPa", 0.33),
        "ti": ("4430 kg/m3", "113.8 GPa", 0.342)}
SPECIMENS = {"al6061": "al6061-t6.json", "cu": "ofhc-copper.json", "ti": "ti6al4v.json",
             "pmma": "pmma.json"}
SHAPES = [("10 mm", "5 mm"), ("16 mm", "2 mm"), ("6 mm", "6 mm")]
# name: (sample rate or None for the simulated one, bits or 0, noise and offset over the peak)
RECORDS = {"as simulated": (None, 0, 0, 0), "1 MS/s": (1e6, 0, 0, 0), "500 kS/s": (5e5, 0, 0, 0),
           "8 bits": (None, 8, 0, 0), "noise 1 %": (None, 0, 0.01, 0),
           "offset 3 %": (None, 0, 0, 0.03), "scope": (1e6, 8, 0.005, 0.02)}
BOUND = 0.03
SMOOTH = 2e-6  # s: longer than a 6 mm metal specimen's transit, shorter than its loading
LOADING = (0.1, 0.9)  # fractions of the strain maximum: past the rise, short of the turn


def variant(experiment, roles, bars, specimen, shape, velocity):
    """The experiment's scene with these bars (roles: striker, incident, transmitter, specimen
    indices), specimen (a specimens/ file or a material of the scene), shape and velocity."""
    scene = json.loads((ROOT / "experiments" / experiment / "scene.json").read_text())
    for bar in scene["bars"]:  # paths relative to the experiment, the scene is written elsewhere
        if bar["material"].endswith(".json"):
            bar["material"] = str((ROOT / "experiments" / experiment / bar["material"]).resolve())
    scene["materials"].update({name: {"model": "elastic", "density": rho, "youngs_modulus": e,
                                      "poisson_ratio": nu} for name, (rho, e, nu) in BARS.items()})
    for bar in roles[:3]:
        scene["bars"][bar]["material"] = bars
    scene["bars"][roles[0]]["velocity"] = f"{velocity} m/s"
    material = str(ROOT / "specimens" / SPECIMENS[specimen]) if specimen in SPECIMENS else specimen
    scene["bars"][roles[3]].update(material=material, diameter=shape[0], length=shape[1])
    name = f"{bars}_{specimen}_{shape[0].split()[0]}x{shape[1].split()[0]}_{abs(velocity)}"
    return name, scene


def scenes():
    if MODE == "--tension":
        for bars, specimen, shape, velocity in itertools.product(
                BARS, ["al6061", "cu", "ti", "metal"], [SHAPES[0], SHAPES[2]], [-10, -20]):
            name, scene = variant("tension-bonded", (0, 1, 3, 2), bars, specimen, shape, velocity)
            scene["measurement"] = {"test": "tension"}  # --signals: the test's sign only
            yield name, scene
        return
    if MODE == "--shapers":
        for specimen, shape, velocity in itertools.product(SPECIMENS, SHAPES, [10, 20]):
            yield variant("pulse-shaper", (0, 2, 4, 3), "steel", specimen, shape, velocity)
        return
    shapes = SHAPES[:1] if MODE == "--compare" else SHAPES
    for bars, specimen, shape, velocity in itertools.product(BARS, SPECIMENS, shapes, [8, 25]):
        yield variant("classic-al6061", (0, 1, 3, 2), bars, specimen, shape, velocity)


def rerecord(t, channels, rate, bits, noise, offset, rng):
    times = np.arange(t[0], t[-1], 1 / rate) if rate else t
    out = [times]
    for x in channels:
        y = np.interp(times, t, x)
        peak = np.max(np.abs(y))
        y = y + noise * peak * rng.standard_normal(len(y)) + offset * peak
        if bits:
            lsb = 2 * 1.25 * peak / 2 ** bits
            y = np.clip(np.round(y / lsb), -2 ** (bits - 1), 2 ** (bits - 1) - 1) * lsb
        out.append(y)
    return np.column_stack(out)


def stress_error(curve, truth):
    e, s = curve["true_strain"], curve["true_stress_Pa"]
    te, ts = truth["true_strain"], truth["true_stress_Pa"]
    top, ttop = int(np.argmax(e)), int(np.argmax(te))
    last = 0.9 * min(e[top], te[ttop])
    if last <= 0.02:
        return None  # an elastic specimen: no strain range to compare
    grid = np.linspace(0.02, last, 20)
    order = np.argsort(e[:top + 1])
    processed = np.interp(grid, e[:top + 1][order], s[:top + 1][order])
    return float(np.median(np.abs(processed - np.interp(grid, te[:ttop + 1], ts[:ttop + 1])))
                 / np.max(np.abs(ts)))


def loading(strain):
    """Rows before the strain maximum within LOADING of it."""
    top = int(np.argmax(strain))
    rows = np.arange(top + 1)
    return rows[(strain[:top + 1] >= LOADING[0] * strain[top])
                & (strain[:top + 1] <= LOADING[1] * strain[top])]


def errors(curve, summary, truth):
    """Every error of one run (module docstring), None where it has no value."""
    t = curve["time_s"]
    strain = truth["strain"][truth["time_s"] <= t[-1]]
    if np.max(strain) <= 0.02:
        return {}  # an elastic specimen: no flow to compare (the 3-wave error's bound)
    at = {c: np.interp(t, truth["time_s"], truth[c]) for c in truth.dtype.names}
    rows = loading(curve["strain"])
    peak = np.max(np.abs(truth["stress_Pa"]))
    out = {"3-wave": stress_error(curve, truth)}
    for name, column, face in (("1-wave", "stress_1wave_Pa", "back_stress_Pa"),
                               ("2-wave", "stress_2wave_Pa", "front_stress_Pa")):
        out[name] = float(np.median(np.abs(curve[column][rows] - at[face][rows]))) / peak
    # The specimen's end nodes ring with the contact interfaces (about one transit): its rate
    # as the slope of its strain over SMOOTH, which a reduction from the bars' motion gives.
    own = (np.interp(t + SMOOTH / 2, truth["time_s"], truth["strain"])
           - np.interp(t - SMOOTH / 2, truth["time_s"], truth["strain"])) / SMOOTH
    rate = float(np.median(own[rows]))
    out["rate"] = float(np.median(np.abs(curve["strain_rate_1_s"][rows] - own[rows]))) / rate
    out["max strain"] = abs(summary["max_strain"] - np.max(strain)) / np.max(strain)
    flow = loading(strain)
    plateau = float(np.median(truth["strain_rate_1_s"][flow]))
    measured = summary["plateau_strain_rate_1_s"]
    out["plateau rate"] = None if measured is None else abs(measured - plateau) / plateau
    return out


def read(path, sign=1):
    table = np.genfromtxt(path, delimiter=",", names=True)
    for column in table.dtype.names[1:]:
        table[column] *= sign
    return table


def process(tmp, path, record, truth):
    out = tmp / "processed"
    run = subprocess.run([SHPB, "process", str(path), "--signals", str(record), "-o", str(out),
                          "-q"], capture_output=True, text=True)
    if run.returncode:
        return None, run.stderr.strip()[:120]
    summary = json.loads((out / "summary.json").read_text())
    return errors(read(out / "curve.csv"), summary, truth), "; ".join(summary["warnings"])


def compare(tmp, scene, record, columns, velocity):
    scene = json.loads(json.dumps(scene))
    scene["measurement"] = {
        "file": str(record), "time": {"column": columns[0], "unit": "s"},
        "channels": [{"gauge": c, "column": c, "unit": "strain"} for c in columns[1:]]}
    path = tmp / "compared.json"
    path.write_text(json.dumps(scene))
    out = tmp / "compared"
    run = subprocess.run([SHPB, "compare", str(path), "--no-dispersion", "-o", str(out), "-q"],
                         capture_output=True, text=True)
    if run.returncode:
        return None, run.stderr.strip()[:120]
    summary = json.loads((out / "summary.json").read_text())
    inferred = summary["striker_velocity_m_s"]
    nrmse = {p["pulse"]: p["nrmse"] for p in summary["pulses"] if p.get("nrmse") is not None}
    found = {"velocity": abs(abs(inferred) - abs(velocity)) / abs(velocity)}
    found.update({f"nrmse {p}": v for p, v in nrmse.items()})
    return found, "; ".join(summary.get("warnings", []))


def report(results):
    for kind, rows in results.items():
        print(f"{kind}: {len(rows)} runs")
        failed = [r for r in rows if r[1] is None]
        if failed:
            print(f"  {len(failed)} failed, e.g. {failed[0][0]}: {failed[0][2]}")
        rows = [r for r in rows if r[1] is not None]
        for error in max((e for _, e, _ in rows), key=len, default={}):
            values = [(name, e[error], w) for name, e, w in rows if e.get(error) is not None]
            off = sorted((r for r in values if r[1] > BOUND), key=lambda r: -r[1])
            median = 100 * np.median([v for _, v, _ in values])
            silent = sum(not w for _, _, w in off)
            print(f"  {error}: {len(values)} with a value, median {median:.2f} %, "
                  f"{len(off)} beyond {100 * BOUND:g} % ({silent} without a warning)")
            for name, value, warning in off[:3]:
                print(f"    {name}: {100 * value:.1f} % {warning[:100]}")


def main():
    rng = np.random.default_rng(1)
    results = {kind: [] for kind in RECORDS}
    sign = -1 if MODE == "--tension" else 1  # specimen.csv is compression positive
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for name, scene in scenes():
            path = tmp / f"{name}.json"
            path.write_text(json.dumps(scene))
            subprocess.run([SHPB, "simulate", str(path), "-o", str(tmp / name), "-q"], check=True,
                           capture_output=True)
            gauges = np.genfromtxt(tmp / name / "gauges.csv", delimiter=",", names=True)
            truth = read(tmp / name / "specimen.csv", sign)
            columns = gauges.dtype.names
            for kind, (rate, bits, noise, offset) in RECORDS.items():
                record = tmp / "record.csv"
                np.savetxt(record, rerecord(gauges[columns[0]], [gauges[c] for c in columns[1:]],
                                            rate, bits, noise, offset, rng),
                           delimiter=",", header=",".join(columns), comments="")
                if MODE == "--compare":
                    velocity = float(scene["bars"][0]["velocity"].split()[0])
                    found, warning = compare(tmp, scene, record, columns, velocity)
                else:
                    found, warning = process(tmp, path, record, truth)
                results[kind].append((name, found, warning))
    report(results)


main()

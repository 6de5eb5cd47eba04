#!/usr/bin/python3
"""`shpb process` on simulated records degraded as lab instruments record them, against the
simulation's own specimen (docs/validation.md "Records as a coarse scope writes them").

Usage: tools/survey_process.py SHPB

The classic experiment's layout with steel, aluminium or titanium bars, an Al 6061, copper,
Ti-6Al-4V or PMMA specimen (specimens/*.json) of 10 × 5, 16 × 2 or 6 × 6 mm, struck at 8 or 25 m/s:
72 scenes, each simulated by `shpb simulate` at its defaults. Each record (10 MS/s) is then
re-recorded point-sampled at 1 MS/s and 500 kS/s, by an 8-bit digitizer of range 1.25 × the
channel's peak, with white noise of 1 % of the peak, with an offset of 3 % of the peak, and as a
"scope" (1 MS/s, 8 bits, 0.5 % noise, 2 % offset; the noise seeded, the same every run), and
processed with `shpb process --signals`. The error of a run is the median, over 20 strains from
0.02 to 0.9 of the smaller of the two strain maxima, of |processed 3-wave true stress − the
specimen's true stress at that true strain| over the specimen's peak stress, both on their loading
branches. Prints, per record kind, the median error, the runs beyond 3 % and how many of those
carried no warning, and the worst of them.
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


def scenes():
    base = json.loads((ROOT / "experiments/classic-al6061/scene.json").read_text())
    base.pop("measurement", None)
    for bars, specimen, shape, velocity in itertools.product(BARS, SPECIMENS, SHAPES, [8, 25]):
        scene = json.loads(json.dumps(base))
        scene["materials"] = {name: {"model": "elastic", "density": rho, "youngs_modulus": e,
                                     "poisson_ratio": nu} for name, (rho, e, nu) in BARS.items()}
        for bar in (0, 1, 3):
            scene["bars"][bar]["material"] = bars
        scene["bars"][0]["velocity"] = f"{velocity} m/s"
        scene["bars"][2].update(material=str(ROOT / "specimens" / SPECIMENS[specimen]),
                                diameter=shape[0], length=shape[1])
        yield f"{bars}_{specimen}_{shape[0].split()[0]}x{shape[1].split()[0]}_{velocity}", scene


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


def main():
    rng = np.random.default_rng(1)
    results = {kind: [] for kind in RECORDS}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for name, scene in scenes():
            path = tmp / f"{name}.json"
            path.write_text(json.dumps(scene))
            subprocess.run([SHPB, "simulate", str(path), "-o", str(tmp / name), "-q"], check=True,
                           capture_output=True)
            gauges = np.genfromtxt(tmp / name / "gauges.csv", delimiter=",", names=True)
            truth = np.genfromtxt(tmp / name / "specimen.csv", delimiter=",", names=True)
            columns = gauges.dtype.names
            for kind, (rate, bits, noise, offset) in RECORDS.items():
                record = tmp / "record.csv"
                np.savetxt(record, rerecord(gauges[columns[0]], [gauges[c] for c in columns[1:]],
                                            rate, bits, noise, offset, rng),
                           delimiter=",", header=",".join(columns), comments="")
                out = tmp / "processed"
                run = subprocess.run([SHPB, "process", str(path), "--signals", str(record), "-o",
                                      str(out), "-q"], capture_output=True, text=True)
                if run.returncode:
                    results[kind].append((name, None, run.stderr.strip()[:120]))
                    continue
                curve = np.genfromtxt(out / "curve.csv", delimiter=",", names=True)
                warnings = json.loads((out / "summary.json").read_text())["warnings"]
                results[kind].append((name, stress_error(curve, truth), "; ".join(warnings)))
    for kind, rows in results.items():
        errors = [e for _, e, _ in rows if e is not None]
        off = sorted((r for r in rows if r[1] is not None and r[1] > BOUND), key=lambda r: -r[1])
        failed = [r for r in rows if r[1] is None]
        print(f"{kind}: {len(rows)} runs, median error {100 * np.median(errors):.2f} %, "
              f"{len(off)} beyond {100 * BOUND:g} % ({sum(not w for _, _, w in off)} without a "
              f"warning), {len(failed)} not compared (a strain below 0.02 or a failed run)")
        for name, error, warning in off[:3]:
            print(f"  {name}: {100 * error:.1f} % {warning[:100]}")


main()

#!/usr/bin/python3
"""Survey of where a gauge record starts: good records (a pre-trigger of P samples of rest before
the incident pulse's first motion) and records cut on the incident pulse's front (starting where
the noise-free pulse has reached a fraction f of its peak), for sharp and ramped (pulse-shaped)
fronts, processed by two shpb binaries.

Usage: tools/survey_record_start.py OLD_SHPB NEW_SHPB OUTDIR [--quick]

Each of experiments/{pulse-shaper,classic-al6061,lanl-cu-ofe-273k,tension-bonded} is simulated
once at 100 MS/s (OUTDIR/sims), its two gauges point-sampled at 100 MS/s, 10 MS/s, 1 MS/s and
250 kS/s, given white noise of 0.1, 1 or 2 % of each gauge's peak and offsets of +3 / −2 %,
digitized at 8 or 16 bits over a range of 1.2 × the peak rounded up to 1, 2 or 5 × a power of
ten (mV), printed to 6 significant digits, and cut to start P = 10, 15, 25 or 50 samples before
the pulse's first motion (good: |x| beyond 10⁻³ of the peak) or where it first reaches f = 3, 10,
25 or 50 % of its peak (cut: the missing part of its integral and its time origin are lost).
Prints one JSON row per record and the counts per kind and start; `same` is a byte comparison of
the two binaries' outputs (summary.json's wall times aside). --quick: 10 MS/s and 250 kS/s, 16
and 8 bits, 0.1 and 2 % noise only. OLD and NEW the same binary: each record is processed once.
"""
import json
import math
import os
import pathlib
import subprocess
import sys
import zlib

import numpy as np

OLD, NEW, OUT = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3]).resolve()
QUICK = "--quick" in sys.argv
REPO = pathlib.Path(__file__).resolve().parent.parent
RECORDS = ["pulse-shaper", "classic-al6061", "lanl-cu-ofe-273k", "tension-bonded"]
RATES = [10e6, 250e3] if QUICK else [100e6, 10e6, 1e6, 250e3]
BITS = [16, 8]
NOISES = [0.001, 0.02] if QUICK else [0.001, 0.01, 0.02]
PRE = [10, 15, 25, 50]
CUTS = [0.03, 0.1, 0.25, 0.5]


def absolutize(v, base):
    if isinstance(v, dict):
        return {k: absolutize(x, base) for k, x in v.items()}
    if isinstance(v, list):
        return [absolutize(x, base) for x in v]
    if isinstance(v, str) and (base / v).is_file():
        return str((base / v).resolve())
    return v


def simulated(e):
    d = OUT / "sims" / e
    if not (d / "gauges.csv").is_file():
        s = absolutize(json.load(open(REPO / "experiments" / e / "scene.json")), REPO / "experiments" / e)
        s.pop("measurement", None)
        s["simulation"]["sample_rate"] = "100 MHz"
        d.parent.mkdir(parents=True, exist_ok=True)
        sc = d.parent / f"{e}.json"  # apart from the output folder, which simulate replaces
        sc.write_text(json.dumps(s, indent=1))
        subprocess.run([NEW, "simulate", str(sc), "-o", str(d), "-q"], check=True)
    return np.genfromtxt(d / "gauges.csv", delimiter=",", names=True)


def scene(e, file):
    s = absolutize(json.load(open(REPO / "experiments" / e / "scene.json")), REPO / "experiments" / e)
    s.pop("measurement", None)
    m = {"file": str(file), "time": {"column": "time_s"},
         "channels": [{"gauge": g, "column": g, "unit": "V", "scale": 1e-3} for g in ("incident", "transmitted")],
         "dispersion": {"correction": "none"}}
    if e == "tension-bonded":
        m["test"] = "tension"
    s["measurement"] = m
    return s


def scope(d, rate, bits, noise, seed):
    t = d["time_s"]
    step = max(1, int(round(1 / rate / (t[1] - t[0]))))
    tn = t[::step]
    rng = np.random.default_rng(seed)
    cols, clean = {}, None
    for j, g in enumerate(("incident", "transmitted")):
        y = d[g][::step]
        peak = np.max(np.abs(y))
        if j == 0:
            clean = y / peak
        v = (y + rng.normal(0, noise * peak, y.size) + (0.03 if j == 0 else -0.02) * peak) / 1e-3
        vr = 10 ** math.ceil(math.log10(1.2 * np.max(np.abs(v))))
        for m in (0.2, 0.5, 1.0):
            if 1.2 * np.max(np.abs(v)) <= m * vr:
                vr = m * vr
                break
        q = 2 * vr / 2 ** bits
        cols[g] = np.clip(np.round(v / q) * q, -vr, vr - q)
    return tn, cols, np.abs(clean)


def write(path, t, cols, a):
    with open(path, "w") as f:
        f.write("time_s,incident,transmitted\n")
        for i in range(a, t.size):
            f.write(f"{t[i] - t[a]:.9e}," + ",".join(f"{cols[g][i]:.6g}" for g in cols) + "\n")


def run(b, sc, out):
    r = subprocess.run([b, "process", str(sc), "-o", str(out), "-q"], capture_output=True, text=True)
    return r.returncode, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ""


def same(a, b):
    fa = sorted(os.listdir(a)) if a.exists() else []
    fb = sorted(os.listdir(b)) if b.exists() else []
    if fa != fb:
        return False
    for f in fa:
        x, y = open(a / f, "rb").read(), open(b / f, "rb").read()
        if f == "summary.json":
            x = b"".join(l for l in x.splitlines(True) if b"wall_time" not in l)
            y = b"".join(l for l in y.splitlines(True) if b"wall_time" not in l)
        if x != y:
            return False
    return True


rows = []
for e in RECORDS:
    d = simulated(e)
    for rate in RATES:
        for bits in BITS:
            for noise in NOISES:
                rid = f"{e}_{rate / 1e6:g}M_{bits}b_n{noise}"
                t, cols, clean = scope(d, rate, bits, noise, zlib.crc32(rid.encode()))
                first = int(np.argmax(clean > 1e-3))
                starts = [(f"pre{p}", first - p) for p in PRE]
                starts += [(f"cut{int(100 * f)}", int(np.argmax(clean >= f))) for f in CUTS]
                seen = set()
                for name, a in starts:
                    if a < 0 or a in seen:
                        continue
                    seen.add(a)
                    dd = OUT / f"{rid}_{name}"
                    dd.mkdir(parents=True, exist_ok=True)
                    write(dd / "rec.csv", t, cols, a)
                    (dd / "scene.json").write_text(json.dumps(scene(e, dd / "rec.csv"), indent=1))
                    ro, eo = run(OLD, dd / "scene.json", dd / "old")
                    rn, en = run(NEW, dd / "scene.json", dd / "new") if NEW != OLD else (ro, eo)
                    row = dict(id=f"{rid}_{name}", record=e, start=name, kind="good" if name.startswith("pre") else "cut",
                               old=ro, new=rn, same=NEW == OLD or same(dd / "old", dd / "new"), err_old=eo[-160:], err_new=en[-160:])
                    rows.append(row)
                    print(json.dumps(row), flush=True)
json.dump(rows, open(OUT / "rows.json", "w"), indent=1)
for k in ("good", "cut"):
    rs = [r for r in rows if r["kind"] == k]
    print(k, len(rs), "old exit 0:", sum(r["old"] == 0 for r in rs), "new exit 0:", sum(r["new"] == 0 for r in rs),
          "identical:", sum(r["same"] for r in rs))
for e in RECORDS:
    for s in [f"pre{p}" for p in PRE] + [f"cut{int(100 * f)}" for f in CUTS]:
        rs = [r for r in rows if r["record"] == e and r["start"] == s]
        print(f"{e:18s} {s:6s} {len(rs):3d} old exit 0: {sum(r['old'] == 0 for r in rs):3d} "
              f"new exit 0: {sum(r['new'] == 0 for r in rs):3d}")

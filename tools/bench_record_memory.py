#!/usr/bin/python3
"""`shpb process` of deep-memory scope records: wall time and peak resident memory per sample.

Figures, not assertions (the machine may be loaded). Writes, under a scratch folder, records of a
classic-bar test (steel C350, gauges 1 m from the specimen, 10 MS/s, the pulses 10 ms after the
start; tools/bench_dispersion.cpp's --write-record test) in the text formats the reader takes:
  csv        time column and two gauge columns ("%.7e,%.6e,%.6e")
  no-time    two gauge columns, the time base from measurement.time.interval
  tektronix  one Tektronix channel file per gauge (metadata in columns 1-3, time 4, volts 5)
and runs `shpb process` on each with every binary given, through /usr/bin/time -v. Prints the
wall time and the peak resident set (ru_maxrss) per record, per sample (row) and per sample per
channel, the binaries side by side.
Usage: tools/bench_record_memory.py [--sizes 1,5,20] [--scratch DIR] [--keep] BIN [BIN ...]
  (sizes in millions of samples; e.g. /work/bin/shpb-main-new build/shpb)
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

C0 = math.sqrt(200e9 / 8080)  # steel C350 bar wave speed, m/s
DT = 1e-7  # 10 MS/s
T0 = 10e-3  # pre-trigger before the incident pulse
LENGTH = 120e-6
BLOCK = 1_000_000  # rows formatted at a time


def trapezoid(t, t0, length, a, rise=10e-6):
    s = t - t0
    out = a * np.minimum(np.minimum(1.0, s / rise), (length - s) / rise)
    return np.where((s > 0) & (s < length), out, 0.0)


def signals(first, n):
    """Time, incident and transmitted strain of rows [first, first + n)."""
    i = np.arange(first, first + n, dtype=np.float64)
    t = i * DT
    rng = np.random.default_rng(first)
    inc = trapezoid(t, T0, LENGTH, -1e-3) + trapezoid(t, T0 + 2 / C0, LENGTH, 6e-4)
    tra = trapezoid(t, T0 + 2 / C0 + 2e-6, LENGTH, -4e-4)
    return t, inc + rng.uniform(-1e-6, 1e-6, n), tra + rng.uniform(-1e-6, 1e-6, n)


def write_blocks(path, n, header, row):
    with open(path, "w") as f:
        f.write(header)
        for first in range(0, n, BLOCK):
            m = min(BLOCK, n - first)
            f.write("".join(row(first, *signals(first, m))))


SCENE = {
    "name": "deep-memory record of a classic test (benchmark)",
    "bars": [
        {"name": "striker", "material": "steel-c350", "length": "300 mm",
         "diameter": "19.05 mm", "velocity": "15 m/s"},
        {"name": "incident", "material": "steel-c350", "length": "2 m", "diameter": "19.05 mm",
         "gauges": [{"name": "incident", "position": "1 m"}]},
        {"name": "specimen", "material": "aluminium", "length": "5 mm", "diameter": "10 mm"},
        {"name": "transmitter", "material": "steel-c350", "length": "2 m",
         "diameter": "19.05 mm", "gauges": [{"name": "transmitted", "position": "1 m"}]},
    ],
    "specimen": "specimen",
    "materials": {
        "steel-c350": {"model": "elastic", "density": "8080 kg/m3", "youngs_modulus": "200 GPa",
                       "poisson_ratio": 0.29, "source": "nominal bar values"},
        "aluminium": {"model": "elastic", "density": "2700 kg/m3", "youngs_modulus": "69 GPa",
                      "poisson_ratio": 0.33, "source": "nominal"},
    },
    "simulation": {"duration": "800 us", "sample_rate": "10 MHz"},
}


def write_record(folder, kind, n):
    os.makedirs(folder, exist_ok=True)
    if kind == "csv":
        write_blocks(f"{folder}/record.csv", n, "time_s,incident_V,transmitted_V\n",
                     lambda first, t, a, b: ("%.7e,%.6e,%.6e\n" % r for r in zip(t, a, b)))
        measurement = {"file": "record.csv", "format": "csv",
                       "time": {"column": "time_s", "unit": "s"},
                       "channels": [{"gauge": "incident", "column": "incident_V", "unit": "strain"},
                                    {"gauge": "transmitted", "column": "transmitted_V",
                                     "unit": "strain"}]}
    elif kind == "no-time":
        write_blocks(f"{folder}/record.csv", n, "incident,transmitted\n",
                     lambda first, t, a, b: ("%.6e,%.6e\n" % r for r in zip(a, b)))
        measurement = {"file": "record.csv", "format": "csv", "time": {"interval": "0.1 us"},
                       "channels": [{"gauge": "incident", "column": "incident", "unit": "strain"},
                                    {"gauge": "transmitted", "column": "transmitted",
                                     "unit": "strain"}]}
    else:  # tektronix: one file per channel, its header in the first rows' columns 1-3
        meta = [f'"Record Length",{n},"Points"', f'"Sample Interval",{DT:.8e},s',
                '"Trigger Point",0,"Samples"', '"Trigger Time",0.0,s', '"",,',
                '"Horizontal Offset",0.0,s']
        for k, name in ((1, "incident"), (2, "transmitted")):
            def row(first, t, a, b, k=k):
                v = a if k == 1 else b
                return (f"{meta[first + j] if first + j < len(meta) else ',,'},"
                        f"{t[j]:.8e},{v[j]:.8e}\n" for j in range(len(t)))
            write_blocks(f"{folder}/ch{k}.csv", n, "", row)
        measurement = {"format": "tektronix",
                       "channels": [{"gauge": g, "file": f"ch{k}.csv", "column": 4,
                                     "unit": "strain"}
                                    for k, g in ((1, "incident"), (2, "transmitted"))]}
    scene = dict(SCENE, measurement=dict(measurement, dispersion={"correction": "none"}))
    with open(f"{folder}/scene.json", "w") as f:
        json.dump(scene, f, indent=1)


def run(binary, folder, out):
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run(["/usr/bin/time", "-v", binary, "process", f"{folder}/scene.json",
                        "-o", out, "--quiet"], capture_output=True, text=True)
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", p.stderr)
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    seconds = (int(wall[1] or 0) * 3600 + int(wall[2]) * 60 + float(wall[3])) if wall else math.nan
    shutil.rmtree(out, ignore_errors=True)
    if p.returncode != 0:
        last = [l for l in p.stderr.splitlines() if "Command" not in l][:1]
        print(f"    {binary}: exit {p.returncode}: {last}", file=sys.stderr)
    return p.returncode, seconds, int(rss[1]) * 1024 if rss else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+")
    ap.add_argument("--sizes", default="1,5,20", help="millions of samples, comma separated")
    ap.add_argument("--formats", default="csv,no-time,tektronix")
    ap.add_argument("--scratch", default=None)
    ap.add_argument("--keep", action="store_true", help="keep the records written")
    args = ap.parse_args()
    scratch = args.scratch or tempfile.mkdtemp(prefix="bench_record_memory_")
    channels = 2
    print(f"shpb process of deep-memory records ({channels} gauge channels, 10 MS/s), "
          f"peak RSS and wall time; records under {scratch}")
    print(f"{'format':10} {'samples':>8} {'MB file':>8}  "
          + "  ".join(f"{os.path.basename(os.path.dirname(os.path.abspath(b))) + '/' + os.path.basename(b):>34}"
                      for b in args.binaries))
    print(f"{'':10} {'':>8} {'':>8}  "
          + "  ".join(f"{'wall s':>7} {'peak MB':>8} {'B/sample':>8} {'B/s/ch':>7}"
                      for _ in args.binaries))
    for kind in args.formats.split(","):
        for size in args.sizes.split(","):
            n = int(float(size) * 1e6)
            folder = f"{scratch}/{kind}-{size}M"
            write_record(folder, kind, n)
            mb = sum(os.path.getsize(f"{folder}/{f}") for f in os.listdir(folder)
                     if f.endswith(".csv")) / 1e6
            cells = []
            for b in args.binaries:
                rc, wall, rss = run(b, folder, f"{scratch}/out")
                cells.append(f"{wall:7.2f} {rss / 1e6:8.0f} {rss / n:8.1f} "
                             f"{rss / n / channels:7.1f}" + ("" if rc == 0 else f" (exit {rc})"))
            print(f"{kind:10} {n / 1e6:7.0f}M {mb:8.0f}  " + "  ".join(cells), flush=True)
            if not args.keep:
                shutil.rmtree(folder)
    if not args.keep and not args.scratch:
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()

"""Benchmark of the Python module (figures, never assertions; tools/bench.sh runs it):
 1. a loop of 100 simulations of the classic experiment from Python: wall time per run against
    the executable's own solve time (summary.json wall_time_s of `shpb simulate`, median);
 2. two simulations in two Python threads against the same two one after the other (the GIL is
    released during a simulation): the ratio of the wall times, median of several repetitions.
Usage: PYTHONPATH=build/python python3 tools/bench_python.py [build-dir] [runs]"""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import shpb

build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 100
scene_file = pathlib.Path(__file__).resolve().parents[1] / "experiments/classic-al6061/scene.json"
scene = shpb.Scene.load(scene_file)

# 1. The executable's solve time, then the loop from Python.
exe_solve = []
with tempfile.TemporaryDirectory() as tmp:
    for i in range(9):
        subprocess.run([build / "shpb", "simulate", scene_file, "-o", f"{tmp}/run", "--quiet"],
                       check=True)
        exe_solve.append(json.loads(pathlib.Path(f"{tmp}/run/summary.json").read_text())
                         ["wall_time_s"])
shpb.simulate(scene)  # warm: first-touch of the library's pages
start = time.perf_counter()
solve = []
for _ in range(runs):
    solve.append(shpb.simulate(scene).wall_time_s)
loop = (time.perf_counter() - start) / runs
exe = statistics.median(exe_solve)
print(f"== {runs} classic simulations from Python")
print(f"  per run from Python {loop * 1e3:.2f} ms (its solve {statistics.median(solve) * 1e3:.2f} ms);"
      f" executable's solve (summary.json, median of 9) {exe * 1e3:.2f} ms;"
      f" Python / executable {loop / exe:.3f}")

# 2. Two simulations: one after the other, then in two threads.
def serial():
    shpb.simulate(scene)
    shpb.simulate(scene)


def threaded():
    ts = [threading.Thread(target=shpb.simulate, args=(scene,)) for _ in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()


ratios = []
for _ in range(7):
    t0 = time.perf_counter(); serial(); t1 = time.perf_counter(); threaded(); t2 = time.perf_counter()
    ratios.append((t2 - t1) / (t1 - t0))
print("== two classic simulations in two Python threads against one after the other")
print(f"  threads / serial: median {statistics.median(ratios):.3f} (of 7: "
      f"{', '.join(f'{r:.2f}' for r in sorted(ratios))}; {os.cpu_count()} cores)")

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
start, cpu_start = time.perf_counter(), time.process_time()
solve = []
for _ in range(runs):
    solve.append(shpb.simulate(scene).wall_time_s)
loop = (time.perf_counter() - start) / runs
loop_cpu = (time.process_time() - cpu_start) / runs
exe = statistics.median(exe_solve)
print(f"== {runs} classic simulations from Python")
print(f"  wall per run from Python {loop * 1e3:.2f} ms (its solve {statistics.median(solve) * 1e3:.2f}"
      f" ms); executable's solve (summary.json, median of 9) {exe * 1e3:.2f} ms;"
      f" Python / executable {loop / exe:.3f}")
bench = subprocess.run([build / "bench_simulator", "--repeat", "9", "--asynchronous-only",
                        scene_file], capture_output=True, text=True)
cpu = [w for w in bench.stdout.split(",") if "ms CPU" in w]
if bench.returncode == 0 and cpu:
    exe_cpu = float(cpu[0].split("ms CPU")[0].split()[-1]) / 1e3
    print(f"  CPU per run from Python {loop_cpu * 1e3:.2f} ms; bench_simulator's simulate() "
          f"{exe_cpu * 1e3:.2f} ms CPU (median of 9); Python / library {loop_cpu / exe_cpu:.3f}")

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


ratios, busy = [], []
for _ in range(7):
    t0 = time.perf_counter()
    serial()
    t1, c1 = time.perf_counter(), time.process_time()
    threaded()
    t2, c2 = time.perf_counter(), time.process_time()
    ratios.append((t2 - t1) / (t1 - t0))
    busy.append((c2 - c1) / (t2 - t1))  # above 1: both threads computed at the same time
print("== two classic simulations in two Python threads against one after the other")
print(f"  threads / serial wall: median {statistics.median(ratios):.3f} (of 7: "
      f"{', '.join(f'{r:.2f}' for r in sorted(ratios))}); cores busy during the threaded runs "
      f"(CPU / wall): median {statistics.median(busy):.2f}; {os.cpu_count()} cores, load "
      f"average {os.getloadavg()[0]:.1f}")

"""Benchmark of the Python module (figures, never assertions; tools/bench.sh runs it):
 1. a loop of 100 simulations of the classic experiment from Python, in rounds interleaved with
    runs of `shpb simulate`: wall time per run against the executable's solve (summary.json
    wall_time_s) in the same round, against its own runs' solve, and against its own runs' whole
    run (run_time_s: mesh choice, set-up, solve, records), medians over the rounds;
 2. two simulations in two Python threads against the same two one after the other (the GIL is
    released during a simulation): the ratio of the wall times, median of 15 repetitions, on a
    pool of two threads that has run before (concurrent.futures, as a notebook's sweep uses
    threads), and on two threads started afresh each time (each pays for its new malloc arena's
    first page faults, a few ms against a 10 ms run).
Usage: PYTHONPATH=build/python python3 tools/bench_python.py [build-dir] [runs]"""
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
import time

import shpb

build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 100
scene_file = pathlib.Path(__file__).resolve().parents[1] / "experiments/classic-al6061/scene.json"
scene = shpb.Scene.load(scene_file)

# 1. The executable's own times (summary.json) and the loop from Python, interleaved: the machine's
# speed drifts by tens of % between minutes (a shared VM), so each of 7 rounds runs the executable
# 3 times and `runs` / 7 Python runs, and the ratios are taken within a round. The solve
# (wall_time_s) is only part of a run: before it the error model chooses the meshes
# (mesh_choice_time_s) and the bars and recorders are set up, after it the records and statistics
# are made; run_time_s is all of it, what the library costs per run whoever calls it. A run from
# Python pays the same, so the like-with-like figure is Python's wall per run against run_time_s.
ROUNDS = 7
shpb.simulate(scene)  # warm: first-touch of the library's pages
exe_solve, exe_run, exe_choice, py_solve, py_run = [], [], [], [], []
to_solve, to_own_solve, overhead, walls, cpus = [], [], [], [], []
with tempfile.TemporaryDirectory() as tmp:
    for _ in range(ROUNDS):
        solves = []
        for i in range(3):
            subprocess.run([build / "shpb", "simulate", scene_file, "-o", f"{tmp}/run{i}",
                            "--quiet"], check=True)
            summary = json.loads(pathlib.Path(f"{tmp}/run{i}/summary.json").read_text())
            solves.append(summary["wall_time_s"])
            exe_run.append(summary["run_time_s"])
            exe_choice.append(summary["mesh_choice_time_s"])
        exe_solve += solves
        n = max(1, runs // ROUNDS)
        start, cpu_start = time.perf_counter(), time.process_time()
        own = []
        for _ in range(n):
            summary = shpb.simulate(scene).summary
            py_solve.append(summary["wall_time_s"])
            own.append(summary["run_time_s"])
        wall = (time.perf_counter() - start) / n
        walls.append(wall)
        cpus.append((time.process_time() - cpu_start) / n)
        py_run += own
        to_solve.append(wall / statistics.median(solves))
        to_own_solve.append(wall / statistics.median(py_solve[-n:]))
        overhead.append(wall / statistics.median(own))
med = statistics.median
print(f"== {ROUNDS * max(1, runs // ROUNDS)} classic simulations from Python, in {ROUNDS} rounds "
      f"each beside 3 runs of the executable")
print(f"  executable (summary.json, median of {len(exe_solve)}): solve {med(exe_solve) * 1e3:.2f} "
      f"ms, mesh choice {med(exe_choice) * 1e3:.2f} ms, whole run {med(exe_run) * 1e3:.2f} ms")
print(f"  from Python: wall per run {med(walls) * 1e3:.2f} ms, CPU {med(cpus) * 1e3:.2f} ms (its "
      f"own summaries: solve {med(py_solve) * 1e3:.2f} ms, whole run {med(py_run) * 1e3:.2f} ms)")
print(f"  Python's wall per run / the executable's solve in the same round: median "
      f"{med(to_solve):.3f} (rounds: {', '.join(f'{r:.2f}' for r in to_solve)})")
print(f"  Python's wall per run / its own runs' solve (the same process: free of the executable's "
      f"cold start and of the machine's drift between processes): median {med(to_own_solve):.3f} "
      f"(rounds: {', '.join(f'{r:.2f}' for r in to_own_solve)})")
print(f"  Python's wall / its own runs' run_time_s (the binding's overhead): median "
      f"{med(overhead):.3f} (rounds: {', '.join(f'{r:.2f}' for r in overhead)})")

# 2. Two simulations: one after the other, then in two threads (a warm pool, then fresh threads).
def serial():
    shpb.simulate(scene)
    shpb.simulate(scene)


pool = ThreadPoolExecutor(2)
list(pool.map(lambda _: shpb.simulate(scene), range(4)))  # each pool thread has run once


def pooled():
    list(pool.map(lambda _: shpb.simulate(scene), range(2)))


def fresh_threads():
    ts = [threading.Thread(target=shpb.simulate, args=(scene,)) for _ in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()


print("== two classic simulations in two Python threads against one after the other")
for name, threaded in (("a pool of two threads", pooled), ("two fresh threads", fresh_threads)):
    ratios, busy = [], []
    for _ in range(15):
        t0 = time.perf_counter()
        serial()
        t1, c1 = time.perf_counter(), time.process_time()
        threaded()
        t2, c2 = time.perf_counter(), time.process_time()
        ratios.append((t2 - t1) / (t1 - t0))
        busy.append((c2 - c1) / (t2 - t1))  # above 1: both threads computed at the same time
    print(f"  {name}: threads / serial wall median {statistics.median(ratios):.3f} (of 15: "
          f"{', '.join(f'{r:.2f}' for r in sorted(ratios))}); cores busy (CPU / wall) median "
          f"{statistics.median(busy):.2f}; {os.cpu_count()} cores, load average "
          f"{os.getloadavg()[0]:.1f}")

# 3. The machine's own ceiling for part 2: two processes, each running 10 simulations of the same
# scene, at the same time against one after the other (no GIL, no shared heap: what two cores give
# this workload; on a shared VM's two cores it is not 0.5).
ceiling = []
worker = ("import shpb, sys\ns = shpb.Scene.load(sys.argv[1])\nfor _ in range(10): "
          "shpb.simulate(s)\n")
command = [sys.executable, "-c", worker, str(scene_file)]
for _ in range(5):
    t0 = time.perf_counter()
    for _ in range(2):
        subprocess.run(command, check=True)
    t1 = time.perf_counter()
    both = [subprocess.Popen(command) for _ in range(2)]
    for p in both:
        p.wait()
    t2 = time.perf_counter()
    ceiling.append((t2 - t1) / (t1 - t0))
print(f"  two processes (10 simulations each) at once / one after the other: median "
      f"{statistics.median(ceiling):.3f} (of 5: {', '.join(f'{r:.2f}' for r in sorted(ceiling))}):"
      f" the machine's ceiling for the threads above")

#!/usr/bin/env bash
# Benchmarks (figures, not assertions), all in one run: builds release, then prints
#  1. for every experiments/*/scene.json and the elastic classic scene (the peers' workload,
#     tools/bench_scenes/elastic-classic.json): the simulator's wall time (median of several
#     runs), node updates per second, causal-economy saving, asynchronous against global stepping;
#  2. the dispersion correction (bench_dispersion): the table, a 1 M-sample correction of a
#     10 MS/s pulse moved 1 m on a 20 mm steel bar, plans shared against planned per correction;
#  3. `shpb process` of a 1 M-row CSV (time and two gauge columns, correction on) as a whole
#     process, reading included: wall, CPU and peak memory; and the LANL copper test's Monte
#     Carlo uncertainty, 1000 draws on 2 threads against 2 draws;
#  4. the full pareto study of the classic experiment on 2 threads, and its Monte Carlo sweep of
#     200 draws in process against 4 GNU parallel shards merged (skipped with BENCH_STUDY=0);
#  5. --tolerance 1 % on the experiments (skipped with BENCH_TOLERANCE=0), and every
#     experiment's default run before (the automatic meshes) and now (the default tolerance, 3.5 %):
#     median solve time (summary.json wall_time_s) and gauge error against the study's reference;
#  6. tools/bench_contact.py (skipped with BENCH_CONTACT=0): every experiment's energy error at
#     --tolerance 0.5-10 % and --courant 0.995-1, and the specimen faces' closings after unloading
#     (rigid and finite links, asynchronous and global);
#  7. the Python module (tools/bench_python.py, when it is built): a loop of 100 classic runs
#     against the executable's solve time, two runs in two Python threads against serial;
#  8. `shpb plan` (tools/bench_plan.sh, skipped with BENCH_PLAN=0): the classic bars planned for
#     1000, 2500 and 5000 1/s with and without a pulse shaper, each re-simulated at 0.5 %;
#  9. the fit's intervals on the classic-bar copper campaign against its truth (skipped with
#     BENCH_FIT_OFHC=0);
# 10. with BENCH_FIT_COVERAGE=1 only (about an hour): the coverage of the fit's 95 % intervals
#     over 100 synthetic campaigns (tools/fit_interval_coverage).
# Usage: tools/bench.sh [build-dir] [repetitions]
set -euo pipefail
BUILD=${1:-build}
REPEAT=${2:-7}
cd "$(dirname "$0")/.."
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j 2 --target shpb bench_simulator bench_dispersion >/dev/null
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

# Wall, user+system CPU and peak resident memory of one command (GNU time when installed).
timed() {
  if [ -x /usr/bin/time ]; then
    /usr/bin/time -f "  wall %e s, CPU %U s user + %S s system, peak memory %M KB" "$@"
  else
    local t0=$SECONDS
    "$@"
    echo "  wall $((SECONDS - t0)) s"
  fi
}

echo "== simulator: experiments and the elastic classic scene"
"$BUILD"/bench_simulator --repeat "$REPEAT" experiments/*/scene.json \
  tools/bench_scenes/elastic-classic.json

echo
echo "== dispersion correction"
"$BUILD"/bench_dispersion

echo
echo "== shpb process of a 1 M-row CSV (time + 2 gauges, Pochhammer-Chree correction on)"
"$BUILD"/bench_dispersion --write-record "$WORK/record"
ls -l "$WORK/record/record.csv" | awk '{printf "  record.csv: %.1f MB\n", $5 / 1e6}'
for i in 1 2 3; do
  timed "$BUILD"/shpb process "$WORK/record/scene.json" -o "$WORK/process-$i" --quiet
done

echo
echo "== Monte Carlo uncertainty of the LANL copper test (measurement.uncertainty), 2 threads:"
echo "   1000 draws against 2 (the reading, the nominal reduction and the outputs alone)"
for draws in 2 1000; do
  echo "  --draws $draws"
  timed "$BUILD"/shpb process experiments/lanl-cu-ofe-273k/scene.json -o "$WORK/mc-$draws" \
    --draws "$draws" --threads 2 --quiet
done

if [ "${BENCH_STUDY:-1}" != 0 ]; then
  echo
  echo "== full pareto study of the classic experiment, 2 threads"
  timed "$BUILD"/shpb study experiments/classic-al6061/scene.json -o "$WORK/study" \
    --threads 2 --quiet
  grep -m1 '"reference"' "$WORK/study/summary.json" || true
  echo
  echo "== Monte Carlo sweep of the classic experiment, 200 draws (its distributions.json):"
  echo "   in process on 2 threads, then planned, 4 shards by GNU parallel (-j 2) and merged"
  mc=(experiments/classic-al6061/scene.json --sweep monte-carlo --draws 200
      --distributions experiments/classic-al6061/distributions.json)
  timed "$BUILD"/shpb study "${mc[@]}" -o "$WORK/mc-whole" --threads 2 --quiet
  if command -v parallel >/dev/null; then
    "$BUILD"/shpb study "${mc[@]}" --plan "$WORK/mc-plan" --quiet
    SHPB="$BUILD"/shpb timed tools/cluster/parallel.sh 4 study "$WORK/mc-plan" -j 2
    for f in draws.csv gauge_bands.csv curve_bands.csv; do
      if cmp -s "$WORK/mc-whole/$f" "$WORK/mc-plan/result/$f"; then
        echo "  $f: sharded = in process (byte for byte)"
      else
        echo "  $f: DIFFERS between the sharded and the in-process sweep"
      fi
    done
  else
    echo "  (GNU parallel not installed: the sharded run is skipped)"
  fi
fi

# 5. --tolerance 1%: the automatic meshes against the meshes the gauge-error model chooses
#    (model/mesh_choice.hpp): node updates, solve time, recorded error measured against the
#    study's reference and predicted (skipped with BENCH_TOLERANCE=0).
if [ "${BENCH_TOLERANCE:-1}" != 0 ]; then
  echo
  echo "== --tolerance 1%: cost and error against the automatic meshes"
  cmake --build "$BUILD" -j 2 --target calibrate_tolerance >/dev/null
  "$BUILD"/calibrate_tolerance --check 0.01 experiments/classic-al6061/scene.json \
    experiments/lanl-cu-ofe-273k/scene.json experiments/lanl-pmma13-mini-kolsky/scene.json \
    experiments/striker-on-bar/scene.json experiments/pulse-shaper/scene.json \
    experiments/tension-bonded/scene.json
  echo
  echo "== the default run: automatic meshes (before) against the default tolerance (now)"
  "$BUILD"/bench_simulator --repeat "$REPEAT" --defaults experiments/*/scene.json
fi

# 6. Energy near C = 1 and the specimen faces' closings after unloading (docs/methods.md §3.7).
if [ "${BENCH_CONTACT:-1}" != 0 ]; then
  echo
  /usr/bin/python3 tools/bench_contact.py "$BUILD"/shpb
fi

if [ -f "$BUILD"/python/shpb/__init__.py ]; then
  cmake --build "$BUILD" -j 2 --target bench_simulator shpb_python shpb_python_help >/dev/null
  echo
  PYTHONPATH="$BUILD"/python /usr/bin/python3 tools/bench_python.py "$BUILD"
fi

# 8. shpb plan: wall time per plan and the planned scenes re-simulated on their own.
if [ "${BENCH_PLAN:-1}" != 0 ]; then
  echo
  echo "== shpb plan: classic bars, 1000/2500/5000 1/s, with and without a shaper"
  tools/bench_plan.sh "$BUILD" 2
fi

# 9. The classic-bar copper campaign (three OFHC copper tests at 8, 15 and 26 m/s on the classic
#    bars, 1 % white noise, A, B, n, C started 20 % off, seed 2024, 20 bootstrap refits; about 100 s
#    of CPU): each reported 95 % interval must hold the truth (skipped with BENCH_FIT_OFHC=0).
if [ "${BENCH_FIT_OFHC:-1}" != 0 ]; then
  cmake --build "$BUILD" -j 2 --target fit_interval_coverage shpb >/dev/null
  echo
  echo "== fit intervals on the classic-bar copper campaign (20 bootstrap refits)"
  "$BUILD"/fit_interval_coverage --ofhc-classic --campaigns 1 --first 2024 --bootstrap 20 --threads 2
fi

# 10. Coverage of the fit's 95 % intervals over 100 synthetic campaigns (tools/fit_interval_coverage:
#    two materials, two noise levels, white and coloured noise, 30 bootstrap refits each; about an
#    hour on 2 cores): only with BENCH_FIT_COVERAGE=1. BENCH_FIT_COVERAGE_CAMPAIGNS=N runs fewer,
#    BENCH_FIT_COVERAGE_NOISE=white|coloured only the campaigns of that noise.
if [ "${BENCH_FIT_COVERAGE:-0}" != 0 ]; then
  cmake --build "$BUILD" -j 2 --target fit_interval_coverage shpb >/dev/null
  campaigns="${BENCH_FIT_COVERAGE_CAMPAIGNS:-100}"
  noise=()
  [ -n "${BENCH_FIT_COVERAGE_NOISE:-}" ] && noise=(--noise "$BENCH_FIT_COVERAGE_NOISE")
  echo
  echo "== fit intervals: coverage over $campaigns synthetic campaigns ${BENCH_FIT_COVERAGE_NOISE:-} (30 bootstrap refits each)"
  "$BUILD"/fit_interval_coverage --campaigns "$campaigns" --bootstrap 30 --threads 2 "${noise[@]}"
fi

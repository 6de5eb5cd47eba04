#!/usr/bin/env bash
# Benchmarks (figures, not assertions): builds release, then prints for every
# experiments/*/scene.json the simulator's wall time (median of several runs), node updates per
# second, causal-economy saving, asynchronous against global stepping, and the dispersion
# correction throughput. Usage: tools/bench.sh [build-dir] [repetitions]
set -euo pipefail
BUILD=${1:-build}
REPEAT=${2:-7}
cd "$(dirname "$0")/.."
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j 2 --target bench_simulator bench_dispersion >/dev/null
"$BUILD"/bench_simulator --repeat "$REPEAT" experiments/*/scene.json
"$BUILD"/bench_dispersion

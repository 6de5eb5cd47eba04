#!/usr/bin/env bash
# `make run`: validates the default experiment, simulates it, reduces the simulated gauges to the
# specimen's stress–strain curve, and writes the figures and report.html of both.
set -euo pipefail
shpb=$1; experiment=$2; results=$3
name=$(basename "$experiment")
out="$results/$name"
"$shpb" validate "$experiment/scene.json"
mkdir -p "$out"
"$shpb" simulate "$experiment/scene.json" -o "$out/simulate"
"$shpb" process "$experiment/scene.json" -o "$out/process" --signals "$out/simulate/gauges.csv"
"$shpb" report "$out"
echo "make run: simulation in $out/simulate, stress-strain curve in $out/process,"
echo "          report in $(cd "$out" && pwd)/report.html (figures in $out/figures)"

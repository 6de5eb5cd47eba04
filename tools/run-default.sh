#!/usr/bin/env bash
# `make run`: validates the default experiment, simulates it, and reduces the simulated gauges
# to the specimen's stress–strain curve.
set -euo pipefail
shpb=$1; experiment=$2; results=$3
name=$(basename "$experiment")
"$shpb" validate "$experiment/scene.json"
mkdir -p "$results"
"$shpb" simulate "$experiment/scene.json" -o "$results/$name"
"$shpb" process "$experiment/scene.json" -o "$results/$name-curve" --signals "$results/$name/gauges.csv"
echo "make run: simulation in $results/$name, stress-strain curve in $results/$name-curve"

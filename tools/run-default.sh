#!/usr/bin/env bash
# `make run`: validates and (once the simulator exists) runs the default experiment.
set -euo pipefail
shpb=$1; experiment=$2; results=$3
"$shpb" validate "$experiment/scene.json"

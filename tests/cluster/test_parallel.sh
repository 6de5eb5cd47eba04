#!/usr/bin/env bash
# GNU parallel runs the shards of a pareto sweep (plan, 4 shards, merge): the merged pareto.csv
# equals the in-process sweep's apart from the wall-time column; a shard killed outright leaves no
# part; a merge with a part missing names it and exits 2. The sweep is the striker-on-bar
# experiment's (30 runs, exact reference, a second); SHPB_CLUSTER_ACCEPTANCE=1 runs the classic
# experiment's instead (about a minute on 2 cores). Exit 77: skipped.
set -euo pipefail
shpb=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
command -v parallel >/dev/null ||
  { echo "SKIP: GNU parallel is not installed (Debian: apt-get install parallel)"; exit 77; }
scene=$root/experiments/striker-on-bar/scene.json
[ "${SHPB_CLUSTER_ACCEPTANCE:-0}" = 1 ] && scene=$root/experiments/classic-al6061/scene.json
tmp=$(mktemp -d "${TMPDIR:-/tmp}/shpb_test_parallel.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 143' TERM INT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$shpb" study "$scene" --plan "$tmp/plan" --quiet
# Killed outright mid-run: no part, no temporary file left to be mistaken for one. The classic
# experiment's shard runs for seconds, so the kill lands while it computes.
"$shpb" study "$root/experiments/classic-al6061/scene.json" --plan "$tmp/slow" --quiet
timeout -s KILL 0.3 "$shpb" study --run "$tmp/slow" --shard 0/4 --threads 1 --quiet || true
[ -z "$(ls -A "$tmp/slow/parts")" ] || fail "a killed shard left $(ls -A "$tmp/slow/parts")"

SHPB=$shpb bash "$root/tools/cluster/parallel.sh" 4 study "$tmp/plan" -j 2
"$shpb" study "$scene" -o "$tmp/whole" --threads 2 --quiet

# Every column but wall_time_s (the 5th) and the front by wall time (the 8th) identical.
strip() { cut -d, -f1-4,6-7,9- "$1"; }
cmp <(strip "$tmp/whole/pareto.csv") <(strip "$tmp/plan/result/pareto.csv") ||
  fail "merged pareto.csv differs from the in-process sweep"
[ "$(wc -l <"$tmp/whole/pareto.csv")" -gt 1 ] || fail "empty pareto.csv"

# A missing part is named, exit 2, and the previous result stays.
rm "$tmp/plan/parts/2-of-4.json"
set +e
err=$("$shpb" study --merge "$tmp/plan" -o "$tmp/again" 2>&1)
code=$?
set -e
[ $code -eq 2 ] || fail "merge with a missing part: exit $code, expected 2 ($err)"
[[ $err == *"missing part 2-of-4"* ]] || fail "merge does not name the missing part: $err"
[ ! -e "$tmp/again" ] || fail "a failed merge wrote $tmp/again"
echo "ok: 4 shards by GNU parallel equal the in-process pareto sweep of $(basename "$(dirname "$scene")")"

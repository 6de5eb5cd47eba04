#!/usr/bin/env bash
# Slurm runs a stability sweep as an 8-task job array on a one-node cluster started here
# (tools/cluster/local-slurm.sh), then the merge as a dependent job: stability.csv and
# stability_boundary.csv equal the in-process sweep's byte for byte. Then one task of a second
# array is killed: the dependent merge is cancelled, a merge by hand names the missing part, and
# the task resubmitted alone completes the set. The cluster stops exactly the daemons it started
# and its folder is removed, whatever happens. The sweep: the stability map of plain penalty at
# refine 2 (about 4 x the grid points, seconds); SHPB_CLUSTER_ACCEPTANCE=1 runs the whole map at
# refine 2 instead (all methods, minutes on 2 cores). Then submit.sh's own contract: a second
# submission into a plan keeps the first's logs; a logs folder of the user's is refused, nothing
# queued; an OUT_DIR that is a link to nothing is not created; stopped by SIGTERM while it queues
# the merge, it leaves no job to run. local-slurm.sh start stopped by SIGTERM once its daemons run
# stops them and removes its folder. Exit 77: skipped (not root, no packages).
set -euo pipefail
shpb=$(realpath "$1")
root=$(cd "$(dirname "$0")/../.." && pwd)
sweep=(--sweep stability --refine 2 --contact penalty)
[ "${SHPB_CLUSTER_ACCEPTANCE:-0}" = 1 ] && sweep=(--sweep stability --refine 2)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/shpb_test_slurm.XXXXXX")
cluster=$tmp/cluster
cleanup() {
  local c
  for c in "$cluster" "$tmp/cluster2"; do
    [ -f "$c/slurm.conf" ] && bash "$root/tools/cluster/local-slurm.sh" stop "$c"
  done
  rm -rf "$tmp"
}
trap cleanup EXIT
trap "exit 143" TERM INT  # the EXIT trap then stops the cluster
fail() { echo "FAIL: $*" >&2; exit 1; }

set +e
bash "$root/tools/cluster/local-slurm.sh" start "$cluster" >/dev/null
code=$?
set -e
[ $code -eq 77 ] && exit 77
[ $code -eq 0 ] || fail "the local cluster did not start"
export SLURM_CONF=$cluster/slurm.conf SHPB=$shpb

# Waits until none of the given jobs (array jobs with their tasks) is in the queue.
wait_jobs() {
  local jobs=$1
  for _ in $(seq 6000); do
    [ -z "$(squeue -h -j "$jobs" 2>/dev/null)" ] && return 0
    sleep 0.1
  done
  fail "jobs $jobs still queued after 10 min: $(squeue -j "$jobs")"
}

scene=$root/experiments/classic-al6061/scene.json
"$shpb" study "$scene" --plan "$tmp/plan" "${sweep[@]}" --quiet
read -r array merge < <(bash "$root/tools/cluster/submit.sh" 8 study "$tmp/plan")
first=("$array" "$merge")
"$shpb" study "$scene" -o "$tmp/whole" "${sweep[@]}" --threads 1 --quiet
wait_jobs "$array,$merge"
[ -f "$tmp/plan/result/stability.csv" ] ||
  fail "no merged result; merge log: $(cat "$tmp/plan/logs/merge-$merge.out" 2>/dev/null)"
[ "$(ls "$tmp/plan/parts" | wc -l)" -eq 8 ] || fail "expected 8 parts: $(ls "$tmp/plan/parts")"
for f in stability.csv stability_boundary.csv; do
  cmp "$tmp/whole/$f" "$tmp/plan/result/$f" || fail "merged $f differs from the in-process sweep"
done

# A second plan; task 3 is cancelled before it runs (the array is held until then).
"$shpb" study "$scene" --plan "$tmp/plan2" "${sweep[@]}" --quiet
read -r array merge < <(bash "$root/tools/cluster/submit.sh" 8 study "$tmp/plan2" --hold)
scancel "${array}_3"
scontrol release "$array"
scontrol release "$merge" 2>/dev/null || true
wait_jobs "$array,$merge"
[ ! -e "$tmp/plan2/result" ] || fail "the merge ran although task 3 was killed"
[ ! -e "$tmp/plan2/parts/3-of-8.json" ] || fail "the killed task left its part"
set +e
err=$("$shpb" study --merge "$tmp/plan2" 2>&1)
code=$?
set -e
[ $code -eq 2 ] && [[ $err == *"missing part 3-of-8"* ]] ||
  fail "merge without task 3: exit $code, $err"
# Task 3 alone, then the merge after it.
task=$(sbatch --parsable --array=3 --output="$tmp/plan2/logs/shard-%a.again.out" \
  "$root/tools/cluster/shard.sbatch" 8 study --run "$tmp/plan2")
merge=$(sbatch --parsable --dependency="afterok:$task" --kill-on-invalid-dep=yes \
  --output="$tmp/plan2/logs/merge.again.out" "$root/tools/cluster/merge.sbatch" study --merge "$tmp/plan2")
wait_jobs "$task,$merge"
cmp "$tmp/whole/stability.csv" "$tmp/plan2/result/stability.csv" ||
  fail "the set completed by the resubmitted task differs from the in-process sweep"

# A second submission into the same plan: its shards skip the parts, its merge writes the same
# result, and the first submission's logs are kept beside its own (they were replaced).
read -r array2 merge2 < <(bash "$root/tools/cluster/submit.sh" 8 study "$tmp/plan")
wait_jobs "$array2,$merge2"
[ -f "$tmp/plan/logs/shard-${first[0]}_0.out" ] ||
  fail "the first submission's shard log was not kept: $(ls "$tmp/plan/logs")"
[ -f "$tmp/plan/logs/merge-${first[1]}.out" ] && [ -f "$tmp/plan/logs/merge-$merge2.out" ] ||
  fail "both merges' logs expected: $(ls "$tmp/plan/logs")"
cmp "$tmp/whole/stability.csv" "$tmp/plan/result/stability.csv" ||
  fail "the second merge changed the result"

# OUT_DIR.logs holding the user's file: refused (exit 2), the file kept, nothing queued.
campaign=$root/experiments/measured-campaign.json
mkdir "$tmp/out.logs"
echo "my notes" >"$tmp/out.logs/merge.out"
set +e
err=$(bash "$root/tools/cluster/submit.sh" 2 process "$campaign" "$tmp/out" 2>&1 >/dev/null)
code=$?
set -e
[ $code -eq 2 ] && [[ $err == *"did not write"* ]] || fail "a user's logs folder: exit $code, $err"
[ "$(cat "$tmp/out.logs/merge.out")" = "my notes" ] || fail "the user's merge.out was replaced"
[ -z "$(squeue -h)" ] || fail "jobs queued into a refused output: $(squeue)"

# OUT_DIR a symbolic link to nothing: shpb refuses it, the scripts do not create its target.
ln -s "$tmp/nowhere/out" "$tmp/dangling"
read -r array merge < <(bash "$root/tools/cluster/submit.sh" 2 process "$campaign" "$tmp/dangling")
wait_jobs "$array,$merge"
[ ! -e "$tmp/nowhere" ] || fail "the target of a dangling -o link was created"

# SIGTERM to submit.sh while it queues the merge (an sbatch slowed down here, the array already
# queued): it cancels what it queued, the merge is cancelled with it; nothing runs, no part.
mkdir "$tmp/bin"
cat >"$tmp/bin/sbatch" <<SBATCH
#!/usr/bin/env bash
[[ "\$*" == *--dependency=* ]] || exec "$(command -v sbatch)" "\$@"
touch "$tmp/merge-queuing"
sleep 2
"$(command -v sbatch)" "\$@"
touch "$tmp/merge-queued"
SBATCH
chmod +x "$tmp/bin/sbatch"
"$shpb" study "$scene" --plan "$tmp/plan3" "${sweep[@]}" --quiet
PATH=$tmp/bin:$PATH bash "$root/tools/cluster/submit.sh" 2 study "$tmp/plan3" >/dev/null &
submit=$!
for _ in $(seq 600); do [ -e "$tmp/merge-queuing" ] && break; sleep 0.05; done
kill -TERM $submit
set +e
wait $submit
code=$?
set -e
[ $code -eq 143 ] || fail "submit.sh stopped by SIGTERM: exit $code"
# The sbatch it was waiting for queues the merge after it; Slurm cancels it, its array gone.
for _ in $(seq 600); do [ -e "$tmp/merge-queued" ] && break; sleep 0.05; done
for _ in $(seq 300); do [ -z "$(squeue -h)" ] && break; sleep 0.1; done
[ -z "$(squeue -h)" ] || fail "jobs left by a stopped submit.sh: $(squeue)"
[ -z "$(ls -A "$tmp/plan3/parts")" ] || fail "a stopped submission ran shards: $(ls "$tmp/plan3/parts")"
# A second cluster's start stopped by SIGTERM once its three daemons run, while it waits for the
# node (a sinfo that never says idle, here): no daemon of it left running, no folder.
cat >"$tmp/bin/sinfo" <<SINFO
#!/usr/bin/env bash
touch "$tmp/waiting-for-node"
echo down
SINFO
chmod +x "$tmp/bin/sinfo"
PATH=$tmp/bin:$PATH bash "$root/tools/cluster/local-slurm.sh" start "$tmp/cluster2" >/dev/null &
starting=$!
for _ in $(seq 600); do [ -e "$tmp/waiting-for-node" ] && break; sleep 0.05; done
[ -e "$tmp/waiting-for-node" ] || fail "the second cluster did not start its daemons"
kill -TERM $starting
set +e
wait $starting
code=$?
set -e
[ $code -eq 143 ] || fail "local-slurm.sh start stopped by SIGTERM: exit $code"
[ -z "$(pgrep -af "$tmp/cluster2")" ] || fail "daemons left running: $(pgrep -af "$tmp/cluster2")"
[ ! -e "$tmp/cluster2" ] || fail "the stopped cluster's folder was left: $(ls -A "$tmp/cluster2")"
echo "ok: an 8-task Slurm array and its merge equal the in-process stability sweep; a killed task resubmitted completes the set; submit.sh keeps logs, refuses a user's logs folder and a dangling link's target, and leaves nothing when stopped; a stopped cluster start leaves no daemon"

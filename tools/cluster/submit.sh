#!/usr/bin/env bash
# Submits an shpb plan to Slurm: a job array of N shards, then the merge once all succeeded.
#   tools/cluster/submit.sh N study PLAN_DIR [sbatch options...]
#       shards: shpb study --run PLAN_DIR --shard K/N --threads $SLURM_CPUS_PER_TASK
#       merge:  shpb study --merge PLAN_DIR            (writes PLAN_DIR/result)
#   tools/cluster/submit.sh N process CAMPAIGN.json OUT_DIR [sbatch options...]
#       shards: shpb process --campaign CAMPAIGN.json -o OUT_DIR --shard K/N
#       merge:  shpb process --campaign CAMPAIGN.json -o OUT_DIR --merge
# sbatch options (e.g. --partition=short --time=1:00:00 --cpus-per-task=4) go to both jobs.
# Prints "<array job id> <merge job id>". SHPB (default: shpb on PATH) must be the same build on
# every node, and the folders must be on a file system every node sees at the same path.
# The jobs' logs go to PLAN_DIR/logs (OUT_DIR.logs), named by job id (shard-<array>_<K>.out,
# merge-<job>.out), so a second submission keeps the first's; a logs folder is used only if it is
# new, empty or one this script made (its marker .shpb-logs), never one holding the user's files.
# The array is submitted held and released once the merge is queued; stopped by SIGINT or SIGTERM
# before that, the script cancels what it submitted (the merge then has no array to wait for, and
# Slurm cancels it): both run or neither. Given --hold (-H), it leaves both held for the user.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { echo "usage: $0 N study PLAN_DIR [sbatch options] | N process CAMPAIGN OUT_DIR [sbatch options]" >&2; exit 2; }
[ $# -ge 3 ] || usage
n=$1 kind=$2
[[ $n =~ ^[1-9][0-9]*$ ]] || usage
shift 2
case $kind in
  study)
    dir=$(realpath "$1"); shift
    [ -f "$dir/plan.json" ] || { echo "error: $dir/plan.json: missing (shpb study SCENE --plan DIR first)" >&2; exit 2; }
    logs=$dir/logs
    shard_args=(study --run "$dir")
    merge_args=(study --merge "$dir")
    ;;
  process)
    [ $# -ge 2 ] || usage
    # An OUT_DIR that is a symbolic link stays one: shpb writes through it or refuses a link to
    # nothing (docs/outputs.md), which resolving it here would create.
    campaign=$(realpath "$1") dir=$(realpath -m -s "$2"); shift 2
    logs=$dir.logs
    shard_args=(process --campaign "$campaign" -o "$dir")
    merge_args=(process --campaign "$campaign" -o "$dir" --merge)
    ;;
  *) usage ;;
esac
marker=.shpb-logs
if [ -e "$logs" ] && [ -n "$(ls -A "$logs")" ] && [ ! -f "$logs/$marker" ]; then
  echo "error: $logs: holds files this script did not write (no $marker marker): move them away or choose another output folder" >&2
  exit 2
fi
mkdir -p "$logs"
echo "logs of shpb's cluster jobs (tools/cluster/submit.sh)" >"$logs/$marker"
export SHPB=${SHPB:-$(command -v shpb || echo shpb)}
submitted=()
cancel() {
  [ ${#submitted[@]} -eq 0 ] || scancel "${submitted[@]}" 2>/dev/null || true
  exit "$1"
}
trap 'cancel 130' INT
trap 'cancel 143' TERM
held_by_user=0
for option in "$@"; do [[ $option == --hold || $option == -H ]] && held_by_user=1; done
array=$(sbatch --parsable --hold --array="0-$((n - 1))" --output="$logs/shard-%A_%a.out" "$@" \
  "$here/shard.sbatch" "$n" "${shard_args[@]}")
array=${array%%;*}
submitted+=("$array")
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$logs/merge-%j.out" "$@" "$here/merge.sbatch" "${merge_args[@]}")
merge=${merge%%;*}
submitted+=("$merge")
[ $held_by_user = 1 ] || scontrol release "$array"
trap - INT TERM
echo "$array $merge"

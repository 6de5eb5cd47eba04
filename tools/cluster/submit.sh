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
    campaign=$(realpath "$1") dir=$(realpath -m "$2"); shift 2
    logs=$dir.logs
    shard_args=(process --campaign "$campaign" -o "$dir")
    merge_args=(process --campaign "$campaign" -o "$dir" --merge)
    ;;
  *) usage ;;
esac
mkdir -p "$logs"
export SHPB=${SHPB:-$(command -v shpb || echo shpb)}
array=$(sbatch --parsable --array="0-$((n - 1))" --output="$logs/shard-%a.out" "$@" \
  "$here/shard.sbatch" "$n" "${shard_args[@]}")
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$logs/merge.out" "$@" "$here/merge.sbatch" "${merge_args[@]}")
merge=${merge%%;*}
echo "$array $merge"

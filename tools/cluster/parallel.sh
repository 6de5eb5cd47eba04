#!/usr/bin/env bash
# Runs the shards of an shpb plan with GNU parallel, on this machine or across workstations, then
# merges them (README.md, "On a cluster"):
#   tools/cluster/parallel.sh N study PLAN_DIR [parallel options...]
#   tools/cluster/parallel.sh N process CAMPAIGN.json OUT_DIR [parallel options...]
# e.g. `--sshloginfile hosts.txt` (one line per host, "2/user@host" for 2 jobs there, ":" for this
# machine) or `-j 4`. Remote hosts need the same SHPB (default: shpb on PATH) and see the
# folders at the same paths (a shared file system). Failed shards are retried twice; a shard whose
# part exists is skipped, so running this again completes an interrupted set.
set -euo pipefail
usage() { echo "usage: $0 N study PLAN_DIR [parallel options] | N process CAMPAIGN OUT_DIR [parallel options]" >&2; exit 2; }
[ $# -ge 3 ] || usage
n=$1 kind=$2
[[ $n =~ ^[1-9][0-9]*$ ]] || usage
shift 2
shpb=${SHPB:-$(command -v shpb || echo shpb)}
case $kind in
  study)
    dir=$(realpath "$1"); shift
    shard=(study --run "$dir" --threads 1)
    merge=(study --merge "$dir")
    ;;
  process)
    [ $# -ge 2 ] || usage
    campaign=$(realpath "$1") dir=$(realpath -m -s "$2"); shift 2  # a link stays one (submit.sh)
    shard=(process --campaign "$campaign" -o "$dir")
    merge=(process --campaign "$campaign" -o "$dir" --merge)
    ;;
  *) usage ;;
esac
# One command line for the (possibly remote) shell, every word quoted; {} is the shard index.
command="$(printf '%q ' "$shpb" "${shard[@]}") --shard {}/$n --quiet"
seq 0 $((n - 1)) | parallel --will-cite --retries 3 "$@" "$command"
"$shpb" "${merge[@]}" --quiet

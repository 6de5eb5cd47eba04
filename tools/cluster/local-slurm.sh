#!/usr/bin/env bash
# A one-node Slurm cluster living in one folder, for the tests and for trying the cluster scripts
# on a workstation (README.md, "On a cluster"):
#   tools/cluster/local-slurm.sh start DIR   munged, slurmctld and slurmd as root; configuration,
#                                            key, state, spool, logs and pid files all in DIR;
#                                            ports on the loopback; waits until the node is idle
#   export SLURM_CONF=DIR/slurm.conf         then sbatch, squeue, sinfo talk to it
#   tools/cluster/local-slurm.sh stop DIR    cancels its jobs, sends SIGTERM to exactly the pids in
#                                            DIR's three pid files, waits for them, removes DIR
# Needs root and Debian's slurm-wlm and munge. Exit 77 (skip) when they are not there.
set -euo pipefail

die() { echo "local-slurm: $*" >&2; exit 1; }
skip() { echo "local-slurm: SKIP: $*" >&2; exit 77; }

# The pid in a pid file if it is the daemon named (a pid reused by another program is never
# signalled), else nothing.
daemon_pid() {
  local file=$1 name=$2 pid
  [ -s "$file" ] || return 0
  pid=$(cat "$file")
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] && echo "$pid"
  return 0
}

# The process has ended: gone, or a zombie its parent has not reaped yet (a container whose first
# process reaps nothing keeps one for ever).
ended() {
  local state
  state=$(ps -o stat= -p "$1" 2>/dev/null) || return 0
  [[ $state == Z* ]]
}

# SIGTERM to the daemons' pids, then waits up to 10 s for them to end (SIGKILL after that).
stop_pids() {
  local pid
  [ $# -gt 0 ] || return 0
  kill -TERM "$@" 2>/dev/null || true
  for _ in $(seq 200); do
    for pid in "$@"; do ended "$pid" || break; pid=; done
    [ -z "$pid" ] && return 0
    sleep 0.05
  done
  echo "local-slurm: pids $* ignored SIGTERM for 10 s; sending SIGKILL" >&2
  kill -KILL "$@" 2>/dev/null || true
}

free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

start() {
  local dir=$1
  [ "$(id -u)" -eq 0 ] || skip "not root (munged --force and slurmd need root)"
  for tool in munged slurmctld slurmd sbatch sinfo python3; do
    command -v "$tool" >/dev/null || skip "$tool not installed (Debian: apt-get install slurm-wlm munge)"
  done
  [ ! -e "$dir" ] || [ -z "$(ls -A "$dir")" ] || die "$dir exists and is not empty"
  mkdir -p "$dir"/{state,spool,log}
  dir=$(cd "$dir" && pwd)
  # Stopped before the node is up (Ctrl-C, SIGTERM), it stops the daemons it started so far.
  trap 'abort_start "$dir" 130' INT
  trap 'abort_start "$dir" 143' TERM
  local host ctld_port node_port
  host=$(hostname -s)
  ctld_port=$(free_port)
  node_port=$(free_port)
  while [ "$node_port" = "$ctld_port" ]; do node_port=$(free_port); done
  head -c 1024 /dev/urandom >"$dir/munge.key"
  chmod 600 "$dir/munge.key"
  chmod 700 "$dir"
  cat >"$dir/slurm.conf" <<CONF
ClusterName=shpblocal
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MinJobAge=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  munged --force --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munged.seed" ||
    { stop "$dir"; die "munged did not start (see above)"; }
  slurmctld -f "$dir/slurm.conf" || { stop "$dir"; die "slurmctld did not start: $(tail -3 "$dir/log/slurmctld.log" 2>/dev/null)"; }
  slurmd -f "$dir/slurm.conf" || { stop "$dir"; die "slurmd did not start: $(tail -3 "$dir/log/slurmd.log" 2>/dev/null)"; }
  for _ in $(seq 300); do
    if [ "$(SLURM_CONF=$dir/slurm.conf sinfo -h -o %T 2>/dev/null)" = idle ]; then
      trap - INT TERM
      echo "export SLURM_CONF=$dir/slurm.conf"
      return 0
    fi
    sleep 0.1
  done
  local why
  why=$(tail -3 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" 2>/dev/null || true)
  stop "$dir"
  die "the node did not become idle within 30 s: $why"
}

abort_start() {
  if [ -f "$1/slurm.conf" ]; then stop "$1"; else rm -rf "$1"; fi
  exit "$2"
}

stop() {
  local dir=$1
  [ -f "$dir/slurm.conf" ] || die "$dir holds no local cluster (no slurm.conf)"
  # Jobs first, so that no job step outlives its slurmd.
  if [ -s "$dir/slurmctld.pid" ]; then
    SLURM_CONF=$dir/slurm.conf scancel --full --quiet --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 100); do
      [ -z "$(SLURM_CONF=$dir/slurm.conf squeue -h 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  # The Slurm daemons together, munged (which they authenticate through) after them.
  # shellcheck disable=SC2046
  stop_pids $(daemon_pid "$dir/slurmd.pid" slurmd) $(daemon_pid "$dir/slurmctld.pid" slurmctld)
  # shellcheck disable=SC2046
  stop_pids $(daemon_pid "$dir/munged.pid" munged)
  rm -rf "$dir"
}

case ${1:-} in
  start) [ $# -eq 2 ] || die "usage: $0 start DIR"; start "$2" ;;
  stop) [ $# -eq 2 ] || die "usage: $0 stop DIR"; stop "$2" ;;
  *) die "usage: $0 start DIR | stop DIR" ;;
esac

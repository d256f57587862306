#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, to try the recipes on and for make check-dist:
# munged, slurmctld and slurmd with a minimal configuration (no cgroups, no accounting),
# every file of it in DIR, on two free TCP ports.
#   dist/slurm/local-cluster.sh start DIR   start the daemons; then use SLURM_CONF=DIR/slurm.conf
#   dist/slurm/local-cluster.sh stop DIR    cancel its jobs, stop the daemons it started
# Needs root (the daemons run as root), Debian's slurm-wlm and munge, and DIR's parent
# folders open to all (munged checks the path to its socket). start fails
# loudly (the daemon's last log lines, exit 1) when a daemon does not come up in time;
# stop may be called after any failure of start. DIR is left for the caller to remove.
set -euo pipefail
cmd=${1:-} dir=${2:-}
if [ -z "$dir" ] || { [ "$cmd" != start ] && [ "$cmd" != stop ]; }; then
  echo "usage: $0 start|stop DIR" >&2
  exit 2
fi
dir=$(realpath -m "$dir")
conf=$dir/slurm.conf
export SLURM_CONF=$conf

fail() {
  echo "local-cluster: $1" >&2
  [ -f "${2:-}" ] && tail -n 15 "$2" | sed 's/^/    /' >&2
  exit 1
}

# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local seconds=$1 start=$SECONDS
  shift
  until "$@" >/dev/null 2>&1; do
    [ $((SECONDS - start)) -lt "$seconds" ] || return 1
    sleep 0.2
  done
}

# A TCP port nothing listens on (a connection to it is refused).
free_port() {
  local port
  for _ in $(seq 50); do
    port=$(shuf -i 20000-60000 -n 1)
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
      echo "$port"
      return
    fi
  done
  fail "no free TCP port found"
}

munge_up() { munge -S "$dir/munge/munge.socket" -n | unmunge -S "$dir/munge/munge.socket"; }
controller_up() { scontrol ping | grep -q 'is UP'; }
node_idle() { [ "$(sinfo -h -o %T)" = idle ]; }

start() {
  [ "$(id -u)" = 0 ] || fail "needs root: the daemons run as root"
  local tool
  for tool in munged mungekey slurmctld slurmd; do
    command -v $tool >/dev/null || fail "$tool is missing: apt-get install slurm-wlm munge"
  done
  [ ! -e "$conf" ] || fail "$dir already holds a cluster"
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
  chmod 755 "$dir" "$dir/munge" # munged wants its socket's folders open to all
  mungekey --create --keyfile="$dir/munge/munge.key"
  munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" ||
    fail "munged did not start" "$dir/munge/munged.log"
  wait_for 10 munge_up || fail "munged does not answer" "$dir/munge/munged.log"

  local node cpus
  node=$(hostname -s)
  cpus=$(nproc)
  cat >"$conf" <<CONF
# Written by dist/slurm/local-cluster.sh: one node, no cgroups, no accounting.
ClusterName=rtklocal
SlurmctldHost=$node
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
MinJobAge=600
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
  slurmctld -f "$conf" || fail "slurmctld did not start" "$dir/slurmctld.log"
  wait_for 30 controller_up || fail "slurmctld does not answer" "$dir/slurmctld.log"
  slurmd -f "$conf" || fail "slurmd did not start" "$dir/slurmd.log"
  wait_for 30 node_idle || fail "the node did not come up idle: $(sinfo -h -o %T 2>&1)" "$dir/slurmd.log"
  echo "local-cluster: up in $dir (SLURM_CONF=$conf)"
}

# Stops the process in pid file $1: TERM, then KILL after 10 s. Only that process.
stop_daemon() {
  [ -f "$1" ] || return 0
  local pid
  pid=$(cat "$1")
  kill "$pid" 2>/dev/null || return 0
  wait_for 10 bash -c "! kill -0 $pid" || kill -9 "$pid" 2>/dev/null || true
}

stop() {
  if [ -f "$conf" ] && [ -f "$dir/slurmctld.pid" ]; then
    scancel --user="$(id -un)" 2>/dev/null || true
    # shellcheck disable=SC2016 # the inner shell expands it, each time
    wait_for 15 bash -c '[ -z "$(squeue -h 2>/dev/null)" ]' || true
  fi
  stop_daemon "$dir/slurmd.pid"
  stop_daemon "$dir/slurmctld.pid"
  stop_daemon "$dir/munge/munged.pid"
}

"$cmd"

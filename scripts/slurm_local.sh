#!/usr/bin/env bash
# Starts and stops a real one-node Slurm cluster on this machine, from Debian's slurm-wlm and
# munge, for the tests of `attend sweep --slurm` and for trying a sweep out (docs/SWEEPS.md).
#
#   scripts/slurm_local.sh start [STATE]   start it; the last line printed is STATE/env
#   . STATE/env                            a client's environment (SLURM_CONF)
#   sbatch ...; squeue; scontrol show job ...
#   scripts/slurm_local.sh status [STATE]  sinfo, exit 1 when it is not running
#   scripts/slurm_local.sh stop [STATE]    stop it and remove STATE
#
# STATE defaults to ${TMPDIR:-/tmp}/attend-slurm-UID. Everything lives there: a fresh munge key
# and munged on its own socket (nothing in /etc/munge or /run/munge), slurm.conf, the
# controller's state, the daemons' logs and pid files, and jobcomp.txt, where each finished
# job's state (COMPLETED, FAILED, TIMEOUT, CANCELLED) is written. slurmctld and slurmd listen on
# free unprivileged ports; one node (attendnode, all the cores) in one partition (debug).
# There is no accounting daemon: `sacct` does not work, `scontrol show job` keeps a finished
# job for 10 minutes (MinJobAge) and jobcomp.txt keeps it for good.
#
# `start` installs slurm-wlm and munge through scripts/install_deps.sh when they are missing,
# and stops a cluster already running from STATE first. When the cluster cannot start, it
# prints "slurm_local: cannot start: REASON" and the tail of the daemon's log on stderr, stops
# what it started, and exits 1: the tests skip with that message. slurmd runs jobs as the user
# who submits them, so `start` needs root (as the tests in CI have).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command="${1:-}"
state="${2:-${TMPDIR:-/tmp}/attend-slurm-$(id -u)}"

usage() {
  echo "usage: scripts/slurm_local.sh start|stop|status [STATE]" >&2
  exit 2
}

# Stops the daemons started from $state (by their pid files), SIGKILL after 5 s.
stop_daemons() {
  local name pid
  for name in slurmd slurmctld munged; do
    [ -f "$state/$name.pid" ] || continue
    pid="$(cat "$state/$name.pid" 2>/dev/null || true)"
    [ -n "$pid" ] || continue
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$state/$name.pid"
  done
}

fail() {
  echo "slurm_local: cannot start: $1" >&2
  if [ -n "${2:-}" ] && [ -f "$2" ]; then
    tail -n 12 "$2" | sed 's/^/  /' >&2
  fi
  stop_daemons
  rm -rf "$state"
  exit 1
}

# The first port from $1 on that nothing listens on (bash's /dev/tcp: no other tool needed).
free_port() {
  local port="$1"
  while (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; do
    port=$((port + 1))
  done
  echo "$port"
}

start() {
  if ! command -v slurmctld >/dev/null 2>&1 || ! command -v slurmd >/dev/null 2>&1 ||
    ! command -v sbatch >/dev/null 2>&1 || ! command -v munged >/dev/null 2>&1; then
    "$root/scripts/install_deps.sh" >&2 || true
  fi
  local tool
  for tool in slurmctld slurmd sbatch sinfo munged; do
    command -v "$tool" >/dev/null 2>&1 ||
      fail "$tool is missing (Debian packages slurm-wlm and munge, scripts/install_deps.sh)"
  done
  [ "$(id -u)" -eq 0 ] || fail "slurmd must run as root to run jobs as their users; run as root"

  if [ -d "$state" ]; then
    stop_daemons
    rm -rf "$state"
  fi
  mkdir -p "$state/ctld" "$state/spool"
  chmod 700 "$state"

  # munge: a key of its own, and munged on a socket in the state folder.
  dd if=/dev/urandom of="$state/munge.key" bs=1024 count=1 status=none
  chmod 400 "$state/munge.key"
  munged --force --socket="$state/munge.socket" --key-file="$state/munge.key" \
    --pid-file="$state/munged.pid" --log-file="$state/munged.log" \
    --seed-file="$state/munged.seed" 2>>"$state/munged.log" ||
    fail "munged did not start" "$state/munged.log"

  local user ctld_port slurmd_port memory
  user="$(id -un)"
  # From a port of this process's own, so that clusters started at once (tests in parallel)
  # do not pick the same free port before either listens on it.
  ctld_port="$(free_port $((20000 + ($$ % 10000) * 2)))"
  slurmd_port="$(free_port $((ctld_port + 1)))"
  # Slurm refuses a node whose RealMemory exceeds what it finds: 90 % of the machine's.
  memory="$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)"
  cat >"$state/slurm.conf" <<EOF
# A one-node cluster for attend's tests (scripts/slurm_local.sh); every path in $state.
ClusterName=attendlocal
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$state/munge.socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
KillWait=5
OverTimeLimit=0
MinJobAge=600
InactiveLimit=0
NodeName=attendnode NodeAddr=127.0.0.1 NodeHostname=$(hostname) CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=debug Nodes=attendnode Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$state/slurm.conf"
  slurmctld -f "$SLURM_CONF" 2>>"$state/slurmctld.log" ||
    fail "slurmctld did not start" "$state/slurmctld.log"
  slurmd -f "$SLURM_CONF" -N attendnode 2>>"$state/slurmd.log" ||
    fail "slurmd did not start" "$state/slurmd.log"

  local node=""
  for _ in $(seq 120); do
    node="$(sinfo -h -n attendnode -o %t 2>/dev/null || true)"
    [ "$node" = "idle" ] && break
    sleep 0.5
  done
  [ "$node" = "idle" ] ||
    fail "the node is not idle after 60 s (sinfo says '${node:-nothing}')" "$state/slurmd.log"
  echo "export SLURM_CONF=$state/slurm.conf" >"$state/env"
  echo "$state/env"
}

case "$command" in
  start) start ;;
  stop)
    stop_daemons
    rm -rf "$state"
    ;;
  status)
    [ -f "$state/slurm.conf" ] || exit 1
    SLURM_CONF="$state/slurm.conf" sinfo
    ;;
  *) usage ;;
esac

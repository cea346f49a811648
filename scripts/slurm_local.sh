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
# free unprivileged ports; one node (attendnode, all the cores) in one partition (debug). No
# systemd: the daemons are started directly. There is no accounting daemon: `sacct` does not
# work, `scontrol show job` keeps a finished job for 10 minutes (MinJobAge) and jobcomp.txt
# keeps it for good.
#
# Jobs start about a second after their submission or after a task of their array ends
# (batch_sched_delay=0; the first job after `start` waits about 3 s). Time limits: KillWait=5
# and OverTimeLimit=0, so a job past its --time gets SIGTERM and 5 s later SIGKILL, and ends as
# TIMEOUT. slurmctld looks at time limits every 30 s (fixed in Slurm), so a job with --time=1
# is ended between 60 and 90 s after it started.
#
# `start` installs slurm-wlm and munge through scripts/install_deps.sh when they are missing,
# and stops a cluster already running from STATE first; it takes about a second, `stop` half a
# second. When the cluster cannot start, it prints "slurm_local: cannot start: REASON" and the
# tail of the daemon's log on stderr, stops what it started, and exits 1: the tests skip with
# that message. The daemons run as the user who starts them (no root needed): started by root,
# the cluster runs jobs of any user; started by another user, only that user's jobs. `stop`
# also kills the jobs still running.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command="${1:-}"
state="${2:-${TMPDIR:-/tmp}/attend-slurm-$(id -u)}"
state="${state%/}"

usage() {
  echo "usage: scripts/slurm_local.sh start|stop|status [STATE]" >&2
  exit 2
}

# Whether process $1 runs. A zombie does not: this machine's init may never reap them.
alive() {
  local stat
  stat="$(ps -o stat= -p "$1" 2>/dev/null)" || return 1
  [ -n "$stat" ] && [ "${stat:0:1}" != "Z" ]
}

# The pid in $state/$1.pid when that process runs and is the daemon started from $state (its
# command line names a file in $state: not a pid reused since).
daemon_pid() {
  local pid
  pid="$(cat "$state/$1.pid" 2>/dev/null || true)"
  [ -n "$pid" ] && alive "$pid" || return 1
  tr '\0' ' ' 2>/dev/null <"/proc/$pid/cmdline" | grep -qF "$state/" || return 1
  echo "$pid"
}

# Kills the jobs still running on this cluster: its slurmstepd processes (found by the
# SLURM_CONF slurmd gave them, so that other clusters' jobs are left alone) and everything
# under them.
kill_jobs() {
  local pid steps=""
  for pid in $(pgrep -x slurmstepd || true); do
    alive "$pid" || continue
    if tr '\0' '\n' 2>/dev/null <"/proc/$pid/environ" |
      grep -qxF "SLURM_CONF=$state/slurm.conf"; then
      steps="$steps $pid"
    fi
  done
  [ -n "$steps" ] || return 0
  # shellcheck disable=SC2046  # one pid a word
  kill -9 $(ps -eo pid=,ppid= | awk -v roots="$steps" '
    BEGIN { n = split(roots, r, " "); for (i = 1; i <= n; i++) keep[r[i]] = 1 }
    { parent[$1] = $2 }
    END {
      do {
        more = 0
        for (p in parent) if (!(p in keep) && (parent[p] in keep)) { keep[p] = 1; more = 1 }
      } while (more)
      for (p in keep) print p
    }') 2>/dev/null || true
}

# Stops the jobs and the daemons started from $state (by their pid files), SIGKILL after 5 s.
stop_daemons() {
  local name pid
  kill_jobs
  for name in slurmd slurmctld munged; do
    if pid="$(daemon_pid "$name")"; then
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do
        alive "$pid" || break
        sleep 0.1
      done
      kill -9 "$pid" 2>/dev/null || true
    fi
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
MailProg=/bin/true
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
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

  local node="" name log deadline=$((SECONDS + 60))
  while [ "$SECONDS" -lt "$deadline" ]; do
    node="$(sinfo -h -n attendnode -o %t 2>/dev/null || true)"
    [ "$node" = "idle" ] && break
    # A daemon that has written its pid file and died: no use waiting for it.
    for name in munged slurmctld slurmd; do
      if [ -s "$state/$name.pid" ] && ! daemon_pid "$name" >/dev/null; then
        fail "$name stopped" "$state/$name.log"
      fi
    done
    sleep 0.5
  done
  if [ "$node" != "idle" ]; then
    log="$state/slurmd.log"
    [ -s "$log" ] || log="$state/slurmctld.log"
    fail "the node is not idle after 60 s (sinfo says '${node:-nothing}')" "$log"
  fi
  printf 'export SLURM_CONF=%q\n' "$state/slurm.conf" >"$state/env"
  echo "$state/env"
}

case "$command" in
  start) start ;;
  stop)
    stop_daemons
    rm -rf "$state"
    ;;
  status)
    daemon_pid slurmctld >/dev/null || exit 1
    SLURM_CONF="$state/slurm.conf" sinfo
    ;;
  *) usage ;;
esac

#!/usr/bin/env bash
# A real single-node SLURM cluster on this machine, without systemd, for trying `mosb run --slurm`
# (spec/RUN.md §8) on a laptop and for tests/cli/test_slurm.py. Debian's `slurm-wlm` and `munge`
# packages (tools/install-deps.sh installs them); run as root (slurmd starts jobs as their users).
#
#   sudo tools/slurm-cluster.sh start     # munged, slurmctld -D, slurmd -D; waits until the node is idle
#   eval "$(tools/slurm-cluster.sh env)"  # SLURM_CONF for sbatch, squeue, sacct, sinfo, scancel
#   sinfo; sbatch ...; squeue
#   sudo tools/slurm-cluster.sh status    # the daemons' PIDs, sinfo and squeue; exit 0 when all run
#   sudo tools/slurm-cluster.sh stop      # cancels the jobs, then stops every daemon it started
#
# Everything lives in one state directory, $MOSB_SLURM_DIR (default /tmp/mosb-slurm; sudo drops the
# variable, so pass it as `sudo MOSB_SLURM_DIR=... tools/slurm-cluster.sh start`): a fresh munge key
# and munged's pid and seed files (munge/), its socket (socket/, for every user's clients, named by
# slurm.conf's AuthInfo=socket=...); slurm.conf; slurmctld's state (state/), slurmd's spool (spool/)
# and every daemon's log (log/: munged.log, slurmctld.log, slurmd.log); and the PID of each daemon
# started (pids/), which `stop` kills by that PID alone (SIGTERM, then SIGKILL after 10 s), after
# cancelling every job so that no slurmstepd outlives the cluster. `start` wipes the directory's
# earlier state, so every cluster starts with an empty queue; it refuses while one runs there.
#
# The cluster talks over loopback only: SlurmctldHost=HOSTNAME(127.0.0.1) (slurmctld must run on
# the host its name says, so NAME is `hostname -s`), NodeAddr=127.0.0.1, and two free TCP ports
# chosen at start. The node has the CPUs and RealMemory `slurmd -C` reports; memory is a consumable
# resource (select/cons_tres, CR_Core_Memory) with DefMemPerCPU = RealMemory / CPUs. Processes are
# tracked by proctrack/linuxproc with task/none and jobacct_gather/linux, so no cgroup setup is
# needed. There is no slurmdbd: AccountingStorageType=accounting_storage/none, and finished jobs go
# to log/jobcomp.txt (jobcomp/filetxt); `mosb run --slurm DIR --status` then relies on squeue and
# the shard files.
set -euo pipefail

dir="${MOSB_SLURM_DIR:-/tmp/mosb-slurm}"
conf="$dir/slurm.conf"
name="$(hostname -s)"
partition="mosb"

die() {
  echo "slurm-cluster: $*" >&2
  exit 1
}

usage() {
  echo "usage: tools/slurm-cluster.sh start|stop|status|env  (state in \$MOSB_SLURM_DIR, default /tmp/mosb-slurm)" >&2
  exit 2
}

# The PID a pid file of ours names when that process is alive and still runs the program it was
# started as (the file holds "PID EXECUTABLE"), else nothing.
live_pid() {
  local file="$dir/pids/$1.pid" pid want exe
  [[ -f "$file" ]] || return 0
  read -r pid want <"$file" || true
  [[ "$pid" =~ ^[0-9]+$ ]] || return 0
  exe="$(readlink "/proc/$pid/exe" 2>/dev/null || true)"
  [[ -n "$exe" && "${exe% (deleted)}" == "$want" ]] && echo "$pid"
  return 0
}

daemons=(slurmd slurmctld munged) # in stop order

# Two TCP ports nothing listens on now (the kernel's choice of free ephemeral ports).
free_ports() {
  python3 -c '
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in socks))'
}

log_tails() {
  local f
  for f in "$dir/log/munged.log" "$dir/log/slurmctld.log" "$dir/log/slurmd.log" \
    "$dir/log/slurmctld.out" "$dir/log/slurmd.out"; do
    [[ -s "$f" ]] && { echo "--- tail of $f"; tail -n 15 "$f"; }
  done >&2
  return 0
}

# Starts `program args...` in the background in a session of its own, every stream redirected (so
# whoever ran this script does not wait on its pipes), and records its PID.
spawn() {
  local pidname="$1" out="$2" want pid i
  shift 2
  want="$(readlink -f "$(command -v "$1")")" # Debian's slurmctld is a link to slurmctld-wlm
  setsid "$@" </dev/null >"$out" 2>&1 &
  pid=$!
  echo "$pid $want" >"$dir/pids/$pidname.pid"
  for ((i = 0; i < 100; i++)); do # until setsid has executed the daemon
    [[ "$(readlink "/proc/$pid/exe" 2>/dev/null || true)" == "$want" ]] && return 0
    sleep 0.02
  done
}

write_conf() {
  local ports node cpus memory
  read -r -a ports <<<"$(free_ports)"
  # "NodeName=vm CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=N"
  node="$(slurmd -C | head -n 1)"
  cpus="$(sed -n 's/.*CPUs=\([0-9]*\).*/\1/p' <<<"$node")"
  memory="$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$node")"
  [[ -n "$cpus" && -n "$memory" ]] || die "cannot read the node's CPUs and memory from 'slurmd -C': $node"
  : >"$dir/plugstack.conf"
  cat >"$conf" <<EOF
# Written by tools/slurm-cluster.sh: a single-node cluster over loopback, state in $dir.
ClusterName=mosb
SlurmctldHost=$name(127.0.0.1)
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/socket/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=10
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=$((memory / cpus))
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
InactiveLimit=0
KillWait=5
MinJobAge=600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$name NodeAddr=127.0.0.1 ${node#NodeName=* } State=UNKNOWN
PartitionName=$partition Nodes=$name Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  [[ "$(id -u)" -eq 0 ]] || die "run as root (slurmd starts every job as its user)"
  local program
  for program in munged slurmctld slurmd sinfo sbatch; do
    command -v "$program" >/dev/null || die "$program is not installed (apt-get install slurm-wlm munge)"
  done
  local daemon
  for daemon in "${daemons[@]}"; do
    [[ -z "$(live_pid "$daemon")" ]] ||
      die "a cluster is running in $dir ($daemon PID $(live_pid "$daemon")); stop it first"
  done
  rm -rf "$dir/state" "$dir/spool" "$dir/log" "$dir/run" "$dir/munge" "$dir/socket" "$dir/pids"
  mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/run" "$dir/munge" "$dir/socket" "$dir/pids"
  chmod 755 "$dir"
  chmod 700 "$dir/munge" # the key: root's alone
  chmod 755 "$dir/socket" # the socket: every user's client
  write_conf

  # munged: a fresh key, its own socket, pid, seed and log files.
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$dir/munge/munge.key"
  spawn munged "$dir/log/munged.out" munged --foreground --force \
    --socket="$dir/socket/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/munged.seed" \
    --log-file="$dir/log/munged.log"
  local i
  for ((i = 0; i < 100; i++)); do
    [[ -S "$dir/socket/munge.socket" ]] && break
    [[ -n "$(live_pid munged)" ]] || { log_tails; die "munged did not start"; }
    sleep 0.1
  done
  [[ -S "$dir/socket/munge.socket" ]] || { log_tails; die "munged made no socket in 10 s"; }

  export SLURM_CONF="$conf"
  spawn slurmctld "$dir/log/slurmctld.out" slurmctld -D -f "$conf"
  spawn slurmd "$dir/log/slurmd.out" slurmd -D -f "$conf" -N "$name"

  # Ready when the node is idle (registered with slurmctld, no job).
  local state=""
  for ((i = 0; i < 300; i++)); do
    for daemon in "${daemons[@]}"; do
      [[ -n "$(live_pid "$daemon")" ]] || { log_tails; stop_daemons; die "$daemon exited while starting"; }
    done
    state="$(sinfo -h -n "$name" -o %T 2>/dev/null || true)"
    [[ "$state" == "idle" ]] && break
    sleep 0.2
  done
  if [[ "$state" != "idle" ]]; then
    log_tails
    stop_daemons
    die "the node did not become idle in 60 s (state: ${state:-none})"
  fi
  echo "slurm-cluster: running in $dir: node $name ($(sinfo -h -n "$name" -o '%c CPUs, %m MB'))," \
    "partition $partition; for the client commands:"
  echo "  export SLURM_CONF=$conf"
}

# SIGTERM to each daemon we started, by its PID; SIGKILL to what is left after 10 s.
stop_daemons() {
  local daemon pid pids=()
  for daemon in "${daemons[@]}"; do
    pid="$(live_pid "$daemon")"
    if [[ -n "$pid" ]]; then
      kill -TERM "$pid" 2>/dev/null || true
      pids+=("$pid")
    fi
  done
  local i left
  for ((i = 0; i < 100; i++)); do
    left=()
    for pid in "${pids[@]}"; do
      [[ -d "/proc/$pid" ]] && [[ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)" != Z ]] && left+=("$pid")
    done
    ((${#left[@]} == 0)) && break
    sleep 0.1
  done
  for pid in "${left[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  rm -f "$dir"/pids/*.pid
}

stop() {
  if [[ -n "$(live_pid slurmctld)" && -f "$conf" ]]; then
    export SLURM_CONF="$conf"
    # Every job first, so that no slurmstepd (started by slurmd, not by us) outlives the cluster.
    local jobs i
    jobs="$(squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ' || true)"
    if [[ -n "${jobs// /}" ]]; then
      # shellcheck disable=SC2086
      scancel $jobs 2>/dev/null || true
      for ((i = 0; i < 100; i++)); do
        [[ -z "$(squeue -h -o %A 2>/dev/null || true)" ]] && break
        sleep 0.2
      done
    fi
  fi
  stop_daemons
  echo "slurm-cluster: stopped ($dir)"
}

status() {
  local daemon pid running=0
  for daemon in "${daemons[@]}"; do
    pid="$(live_pid "$daemon")"
    if [[ -n "$pid" ]]; then echo "$daemon: running, PID $pid"; else echo "$daemon: not running"; fi
    [[ -n "$pid" ]] && running=$((running + 1))
  done
  if [[ -n "$(live_pid slurmctld)" ]]; then
    SLURM_CONF="$conf" sinfo || true
    SLURM_CONF="$conf" squeue || true
  fi
  ((running == ${#daemons[@]}))
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) status ;;
  env) echo "export SLURM_CONF=$conf" ;;
  *) usage ;;
esac

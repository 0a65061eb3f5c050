#!/usr/bin/env bash
# Starts a single-node Slurm test cluster on this machine from Debian 12's packages
# (slurm-wlm, munge; installed with apt-get if missing). Must run as root. systemd is
# not assumed: munged, slurmctld and slurmd are started directly as daemons.
#
#   CAMSIM_SLURM_DIR  state dir: slurm.conf, logs, pid files, spool, saved state
#                     (default /tmp/camsim-slurm)
#   CAMSIM_SLURM_CRED_EXPIRE  job credential lifetime in s, which is also how long a
#                     requeued job waits before it may start again (default here 20;
#                     Slurm's default, and most clusters', is 120)
#   CAMSIM_SLURM_WAIT seconds to wait for each daemon and the node (default 30)
#
# Idempotent: if this state dir's daemons already run, they are reused. On any
# failure it prints why (the last lines of the daemon logs) and exits non-zero.
# Afterwards:  export SLURM_CONF=$CAMSIM_SLURM_DIR/slurm.conf; sinfo; sbatch ...
# Stop it with scripts/slurm/stop_cluster.sh (same CAMSIM_SLURM_DIR).
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  echo "start_cluster: must run as root (it installs packages and starts munged, slurmctld, slurmd)" >&2
  exit 1
fi

dir=${CAMSIM_SLURM_DIR:-/tmp/camsim-slurm}
conf=$dir/slurm.conf
logdir=$dir/log
host=$(hostname -s)
wait_s=${CAMSIM_SLURM_WAIT:-30}
cred_expire=${CAMSIM_SLURM_CRED_EXPIRE:-20}
if ! [[ $wait_s =~ ^[0-9]+$ ]]; then
  echo "start_cluster: CAMSIM_SLURM_WAIT='$wait_s' is not a whole number of seconds" >&2
  exit 1
fi
if ! [[ $cred_expire =~ ^[0-9]+$ ]] || ((cred_expire < 5)); then
  echo "start_cluster: CAMSIM_SLURM_CRED_EXPIRE='$cred_expire': give a whole number of seconds, at least 5" >&2
  exit 1
fi
export SLURM_CONF=$conf

log() { echo "start_cluster: $*" >&2; }

show_logs() {
  local f
  for f in "$logdir/slurmctld.log" "$logdir/slurmd.log" /var/log/munge/munged.log "$logdir/munged.out"; do
    # munged's log only matters when munge does not work (it logs an Info line per job).
    if [ "$f" = /var/log/munge/munged.log ] && munge_works; then continue; fi
    # Only logs written since this start began.
    if [ -e "$dir/.start" ] && ! [ "$f" -nt "$dir/.start" ]; then continue; fi
    if [ -s "$f" ]; then
      echo "---- last lines of $f ----" >&2
      tail -n 25 "$f" >&2
    fi
  done
}

reported=0
fail() {
  log "FAILED: $*"
  show_logs
  log "daemons started so far are left running; scripts/slurm/stop_cluster.sh stops them"
  reported=1
  exit 1
}
# A fresh daemon gets a fresh log (the previous one is kept as .1), so that the lines
# shown on a failure are this start's.
fresh_log() { if [ -e "$1" ]; then mv -f "$1" "$1.1"; fi; }
on_exit() {
  local rc=$?
  if [ "$rc" -ne 0 ] && [ "$reported" = 0 ]; then
    log "FAILED (exit $rc)"
    show_logs
    log "daemons started so far are left running; scripts/slurm/stop_cluster.sh stops them"
  fi
}
set -E
trap 'log "command failed (line $LINENO): $BASH_COMMAND"' ERR
trap on_exit EXIT

# pid_alive PIDFILE NAME: the pid in PIDFILE is a live process whose command is NAME.
pid_alive() {
  local pid
  [ -s "$1" ] || return 1
  pid=$(head -n 1 "$1")
  [[ $pid =~ ^[0-9]+$ ]] || return 1
  [ -r "/proc/$pid/comm" ] && [ "$(cat "/proc/$pid/comm")" = "$2" ]
}

munge_works() { munge -n 2>/dev/null | unmunge >/dev/null 2>&1; }

mkdir -p "$dir/state" "$dir/spool" "$logdir"
chmod 755 "$dir"
touch "$dir/.start"

# ---- packages -------------------------------------------------------------------
need=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if ((${#need[@]})); then
  log "installing ${need[*]}"
  # Keep the packages' init scripts from starting daemons with the default
  # /etc/slurm config: this script starts its own (a standard Debian mechanism).
  made_policy=0
  if [ ! -e /usr/sbin/policy-rc.d ]; then
    printf '#!/bin/sh\nexit 101\n' >/usr/sbin/policy-rc.d
    chmod 755 /usr/sbin/policy-rc.d
    made_policy=1
  fi
  apt-get update -qq || log "apt-get update failed; trying the install anyway"
  inst_rc=0
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >"$logdir/apt.log" 2>&1 || inst_rc=$?
  if [ "$made_policy" = 1 ]; then rm -f /usr/sbin/policy-rc.d; fi
  if [ "$inst_rc" -ne 0 ]; then
    tail -n 20 "$logdir/apt.log" >&2
    fail "apt-get install slurm-wlm munge exited $inst_rc"
  fi
  rm -f "$logdir/apt.log"
fi
for b in /usr/sbin/munged /usr/sbin/slurmctld /usr/sbin/slurmd /usr/bin/sinfo /usr/bin/scontrol; do
  [ -x "$b" ] || fail "$b missing after installing slurm-wlm and munge"
done

# ---- munge ----------------------------------------------------------------------
key=/etc/munge/munge.key
if [ ! -s "$key" ]; then
  log "creating $key"
  mkdir -p /etc/munge
  if command -v mungekey >/dev/null 2>&1; then
    mungekey --create --keyfile="$key" --force
  elif [ -x /usr/sbin/create-munge-key ]; then
    /usr/sbin/create-munge-key -f
  else
    dd if=/dev/urandom of="$key" bs=1 count=1024 status=none
  fi
fi
chown munge:munge /etc/munge "$key"
chmod 700 /etc/munge
chmod 400 "$key"
# /run/munge is normally made by systemd's tmpfiles; without systemd make it here.
for d in /run/munge /var/lib/munge /var/log/munge; do
  mkdir -p "$d"
  chown munge:munge "$d"
done
chmod 755 /run/munge
chmod 700 /var/lib/munge /var/log/munge

if pid_alive /run/munge/munged.pid munged && munge_works; then
  if ! cmp -s /run/munge/munged.pid "$dir/munged.pid" 2>/dev/null; then
    log "reusing a munged that this script did not start (pid $(cat /run/munge/munged.pid)); stop_cluster.sh will leave it running"
  fi
else
  rm -f "$dir/munged.pid"
  log "starting munged"
  # munged refuses to run as root without --force; Debian runs it as user munge.
  fresh_log "$logdir/munged.out"
  runuser -u munge -- /usr/sbin/munged >"$logdir/munged.out" 2>&1 || fail "munged did not start"
  for _ in $(seq 1 50); do munge_works && break; sleep 0.1; done
  munge_works || fail "munged runs but munge -n | unmunge fails"
  cp /run/munge/munged.pid "$dir/munged.pid"   # marks it as ours for stop_cluster.sh
fi

# ---- slurm.conf -----------------------------------------------------------------
running_ctld=0; running_d=0
pid_alive "$dir/slurmctld.pid" slurmctld && running_ctld=1
pid_alive "$dir/slurmd.pid" slurmd && running_d=1

cpus=$(nproc)

# 95 % of MemTotal in MiB, so that slurmd never finds less than the config says.
mem_mb=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.95 }' /proc/meminfo)
new_conf=$(cat <<CONF
# Written by camsim scripts/slurm/start_cluster.sh: a single-node test cluster.
ClusterName=camsim
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
# cred_expire: also the delay before a requeued job may start again (Slurm's default 120 s).
AuthInfo=cred_expire=$cred_expire
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$logdir/slurmctld.log
SlurmdLogFile=$logdir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
# No accounting (so no sacct): finished jobs' state and exit code go to this text file.
JobCompType=jobcomp/filetxt
JobCompLoc=$logdir/jobcomp.log
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
KillWait=5
JobRequeue=1
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
)
if ((running_ctld || running_d)); then
  if [ "$new_conf" != "$(cat "$conf" 2>/dev/null)" ]; then
    log "note: $conf differs from what this script would write now; keeping it while daemons run (stop_cluster.sh, then start again, to rewrite it)"
  fi
else
  printf '%s\n' "$new_conf" >"$conf"
  chmod 644 "$conf"
fi

# ---- slurmctld, slurmd ----------------------------------------------------------
# A port already taken means another Slurm runs here: its daemons would answer our
# clients and this script would report the wrong cluster as up.
port_busy() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
if ! ((running_ctld)) && port_busy 6817; then
  fail "port 6817 (slurmctld) is in use by another process: another Slurm controller runs on this machine"
fi
if ! ((running_d)) && port_busy 6818; then
  fail "port 6818 (slurmd) is in use by another process: another slurmd runs on this machine"
fi

if ((running_ctld)); then
  log "reusing slurmctld (pid $(cat "$dir/slurmctld.pid"))"
else
  log "starting slurmctld"
  fresh_log "$logdir/slurmctld.log"; fresh_log "$logdir/slurmctld.out"
  /usr/sbin/slurmctld -f "$conf" >"$logdir/slurmctld.out" 2>&1 || fail "slurmctld exited $?"
fi
for _ in $(seq 1 $((wait_s * 5))); do
  scontrol ping 2>/dev/null | grep -q 'is UP' && break
  sleep 0.2
done
scontrol ping 2>/dev/null | grep -q 'is UP' || fail "slurmctld does not answer 'scontrol ping' after ${wait_s} s"
pid_alive "$dir/slurmctld.pid" slurmctld || fail "slurmctld answers but its pid file $dir/slurmctld.pid names no running slurmctld"

if ((running_d)); then
  log "reusing slurmd (pid $(cat "$dir/slurmd.pid"))"
else
  log "starting slurmd"
  fresh_log "$logdir/slurmd.log"; fresh_log "$logdir/slurmd.out"
  /usr/sbin/slurmd -f "$conf" >"$logdir/slurmd.out" 2>&1 || fail "slurmd exited $?"
fi

# ---- wait for slurmd and for the node to be idle (or busy with jobs already) ----
state=""
up=0
deadline=$((SECONDS + wait_s))
while ((SECONDS < deadline)); do
  pid_alive "$dir/slurmctld.pid" slurmctld || fail "slurmctld died"
  # slurmd writes its pid file a moment after forking; it may not be there yet.
  if pid_alive "$dir/slurmd.pid" slurmd; then
    state=$(sinfo -h -n "$host" -o '%T' 2>/dev/null | head -n 1 || true)
    case $state in
      idle | mixed | allocated | completing) up=1; break ;;
      down | drained | draining | drain) # not "down*": that one is only not responding yet
        log "node $host is $state; resuming it"
        scontrol update nodename="$host" state=resume || true ;;
    esac
  elif [ -s "$dir/slurmd.pid" ]; then
    fail "slurmd died"
  fi
  sleep 0.5
done
if ((!up)); then
  pid_alive "$dir/slurmd.pid" slurmd || fail "slurmd is not running (no live pid in $dir/slurmd.pid) after ${wait_s} s"
  scontrol show node "$host" >&2 || true
  fail "node $host is '${state:-unknown}' after ${wait_s} s, not idle"
fi

trap - EXIT
sinfo
cat <<USAGE

Slurm cluster 'camsim' is up on $host (state dir $dir, logs in $logdir).
Use it with:
  export SLURM_CONF=$conf
  sinfo; sbatch --array=0-3 --wrap 'echo \$SLURM_ARRAY_TASK_ID'; squeue
Finished jobs (state, exit code) are logged in $logdir/jobcomp.log.
Stop it with: CAMSIM_SLURM_DIR=$dir scripts/slurm/stop_cluster.sh
USAGE

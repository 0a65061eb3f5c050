#!/usr/bin/env bash
# Stops the single-node Slurm test cluster that scripts/slurm/start_cluster.sh started:
# cancels its jobs, then stops slurmd, slurmctld and (if that script started it)
# munged, by the pid files in the state dir. Leaves no daemon of that cluster running.
#
#   CAMSIM_SLURM_DIR  state dir (default /tmp/camsim-slurm), as for start_cluster.sh
#
# Saved controller state stays in $CAMSIM_SLURM_DIR/state; jobs are cancelled, not kept.
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  echo "stop_cluster: must run as root" >&2
  exit 1
fi

dir=${CAMSIM_SLURM_DIR:-/tmp/camsim-slurm}
export SLURM_CONF=$dir/slurm.conf
log() { echo "stop_cluster: $*" >&2; }

# pid_of PIDFILE NAME: prints the pid in PIDFILE if it is a live process named NAME.
pid_of() {
  local pid
  [ -s "$1" ] || return 1
  pid=$(head -n 1 "$1")
  [[ $pid =~ ^[0-9]+$ ]] || return 1
  [ -r "/proc/$pid/comm" ] && [ "$(cat "/proc/$pid/comm")" = "$2" ] || return 1
  echo "$pid"
}

# stop PIDFILE NAME: SIGTERM, up to 15 s, then SIGKILL.
stop() {
  local pid
  pid=$(pid_of "$1" "$2") || { log "$2 not running"; rm -f "$1"; return 0; }
  log "stopping $2 (pid $pid)"
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 1 150); do
    [ -d "/proc/$pid" ] || break
    sleep 0.1
  done
  if [ -d "/proc/$pid" ]; then
    log "$2 (pid $pid) ignored SIGTERM for 15 s; killing it"
    kill -KILL "$pid" 2>/dev/null || true
    sleep 0.5
  fi
  if [ -d "/proc/$pid" ]; then
    log "FAILED: $2 (pid $pid) still runs"
    failed=1
    return 0
  fi
  rm -f "$1"
}
failed=0

# This cluster's job steps: slurmstepd processes that slurmd started with our SLURM_CONF.
our_stepds() {
  local p
  for p in $(pgrep -x slurmstepd || true); do
    if { tr '\0' '\n' <"/proc/$p/environ"; } 2>/dev/null | grep -qx "SLURM_CONF=$SLURM_CONF"; then
      echo "$p"
    fi
  done
}

# Cancel the jobs first so that their steps end cleanly (SIGTERM, KillWait, SIGKILL).
if pid_of "$dir/slurmctld.pid" slurmctld >/dev/null && scontrol ping 2>/dev/null | grep -q 'is UP'; then
  jobs=$(squeue -h -o '%A' 2>/dev/null | tr '\n' ' ')
  if [ -n "${jobs// /}" ]; then
    log "cancelling jobs: $jobs"
    # shellcheck disable=SC2086  # one word per job id
    scancel $jobs || true
    for _ in $(seq 1 40); do
      [ -z "$(squeue -h -o '%A' 2>/dev/null)" ] && [ -z "$(our_stepds)" ] && break
      sleep 0.5
    done
  fi
fi

stop "$dir/slurmd.pid" slurmd
stepds=$(our_stepds)
if [ -n "$stepds" ]; then
  log "killing leftover slurmstepd: $stepds"
  # shellcheck disable=SC2086
  kill -KILL $stepds 2>/dev/null || true
fi
stop "$dir/slurmctld.pid" slurmctld

if [ -s "$dir/munged.pid" ]; then
  if cmp -s "$dir/munged.pid" /run/munge/munged.pid; then
    stop /run/munge/munged.pid munged
  else
    log "munged was restarted by someone else since start_cluster.sh; leaving it"
  fi
  rm -f "$dir/munged.pid"
else
  log "munged was not started by start_cluster.sh; leaving it"
fi

if [ -n "$(our_stepds)" ]; then
  log "FAILED: slurmstepd still running: $(our_stepds | tr '\n' ' ')"
  failed=1
fi
if [ "$failed" != 0 ]; then exit 1; fi
log "stopped"

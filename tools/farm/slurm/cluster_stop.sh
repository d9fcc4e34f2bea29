#!/bin/sh
# Stops the cluster cluster_start.sh started (by its pid files; munged
# only if cluster_start.sh started it). Runs again harmlessly.
#   BANYAN_SLURM_DIR   as for cluster_start.sh (default /tmp/banyan-slurm)
set -u
dir=${BANYAN_SLURM_DIR:-/tmp/banyan-slurm}
stop() { # pid file, name
  [ -s "$1" ] || return 0
  pid=$(cat "$1")
  if kill -0 "$pid" 2>/dev/null; then
    kill "$pid" 2>/dev/null
    i=0; while kill -0 "$pid" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null
  fi
  rm -f "$1"
}
[ -f "$dir/slurm.conf" ] && SLURM_CONF=$dir/slurm.conf scancel --quiet --user="$(id -un)" 2>/dev/null
stop "$dir/slurmd.pid" slurmd
stop "$dir/slurmctld.pid" slurmctld
if [ -f "$dir/munged.ours" ]; then
  [ -s /run/munge/munged.pid ] && cp /run/munge/munged.pid "$dir/munged.pid" && stop "$dir/munged.pid" munged
  rm -f "$dir/munged.ours"
fi
exit 0

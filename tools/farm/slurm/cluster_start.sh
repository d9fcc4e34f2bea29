#!/bin/sh
# Starts a one-node Slurm cluster on 127.0.0.1 (munged, slurmctld, slurmd
# with BANYAN_SLURM_CPUS CPUs, default 2) for banyan's batch runner; runs
# again harmlessly (whatever already answers is left alone). Needs root
# and Debian's slurm-wlm and munge (tools/setup.sh). Prints the
# `export SLURM_CONF=...` line the Slurm commands need.
#   BANYAN_SLURM_DIR   state, logs and slurm.conf (default /tmp/banyan-slurm)
#   BANYAN_SLURM_PORT  slurmctld's port (default 6817; slurmd uses +1)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
dir=${BANYAN_SLURM_DIR:-/tmp/banyan-slurm}
port=${BANYAN_SLURM_PORT:-6817}
cpus=${BANYAN_SLURM_CPUS:-2}
host=$(hostname -s)
for t in munged slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$t" >/dev/null 2>&1 || PATH=$PATH:/usr/sbin
  command -v "$t" >/dev/null 2>&1 || { echo "cluster_start: $t not found: apt-get install slurm-wlm munge (tools/setup.sh)" >&2; exit 3; }
done
[ "$(id -u)" = 0 ] || { echo "cluster_start: needs root (slurmd runs jobs as their user; SlurmUser=root)" >&2; exit 3; }
mkdir -p "$dir/ctld" "$dir/d"
conf=$dir/slurm.conf
sed -e "s|@HOST@|$host|g" -e "s|@STATE@|$dir|g" -e "s|@CTLD_PORT@|$port|g" \
    -e "s|@SLURMD_PORT@|$((port + 1))|g" -e "s|@CPUS@|$cpus|g" "$here/slurm.conf.in" > "$conf.new"
mv "$conf.new" "$conf"
export SLURM_CONF=$conf

# munged: the Debian package made /etc/munge/munge.key; one daemon serves
# every user, so an answering one is kept (and not ours to stop).
if ! munge -n >/dev/null 2>&1; then
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  runuser -u munge -- /usr/sbin/munged
  touch "$dir/munged.ours"
  i=0; until munge -n >/dev/null 2>&1; do i=$((i + 1)); [ $i -lt 50 ] || { echo "cluster_start: munged does not answer" >&2; exit 1; }; sleep 0.1; done
fi

alive() { [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
alive "$dir/slurmctld.pid" || /usr/sbin/slurmctld -f "$conf"
alive "$dir/slurmd.pid" || /usr/sbin/slurmd -f "$conf"

# Ready when the node is idle (or busy with jobs of an earlier start).
i=0
while :; do
  st=$(sinfo -h -N -o %T 2>/dev/null | head -n 1 || true)
  case "$st" in idle*|mixed*|alloc*|allocated*) break ;; esac
  case "$st" in down*|drain*) scontrol update NodeName="$host" State=RESUME >/dev/null 2>&1 || true ;; esac
  i=$((i + 1))
  [ $i -lt 300 ] || { echo "cluster_start: node not ready (state '$st'); see $dir/slurmctld.log, $dir/slurmd.log" >&2; exit 1; }
  sleep 0.2
done
echo "export SLURM_CONF=$conf"

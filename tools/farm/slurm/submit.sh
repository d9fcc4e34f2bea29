#!/bin/sh
# Queues banyan_array.sbatch over --seeds A:B in tasks of --per-task K
# (array 0 .. ceil((B-A)/K)-1, at most --workers W running at once) and,
# after it, the manifest merge (batch_run.py --merge-manifest OUT --seeds
# A:B, which exits non-zero if a seed has no record). Slurm's logs go to
# --logs DIR (default OUT.slurm-logs, beside OUT, so OUT holds only the
# runner's files). Prints
# "<array job id> <merge job id>". Other arguments go to the runner, which
# checks them (batch_run.py --check) before anything is queued.
#   sh submit.sh --per-task 10 --workers 2 --preset P --seeds 0:40 --out DIR [...]
# Environment as banyan_array.sbatch (BANYAN_ADDON, BANYAN_BLENDER,
# BANYAN_PYTHON); SLURM_CONF as cluster_start.sh prints.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
addon=${BANYAN_ADDON:-$(cd "$here/../../.." && pwd)/blender_addon/banyan}
export BANYAN_ADDON=$addon
# Nothing is queued for a preset the runner refuses: its --check loads the
# preset, hosts and options as a task would (exit 2 with the reason).
"${BANYAN_PYTHON:-python3}" "$addon/batch_run.py" -- --check "$@" >&2 ||
  { echo "submit: the runner refused the job (above): nothing queued" >&2; exit 2; }
per_task= workers= seeds= out= logs= args=
while [ $# -gt 0 ]; do
  case "$1" in
    --per-task) per_task=$2; shift 2 ;;
    --workers) workers=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --logs) logs=$2; shift 2 ;;
    *) args="$args $(printf "'%s'" "$(printf %s "$1" | sed "s/'/'\\\\''/g")")"; shift ;;
  esac
done
[ -n "$per_task" ] && [ -n "$seeds" ] && [ -n "$out" ] || { echo "submit: --per-task, --seeds and --out are required" >&2; exit 2; }
a=${seeds%%:*} b=${seeds##*:}
n=$(( (b - a + per_task - 1) / per_task ))
[ $n -ge 1 ] || { echo "submit: --seeds $seeds is empty" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
logs=${logs:-$out.slurm-logs}
mkdir -p "$logs"
array="0-$((n - 1))"
[ -n "$workers" ] && array="$array%$workers"
eval "set -- $args"
job=$(sbatch --parsable --array="$array" --chdir="$out" --output="$logs/slurm-%A_%a.out" \
      "$here/banyan_array.sbatch" --per-task "$per_task" --seeds "$seeds" --out "$out" "$@")
merge=$(sbatch --parsable --dependency=afterany:"$job" --chdir="$out" --output="$logs/slurm-%j-merge.out" \
      --job-name=banyan-merge --wrap "${BANYAN_PYTHON:-python3} '$addon/batch_run.py' -- --merge-manifest '$out' --seeds '$seeds' --verify")
echo "$job $merge"

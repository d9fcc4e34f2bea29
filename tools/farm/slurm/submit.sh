#!/bin/sh
# Queues banyan_array.sbatch over --seeds A:B in tasks of --per-task K
# (array 0 .. ceil((B-A)/K)-1, at most --workers W running at once) and,
# after it, the manifest merge (batch_run.py --merge-manifest OUT --seeds
# A:B --verify, plus --preset, the glTF options and --format so that it checks the
# preset's hash; it exits non-zero if a seed has no record). Arguments
# reach sbatch and the jobs as argv, never through a shell string; whole
# numbers are decimal (010 is ten). Slurm's logs go to
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
per_task= workers= seeds= out= logs= preset= tsize= notex= shared= format=
hosts_n=0  # --host values in host_1 .. host_N (eval assigns a variable's name only: the value stays data)
die() { echo "submit: $*" >&2; exit 2; }
# Options of this script are taken out; the others stay in "$@" (as data,
# never through eval or a shell string) and go to the runner.
n=$#
while [ $n -gt 0 ]; do
  case "$1" in
    --per-task|--workers|--seeds|--out|--logs)
      [ $n -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --per-task) per_task=$2 ;; --workers) workers=$2 ;; --seeds) seeds=$2 ;; --out) out=$2 ;; --logs) logs=$2 ;;
      esac
      shift 2; n=$((n - 2)) ;;
    --preset|--texture-size|--format)  # also given to the merge, which checks the preset's hash
      [ $n -ge 2 ] || die "$1 needs a value"
      case "$1" in --preset) preset=$2 ;; --texture-size) tsize=$2 ;; --format) format=$2 ;; esac
      set -- "$@" "$1" "$2"; shift 2; n=$((n - 2)) ;;
    --format=*) format=${1#--format=}; set -- "$@" "$1"; shift; n=$((n - 1)) ;;
    --no-textures) notex=1; set -- "$@" "$1"; shift; n=$((n - 1)) ;;
    --shared-textures) shared=1; set -- "$@" "$1"; shift; n=$((n - 1)) ;;
    --host)  # hosts are in the preset's hash: the merge is given them too
      [ $n -ge 2 ] || die "$1 needs a value"
      hosts_n=$((hosts_n + 1)); eval "host_$hosts_n=\$2"
      set -- "$@" "$1" "$2"; shift 2; n=$((n - 2)) ;;
    *) set -- "$@" "$1"; shift; n=$((n - 1)) ;;
  esac
done
[ -n "$per_task" ] && [ -n "$seeds" ] && [ -n "$out" ] || die "--per-task, --seeds and --out are required"
# Whole numbers are decimal digits 0-9 only, read in base 10 (010 is ten).
decimal() {  # decimal WHAT VALUE -> $dec (no leading zeros) or exit 2
  case $2 in
    ''|*[!0123456789]*) die "$1 '$2' must be a whole number in decimal digits 0-9" ;;
  esac
  dec=${2#"${2%%[!0]*}"}
  dec=${dec:-0}
  [ ${#dec} -le 10 ] || die "$1 '$2' is too large"
}
case $seeds in
  *:*:*|*[!0123456789:]*|:*|*:|'') die "--seeds '$seeds' must look like A:B (half-open, decimal digits 0-9)" ;;
  *:*) ;;
  *) die "--seeds '$seeds' must look like A:B (half-open, decimal digits 0-9)" ;;
esac
decimal --seeds "${seeds%%:*}"; a=$dec
decimal --seeds "${seeds##*:}"; b=$dec
[ "$a" -lt "$b" ] && [ "$b" -le 4294967296 ] || die "--seeds '$seeds' must have 0 <= A < B <= 4294967296"
[ $((b - a)) -le 10000000 ] || die "--seeds '$seeds' holds $((b - a)) seeds, more than the 10000000 a run or merge takes: split it"
seeds=$a:$b
decimal --per-task "$per_task"; per_task=$dec
[ "$per_task" -ge 1 ] || die "--per-task must be at least 1"
if [ -n "$workers" ]; then
  decimal --workers "$workers"; workers=$dec
  [ "$workers" -ge 1 ] || die "--workers must be at least 1"
fi
n=$(( (b - a + per_task - 1) / per_task ))
mkdir -p -- "$out"
out=$(cd -- "$out" && pwd)
logs=${logs:-$out.slurm-logs}
mkdir -p -- "$logs"
logs=$(cd -- "$logs" && pwd)
# sbatch reads %x in --output as a pattern: a literal % is %%.
logpat=$(printf '%s\n' "$logs" | sed 's/%/%%/g')
array="0-$((n - 1))"
[ -n "$workers" ] && array="$array%$workers"
job=$(sbatch --parsable --array="$array" --chdir="$out" --output="$logpat/slurm-%A_%a.out" \
      "$here/banyan_array.sbatch" --per-task "$per_task" --seeds "$seeds" --out "$out" "$@")
job=${job%%;*}
# The merge: a batch script with its arguments as argv (no --wrap string).
set -- --merge-manifest "$out" --seeds "$seeds" --verify
[ -n "$preset" ] && set -- "$@" --preset "$preset"
[ -n "$tsize" ] && set -- "$@" --texture-size "$tsize"
[ -n "$notex" ] && set -- "$@" --no-textures
[ -n "$shared" ] && set -- "$@" --shared-textures
[ -n "$format" ] && set -- "$@" --format "$format"
i=1
while [ $i -le $hosts_n ]; do
  eval "set -- \"\$@\" --host \"\$host_$i\""
  i=$((i + 1))
done
merge=$(sbatch --parsable --dependency=afterany:"$job" --chdir="$out" --output="$logpat/slurm-%j-merge.out" \
      --job-name=banyan-merge "$here/banyan_merge.sbatch" "$@")
merge=${merge%%;*}
echo "$job $merge"

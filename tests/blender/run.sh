#!/usr/bin/env bash
# Runs every tests/blender/test_*.py in real headless Blender against the
# library in <build_dir>:   tests/blender/run.sh <build_dir> [test_file...]
# The add-on is loaded straight from the repository through a temporary
# BLENDER_USER_SCRIPTS whose addons/banyan links to blender_addon/banyan,
# with BANYAN_LIB=<build_dir>/libbanyan.so.
#   tests/blender/run.sh <build_dir> --zip [test_file...]
# instead unpacks <build_dir>/banyan.zip as the add-on and leaves BANYAN_LIB
# unset, so the library is the zip's banyan/lib/libbanyan.so.
# The files run in ONE Blender through tests/blender/suite.py (a fresh
# factory scene and a freshly loaded add-on for each), but for those that
# need a Blender of their own (suite.py's SEPARATE, with the reason for
# each); BANYAN_BLENDER_SEPARATE=1 gives every file its own Blender. A file
# that crashes the shared Blender is reported failed and the files after it
# run in a new one. Either way: one line per file, its log in
# <build_dir>/test_out/blender/<name>.log, its time at the end of the line
# (in the shared Blender without the start, which costs about 1-2 s);
# the shared Blender's own output is in suite.log there, with each file's
# CPU time. tests/blender/suite_selftest.sh tests this runner.
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
build=$(cd "${1:?usage: run.sh <build_dir> [test_file...]}" && pwd)
shift
zip=0
if [ "${1:-}" = "--zip" ]; then zip=1; shift; fi
blender=${BLENDER:-blender}
command -v "$blender" >/dev/null || { echo "blender not found (tools/setup.sh installs it)"; exit 1; }

scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons"
out="$build/test_out/blender${BANYAN_BLENDER_TAG:+/$BANYAN_BLENDER_TAG}"
mkdir -p "$out"
# The Blender that tests starting a child Blender run (bt.BLENDER).
export BANYAN_BLENDER="$(command -v "$blender")"
export BLENDER_USER_SCRIPTS="$scripts"
if [ $zip = 1 ]; then
  [ -f "$build/banyan.zip" ] || { echo "no $build/banyan.zip (build the banyan_addon_zip target)"; exit 1; }
  python3 -c "import zipfile, sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$build/banyan.zip" "$scripts/addons"
  unset BANYAN_LIB
  export BANYAN_EXPECT_LIB="$scripts/addons/banyan/lib/libbanyan.so"
  out="$out/zip"; mkdir -p "$out"
else
  ln -s "$src/blender_addon/banyan" "$scripts/addons/banyan"
  export BANYAN_LIB="$build/libbanyan.so"
  export BANYAN_EXPECT_LIB="$BANYAN_LIB"
fi
export BANYAN_SOURCE_DIR="$src"
export BANYAN_BUILD_DIR="$build"
export BANYAN_TEST_OUT="$out"
export PYTHONDONTWRITEBYTECODE=1

echo "blender tests: library $BANYAN_EXPECT_LIB"

if [ $# -gt 0 ]; then tests=("$@"); else tests=("$here"/test_*.py); fi
failed=0
# One line per file, with the Blender it ran on, for tools/test.sh to print
# (ctest shows a passing test's output only with -V).
summary_file="$out/summary.txt"
: >"$summary_file"
now_ms() { local t=${EPOCHREALTIME/./}; echo $((t / 1000)); }
secs() { printf '%d.%d s' $(($1 / 1000)) $(($1 % 1000 / 100)); }

# Which files share one Blender (suite.py), in the order given.
declare -A rc_of ms_of note_of
shared=()
if [ "${BANYAN_BLENDER_SEPARATE:-0}" != 1 ]; then
  separate=" $(python3 "$here/suite.py" --separate | tr '\n' ' ') "
  for t in "${tests[@]}"; do
    name=$(basename "$t" .py)
    [[ "$separate" == *" $name "* ]] || shared+=("$t")
  done
fi
if [ ${#shared[@]} -ge 2 ]; then
  suite_log="$out/suite.log"
  status="$out/suite.status"
  : >"$suite_log"
  todo=("${shared[@]}")
  while [ ${#todo[@]} -gt 0 ]; do
    : >"$status"
    "$blender" -b --factory-startup --addons banyan --python-exit-code 1 --python "$here/suite.py" \
      -- "$status" "$out" "${todo[@]}" >>"$suite_log" 2>&1
    prc=$?
    end_ms=$(now_ms)
    left=()
    progress=0
    for t in "${todo[@]}"; do
      name=$(basename "$t" .py)
      read -r _ _ frc fms < <(grep -E "^end $name " "$status" | tail -1)
      read -r _ _ start < <(grep -E "^start $name " "$status" | tail -1)
      if [ -n "${frc:-}" ]; then
        rc_of[$name]=$frc; ms_of[$name]=$fms; progress=1
      elif [ -n "${start:-}" ]; then
        # The shared Blender ended inside this file (a crash): failed; the
        # files after it run in a new Blender.
        rc_of[$name]=$([ $prc -ne 0 ] && echo $prc || echo 1); ms_of[$name]=$((end_ms - start)); progress=1
        note_of[$name]="the shared Blender ended (exit $prc) inside this file; the files after it ran in a new one"
      else
        left+=("$t")
      fi
      frc=; fms=; start=
    done
    if [ $progress = 0 ]; then
      # The driver ran no file at all: one Blender per file for the rest.
      echo "suite.py ran no file (exit $prc, $suite_log): one Blender per file"
      tail -20 "$suite_log" | sed 's/^/    /'
      break
    fi
    todo=("${left[@]}")
  done
fi

for t in "${tests[@]}"; do
  name=$(basename "$t" .py)
  log="$out/$name.log"
  if [ -n "${rc_of[$name]:-}" ]; then
    rc=${rc_of[$name]}
    ms=${ms_of[$name]}
  else
    t0=$(now_ms)
    "$blender" -b --factory-startup --addons banyan --python-exit-code 1 --python "$t" >"$log" 2>&1
    rc=$?
    ms=$(($(now_ms) - t0))
  fi
  summary=$(grep -E "^$name: [0-9]+ passed, [0-9]+ failed" "$log" | tail -1)
  version=$(grep -m1 -oE "^Blender [0-9]+\.[0-9]+\.[0-9]+" "$log")
  if [ $rc -ne 0 ] || [ -z "$summary" ]; then
    failed=$((failed + 1))
    echo "FAILED $name (exit $rc): ${summary:-no summary line} [${version:-Blender ?}, $(secs $ms)]" | tee -a "$summary_file"
    [ -n "${note_of[$name]:-}" ] && echo "    ${note_of[$name]}"
    grep -E "^(FAIL|SKIP|Traceback|  File|[A-Za-z]+Error)" "$log" | head -40 | sed 's/^/    /'
  else
    echo "ok     $summary [${version:-Blender ?}, $(secs $ms)]" | tee -a "$summary_file"
    grep -E "^SKIP" "$log" | sort -u | sed 's/^/    /'
  fi
done
echo "blender tests${BANYAN_BLENDER_TAG:+ ($BANYAN_BLENDER_TAG)}: ${#tests[@]} files, $failed failed"
[ $failed -eq 0 ]

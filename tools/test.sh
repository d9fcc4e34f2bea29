#!/usr/bin/env bash
# The tests, in two tiers (README, "Tests"):
#
#   bash tools/test.sh          quick tier, for every day (about 10 minutes
#                               on 2 cores): set up, build, then ctest without
#                               the tests labelled `full` or `farm` -- every C
#                               test, the CLI tests, the ISA sweep on three
#                               kernel sets, the Khronos validator, the GLSL
#                               twin, the add-on suite in Debian's Blender 3.4,
#                               the browser viewer on one preset per generator.
#   bash tools/test.sh --full   everything (what .ci/run runs; about 70
#                               minutes): the whole ctest (the ISA sweep on
#                               every kernel set, the add-on in Blender 3.4,
#                               4.2, 4.5, 5.0, 5.1 and 5.2, its zip and its window,
#                               valgrind, the farm tests, the viewer on every
#                               preset), the add-on packages with the build
#                               folder moved away, the C suite under ASan +
#                               UBSan, the thread tests under TSan, a
#                               short libFuzzer run of every harness, and
#                               the Windows x64 build (tools/win/test.sh:
#                               cross-built with its dependencies cached
#                               in ~/.cache/banyan/win, its C tests under
#                               wine64, every preset byte for byte as the
#                               Linux build, its packages).
#
# BANYAN_TEST_TIER (quick or full) is exported for the tests that scale
# with the tier (the ISA sweep, the viewer). Every stage runs even when one
# before it failed; the script fails at the end if any did, and prints a
# table of each stage's time and the slowest tests.
set -uo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
tier=quick
for a in "$@"; do
  case "$a" in
    --full) tier=full ;;
    --quick) tier=quick ;;
    -h|--help) sed -n '2,29p' "$0"; exit 0 ;;
    *) echo "test.sh: unknown argument $a (use --full, or nothing for the quick tier)"; exit 2 ;;
  esac
done
export BANYAN_TEST_TIER=$tier
jobs=$(nproc)
logs="$here/build/test_logs"
names=()
secs=()
codes=()

# stage NAME COMMAND...: runs it, records its time and exit code; a failed
# stage does not stop the ones after it.
stage() {
  local name=$1
  shift
  echo
  echo "== $name =="
  local t0=$SECONDS
  "$@"
  local rc=$?
  names+=("$name")
  secs+=($((SECONDS - t0)))
  codes+=("$rc")
  [ "$rc" -eq 0 ] || echo "== $name: FAILED (exit $rc) =="
  return 0
}

ctest_in() { # ctest_in DIR LOG [ctest args...]
  local dir=$1 log=$2
  shift 2
  (cd "$dir" && ctest --output-on-failure -j "$jobs" "$@") 2>&1 | tee "$log"
}

blender_summaries() {
  for f in build/test_out/blender/summary.txt build/test_out/blender/zip/summary.txt \
           build/test_out/blender/bpy-*/summary.txt; do
    [ -f "$f" ] && { echo "-- ${f#build/test_out/blender/}"; cat "$f"; }
  done
  return 0
}

# prune DIR: once a build's stages have read their outputs, the full tier
# deletes the large ones (meshes, images, packages; text such as summaries
# and logs stays) so the sanitizer builds after it fit on a small CI disk.
prune() {
  local d
  for d in "$1/test_out" "$1/batch_out"; do
    [ -d "$d" ] && find "$d" -type f -size +256k ! -name '*.txt' ! -name '*.log' -delete
  done
  return 0
}

asan() {
  BUILD_DIR=build-asan BANYAN_CMAKE_ARGS="-DBANYAN_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo" \
    bash tools/setup.sh || return $?
  ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 ctest_in build-asan "$logs/ctest_asan.log"
}

tsan() {
  local tests=(test_threads test_avenue test_keyaki test_wind_keyaki test_budget_keyaki)
  cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBANYAN_TSAN=ON >/dev/null || return $?
  cmake --build build-tsan --target "${tests[@]}" || return $?
  local re
  re="^($(IFS='|'; echo "${tests[*]}"))\$"
  TSAN_OPTIONS=halt_on_error=1 ctest_in build-tsan "$logs/ctest_tsan.log" -R "$re"
}

started=$SECONDS
stage "set-up and build" bash tools/setup.sh
mkdir -p "$logs"
rm -f "$logs"/ctest*.log # the table below reads this run's logs only
if [ "$tier" = full ]; then
  # Blender 4.2, 4.5, 5.0, 5.1 and 5.2 as the bpy module (cached venvs).
  stage "Blender 4.2, 4.5, 5.0, 5.1, 5.2 (bpy wheels)" bash tools/blender_versions.sh
  stage "ctest (every test)" ctest_in build "$logs/ctest.log"
else
  stage "ctest (quick tier: without the labels full, farm)" ctest_in build "$logs/ctest.log" -LE '^(full|farm)$'
fi
stage "the add-on's tests, by Blender" blender_summaries
if [ "$tier" = full ]; then
  stage "the add-on packages with the build folder moved away" bash tests/blender/packages.sh build
  prune build
  stage "ASan + UBSan: ctest" asan
  prune build-asan
  stage "TSan: the thread tests" tsan
  prune build-tsan
  stage "fuzzing (FUZZ_SECONDS per harness, default 60)" bash tools/fuzz.sh
  stage "Windows x64: cross-build, C tests under wine64, presets = Linux, packages" bash tools/win/test.sh
  prune build-win
fi

echo
echo "== times ($tier tier, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(df -h --output=avail . | tail -1 | tr -d ' ') free on disk) =="
failed=0
for i in "${!names[@]}"; do
  mark=ok
  [ "${codes[$i]}" -eq 0 ] || { mark=FAILED; failed=$((failed + 1)); }
  printf '  %6d s  %-7s %s\n' "${secs[$i]}" "$mark" "${names[$i]}"
done
printf '  %6d s  total\n' $((SECONDS - started))
echo "-- the slowest tests (ctest's own times, run $jobs at a time) --"
for log in "$logs"/ctest*.log; do
  [ -f "$log" ] || continue
  grep -E '^ *[0-9]+/[0-9]+ Test +#' "$log" |
    sed -E 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: ([^ ]+) .* ([0-9.]+) sec$/\2 \1/' |
    awk -v b="$(basename "$log" .log)" '{print $1, $2 " (" b ")"}'
done | sort -rn | head -15 | awk '{printf "  %8.1f s  %s %s\n", $1, $2, $3}'
if [ $failed -gt 0 ]; then
  echo "test.sh ($tier): $failed of ${#names[@]} stages FAILED"
  exit 1
fi
echo "test.sh ($tier): every stage passed"

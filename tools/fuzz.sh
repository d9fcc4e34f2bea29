#!/usr/bin/env bash
# Short libFuzzer runs of every harness (part of tools/test.sh):
# builds build-fuzz with Debian's clang (libFuzzer + ASan + UBSan), makes
# the seed corpora from presets/, runs each harness FUZZ_SECONDS (default
# 60) two at a time, appends one JSON line per harness to the results file
# and exits non-zero when a harness crashed, leaked, ran out of memory,
# hung or broke an invariant, or an input ran past the per-input limit.
# The corpora stay in build-fuzz/corpus, so runs add up. The seeds hold
# every preset twice: shrunk, and at its real size (<name>.real, under the
# harness's run budget, tests/fuzz/fuzz_common.h).
#   FUZZ_SECONDS   seconds per harness (default 60; fuzz_lod and
#                  fuzz_gltf_write run half of it)
#   FUZZ_JOBS      harnesses at a time (default 2)
#   FUZZ_TIMEOUT   per-input limit in seconds (default 30): an input slower
#                  than this is a failure, a timeout (libFuzzer stops) or a
#                  slow unit (it finished, but past the limit)
#   FUZZ_RESULTS   results file (default out/fuzz_results.json)
# A crasher is left in build-fuzz/fuzz_work/<harness>/crashes/: fix the
# bug, then copy the file into tests/fuzz/regressions/<harness>/, where
# ctest replays it in every build.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
secs=${FUZZ_SECONDS:-60}
jobs=${FUZZ_JOBS:-2}
timeout=${FUZZ_TIMEOUT:-30}
results=${FUZZ_RESULTS:-out/fuzz_results.json}
build=build-fuzz
harnesses=(fuzz_preset fuzz_roots fuzz_keyaki fuzz_ivy fuzz_segments fuzz_hosts fuzz_glb fuzz_lod fuzz_gltf_write)
# The mesh-in harnesses (small meshes, fast inputs) run half as long: the
# stage's wall time grows by a quarter of FUZZ_SECONDS, not a whole one.
half=(fuzz_lod fuzz_gltf_write)

echo "== fuzzing: ${#harnesses[@]} harnesses x ${secs} s, ${jobs} at a time, ${timeout} s an input =="
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBANYAN_FUZZ=ON >/dev/null
cmake --build "$build" --target "${harnesses[@]}" fuzz_seeds

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
corpus=$here/$build/corpus
"$build/tests/fuzz/fuzz_seeds" presets "$corpus"
mkdir -p "$corpus/fuzz_preset" "$corpus/fuzz_hosts" "$corpus/fuzz_glb" "$corpus/fuzz_lod" "$corpus/fuzz_gltf_write"
cp presets/*.json tests/data/bad_presets/* "$corpus/fuzz_preset/"
cp tests/fuzz/seeds/fuzz_hosts/* "$corpus/fuzz_hosts/"
cp tests/fuzz/seeds/fuzz_glb/* "$corpus/fuzz_glb/"
cp tests/fuzz/seeds/fuzz_lod/* "$corpus/fuzz_lod/"
cp tests/fuzz/seeds/fuzz_gltf_write/* "$corpus/fuzz_gltf_write/"

# One harness: runs it, then writes its JSON line to fuzz_work/<h>/result.
run_one() {
  local h=$1 work=$here/$build/fuzz_work/$1 max_len=4096 secs=$secs
  [ "$h" = fuzz_preset ] && max_len=65536
  [[ " ${half[*]} " == *" $h "* ]] && secs=$(( (secs + 1) / 2 ))
  rm -rf "$work"
  mkdir -p "$work/crashes" "$here/tests/fuzz/regressions/$h"
  local start rc=0
  start=$(date +%s)
  (cd "$work" && ASAN_OPTIONS=detect_leaks=1 "$here/$build/tests/fuzz/$h" \
     -max_total_time="$secs" -timeout="$timeout" -report_slow_units="$timeout" \
     -rss_limit_mb=2048 -max_len="$max_len" \
     -print_final_stats=1 -artifact_prefix="$work/crashes/" \
     "$corpus/$h" "$here/tests/fuzz/regressions/$h") >"$work/log.txt" 2>&1 || rc=$?
  local wall=$(( $(date +%s) - start ))
  local execs
  execs=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$work/log.txt" | tail -1)
  # Without final stats (a crash), the last progress line: "#123 ...".
  [ -n "$execs" ] || execs=$(sed -n 's/^#\([0-9][0-9]*\).*/\1/p' "$work/log.txt" | tail -1)
  [ -n "$execs" ] || execs=0
  # Artifacts by kind: crash-, leak-, oom- (crashes), timeout- (an input
  # killed at the limit) and slow-unit- (an input that finished past it).
  local crashes timeouts slow units
  crashes=$(find "$work/crashes" -type f ! -name 'slow-unit-*' ! -name 'timeout-*' | wc -l)
  timeouts=$(find "$work/crashes" -type f -name 'timeout-*' | wc -l)
  slow=$(find "$work/crashes" -type f -name 'slow-unit-*' | wc -l)
  units=$(find "$corpus/$h" -type f | wc -l)
  # libFuzzer exits on a timeout before it writes the artifact in some
  # versions: its log line counts too.
  if [ "$timeouts" -eq 0 ] && grep -q 'ERROR: libFuzzer: timeout' "$work/log.txt"; then timeouts=1; fi
  printf '{"harness": "%s", "date": "%s", "commit": "%s", "seconds": %d, "execs": %d, "crashes": %d, "timeouts": %d, "slow": %d, "timeout_s": %d, "exit": %d, "corpus": %d}\n' \
    "$h" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$commit" \
    "$wall" "$execs" "$crashes" "$timeouts" "$slow" "$timeout" "$rc" "$units" >"$work/result"
  echo "$h: $execs execs in ${wall} s, $crashes crashes, $timeouts timeouts, $slow slow units (limit ${timeout} s), exit $rc"
}

running=0
for h in "${harnesses[@]}"; do
  run_one "$h" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

mkdir -p "$(dirname "$results")"
failed=0
for h in "${harnesses[@]}"; do
  work=$build/fuzz_work/$h
  cat "$work/result" >>"$results"
  if ! grep -q '"crashes": 0, "timeouts": 0, "slow": 0, .*"exit": 0,' "$work/result"; then
    failed=1
    echo "FUZZ FAILURE in $h: see $work/log.txt and $work/crashes/" >&2
    grep -m 5 -E "ERROR|invariant|SUMMARY|Slow unit" "$work/log.txt" >&2 || true
  fi
done
echo "fuzz results appended to $results"
exit $failed

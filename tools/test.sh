#!/usr/bin/env bash
# All the tests: set up, build, run ctest (C unit and property tests, the
# CLI, the Khronos validator on every glTF the tests write, the add-on in
# Debian's Blender 3.4 and in Blender 4.2, 4.5 and 5.0), the add-on zips
# installed with the build folder moved away, then the same
# suite again under AddressSanitizer (with LeakSanitizer, on by default)
# and UndefinedBehaviorSanitizer, the thread tests under ThreadSanitizer,
# and a short libFuzzer run of every harness (tools/fuzz.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
bash tools/setup.sh
# Blender 4.2, 4.5 and 5.0 as the bpy module (cached venvs) for the add-on tests.
bash tools/blender_versions.sh
jobs=$(nproc)
(cd build && ctest --output-on-failure -j "$jobs")
echo "== the add-on's tests, by Blender (tests/blender/run.sh, run_bpy.sh, under ctest) =="
for f in build/test_out/blender/summary.txt build/test_out/blender/zip/summary.txt build/test_out/blender/bpy-*/summary.txt; do
  [ -f "$f" ] && { echo "-- ${f#build/test_out/blender/}"; cat "$f"; }
done

echo "== the add-on packages with the build folder moved away =="
bash tests/blender/packages.sh build

echo "== sanitizer build (ASan + UBSan) =="
BUILD_DIR=build-asan BANYAN_CMAKE_ARGS="-DBANYAN_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo" bash tools/setup.sh
(cd build-asan && ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j "$jobs")

echo "== ThreadSanitizer: the thread tests =="
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBANYAN_TSAN=ON >/dev/null
cmake --build build-tsan --target test_threads test_avenue test_keyaki test_wind_keyaki
(cd build-tsan && TSAN_OPTIONS=halt_on_error=1 ctest --output-on-failure -R '^(test_threads|test_avenue|test_keyaki|test_wind_keyaki)$')

echo "== fuzzing (FUZZ_SECONDS per harness, default 60) =="
bash tools/fuzz.sh

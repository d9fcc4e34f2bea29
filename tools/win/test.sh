#!/usr/bin/env bash
# The Windows build's tests, on Linux: cross-builds (tools/win/build.sh,
# dependencies from the cache), runs the C and C++ tests under wine64
# (ctest in build-win), compares every preset's .glb from the Windows CLI
# with the Linux build's byte for byte (tools/win/compare_presets.sh; both
# compute their elementary functions with the SLEEF in third_party/sleef),
# and packs and checks the windows-x64 zips. Prints each stage's time and
# ends with "N passed, N failed".
#   BUILD_DIR    the Windows build (default build-win)
#   LINUX_BUILD  the project's Linux build, configured (default build); its
#                CLI and OpenVDB module are brought up to date first
set -uo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
cd "$here"
build=${BUILD_DIR:-build-win}
linux=${LINUX_BUILD:-build}
out=$build/test_out/presets
pass=0 fail=0
stage() { # stage NAME COMMAND...
  local name=$1 t0=$SECONDS rc
  shift
  echo "== $name"
  "$@"
  rc=$?
  echo "== $name: $((SECONDS - t0)) s, exit $rc"
  if [ $rc -eq 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
  return $rc
}

stage build bash tools/win/build.sh || { echo "0 passed, 1 failed"; exit 1; }

wine_ctest() {
  # shellcheck source=tools/win/wine_env.sh
  . tools/win/wine_env.sh
  (cd "$build" && ctest --output-on-failure -j "${JOBS:-2}" --timeout 900)
}
stage "C tests under wine64" wine_ctest

linux_cli() {
  [ -f "$linux/CMakeCache.txt" ] || { echo "$linux: not a configured build (LINUX_BUILD)"; return 1; }
  cmake --build "$linux" -j "${JOBS:-2}" --target banyan_cli banyan_vdb
}
stage "Linux CLI ($linux)" linux_cli &&
  stage "presets: Windows = Linux" bash tools/win/compare_presets.sh "$linux" "$build" "$out"

stage "windows-x64 packages" python3 tools/win/package.py "$build"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]

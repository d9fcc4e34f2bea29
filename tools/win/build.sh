#!/usr/bin/env bash
# Cross-builds banyan for Windows x64 with Debian's mingw-w64: the
# dependencies first (tools/win/deps.sh, cached outside the repository),
# then banyan.dll, banyan_vdb.dll and banyan.exe into BUILD_DIR, with the
# DLLs they import copied beside them so wine64 (or Windows) runs them
# from there.
#   BUILD_DIR          build directory (default: build-win)
#   BANYAN_CMAKE_ARGS  extra cmake arguments
#   BANYAN_WIN_DEPS_PREFIX  a prefix of already built dependencies (development)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
cd "$here"
build=${BUILD_DIR:-build-win}

prefix=$(bash tools/win/deps.sh | tail -1)
export BANYAN_WIN_PREFIX=$prefix
export PKG_CONFIG_LIBDIR=$prefix/lib/pkgconfig PKG_CONFIG_PATH=

vdb=ON
[ -f "$prefix/.done-openvdb" ] || vdb=OFF
# shellcheck disable=SC2086
cmake -S . -B "$build" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$here/tools/win/mingw64.cmake" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" -DBANYAN_OPENVDB=$vdb -DOPENVDB_INCLUDE_DIR="$prefix/include" \
      "-DCMAKE_CXX_FLAGS=-isystem $prefix/boost-include" ${BANYAN_CMAKE_ARGS:-}
cmake --build "$build" -j "${JOBS:-2}"

# The DLLs beside the programs (the tests' too: Windows looks for a
# program's DLLs in its own folder first).
cp -u "$prefix"/bin/*.dll "$build/"
if [ -d "$build/tests" ]; then cp -u "$prefix"/bin/*.dll "$build/tests/"; fi

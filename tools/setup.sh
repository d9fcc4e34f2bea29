#!/usr/bin/env bash
# Installs everything banyan needs on Debian 12 and builds it. Safe to run
# again: packages already present are not fetched twice, and the build is
# incremental. Used by main.sh and test.sh (the README's two commands).
#   BUILD_DIR   build directory (default: build)
#   BANYAN_CMAKE_ARGS  extra cmake arguments
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"

# Debian packages: compiler and build tools, the C libraries (libdeflate
# for the PNG textures; tinyexr's header for the Pivot Painter 2 EXR; Embree for mesh hosts; OpenVDB with the Boost headers it includes, TBB and Imath for
# the fused roots surface), node for
# the glTF validator, Blender for the add-on tests, Mesa EGL for the
# geometry-shader twin, clang for fuzzing, valgrind for the failure paths,
# chromium for the viewer test, patchelf for the add-on zips' $ORIGIN, Xvfb
# for the add-on's tests in a real window (progress bar, Esc), Slurm and
# munge for the batch runner's farm tests (a one-node cluster), mingw-w64
# and wine64 for the Windows cross-build and its tests (tools/win/). SLEEF
# is not among them: its source is in third_party/sleef.
packages=(build-essential cmake ninja-build pkg-config locales libtinygltf-dev libstb-dev libcjson-dev libdeflate-dev libtinyexr-dev libembree-dev
          libopenvdb-dev libboost-dev libtbb-dev libimath-dev libmeshoptimizer-dev
          blender python3-numpy libegl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0 glslang-tools clang libclang-rt-dev
          valgrind chromium patchelf xvfb xauth slurm-wlm munge mingw-w64 wine64)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node may come from another packaging of nodejs that bundles npm; ask
# Debian only for what is really missing.
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# A comma-decimal locale for the locale tests (numbers must read the same
# under it): de_DE.UTF-8, generated once.
if ! locale -a 2>/dev/null | grep -qi '^de_DE\.utf-\?8$'; then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo="sudo"
  echo "setup: generating the de_DE.UTF-8 locale"
  $sudo localedef -i de_DE -f UTF-8 de_DE.UTF-8
fi

# The Khronos glTF validator, pinned in tests/gltf/package-lock.json.
if [ ! -d tests/gltf/node_modules/gltf-validator ]; then
  npm ci --prefix tests/gltf --no-audit --no-fund
fi

# three.js for the browser viewer, pinned in docs/viewer/package-lock.json.
if [ ! -f docs/viewer/node_modules/three/build/three.module.js ]; then
  npm ci --prefix docs/viewer --no-audit --no-fund
fi

# Babylon.js for the Babylon load test, pinned in tests/babylon/package-lock.json.
if [ ! -f tests/babylon/node_modules/@babylonjs/loaders/glTF/index.js ]; then
  npm ci --prefix tests/babylon --no-audit --no-fund
fi

build=${BUILD_DIR:-build}
# shellcheck disable=SC2086
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release ${BANYAN_CMAKE_ARGS:-}
cmake --build "$build"

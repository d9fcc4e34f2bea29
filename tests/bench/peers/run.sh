#!/usr/bin/env bash
# The peer benchmark:   tests/bench/peers/run.sh [build_dir] [runs] [script]
# (script: peers.py, the default, or ivy_suzanne.py alone: the ivy
# on Suzanne against IvyGen, printed; peers.py includes it)
# Builds libbanyan.so and bench_tube in build_dir (default build/), loads
# the add-on from the repository the way tests/blender/run.sh does (a
# temporary BLENDER_USER_SCRIPTS whose addons/banyan links to
# blender_addon/banyan, BANYAN_LIB=<build_dir>/libbanyan.so) and runs
# peers.py in one Blender process. Writes docs/benchmarks.md. Not CI.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
runs=${2:-5}
script=${3:-peers.py}
blender=${BLENDER:-blender}
# banyan_cli: the 1,000-tree avenue (section 10); bench_roots: section 7
cmake -S "$src" -B "$build" -DBANYAN_BENCH=ON >/dev/null  # the benchmarks are built only when asked
cmake --build "$build" -j2 --target banyan banyan_cli bench_tube bench_hosts bench_roots_hosts bench_ivy bench_textures \
    bench_roots

scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons"
ln -s "$src/blender_addon/banyan" "$scripts/addons/banyan"
export BLENDER_USER_SCRIPTS="$scripts"
export BANYAN_LIB="$build/libbanyan.so"
export BANYAN_BUILD_DIR="$build"
export PYTHONDONTWRITEBYTECODE=1
"$blender" -b --factory-startup --python-exit-code 1 --python "$here/$script" -- "$runs"

#!/usr/bin/env bash
# The main job: set up, build, grow the default strangler-fig root net
# around the default host box into out/roots.glb, and render it through
# headless Blender with the add-on (Cycles, CPU) into out/roots.png.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
bash tools/setup.sh
mkdir -p out
./build/banyan roots --stats -o out/roots.glb
# The add-on loads build/libbanyan.so when it has no lib/ of its own.
scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons"
ln -s "$here/blender_addon/banyan" "$scripts/addons/banyan"
BLENDER_USER_SCRIPTS="$scripts" BANYAN_LIB="$here/build/libbanyan.so" \
  blender -b --factory-startup --addons banyan --python-exit-code 1 \
  --python docs/examples/render_roots.py -- --out out/roots.png --size 480 >out/render.log 2>&1 ||
  { cat out/render.log; exit 1; }
echo "main: wrote out/roots.glb and out/roots.png"

#!/usr/bin/env bash
# Regenerates the documentation's pictures with headless Blender, the
# add-on loaded as the tests load it (a temporary BLENDER_USER_SCRIPTS
# whose addons/banyan links to blender_addon/banyan, BANYAN_LIB from
# build/):
#   bash tools/render_docs.sh            # everything
#   bash tools/render_docs.sh gallery    # docs/render_gallery.py only
#   (also: params, start, avenue, hosts, roots (look views),
#   ivy (look views: front, close, stems, pillar), keyaki (look
#   views: under, tree, avenue, young), production (LOD chain,
#   growth frames), segments (docs/segments.md's before/after look views);
#   extra arguments go to the script; BANYAN_LIB may name another build's
#   library, e.g. a copy of the library before a change)
#   bash tools/render_docs.sh ui         # docs/screenshots.py in a real window on Xvfb
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
lib=${BANYAN_LIB:-$here/build/libbanyan.so}
[ -f "$lib" ] || { echo "build first (tools/main.sh or cmake + ninja)"; exit 1; }
scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons"
ln -s "$here/blender_addon/banyan" "$scripts/addons/banyan"
run() {
  BLENDER_USER_SCRIPTS="$scripts" BANYAN_LIB="$lib" \
    blender -b --factory-startup --addons banyan --python-exit-code 1 --python "$@"
}
what=${1:-all}
[ $# -gt 0 ] && shift
case $what in
  gallery) run docs/render_gallery.py -- "$@" ;;
  params) run docs/render_params.py -- "$@" ;;
  start) run docs/render_getting_started.py -- "$@" ;;
  avenue) run docs/examples/render_avenue.py -- --out docs/img/avenue.png "$@" ;;
  hosts) run docs/render_hosts.py -- "$@" ;;
  ivy-mesh) run docs/measure_ivy_mesh.py -- "$@" ;;
  roots) run docs/render_roots_look.py -- "$@" ;;
  ivy) run docs/render_ivy_look.py -- "$@" ;;
  keyaki) run docs/render_keyaki_look.py -- "$@" ;;
  segments) run docs/render_segments_look.py -- "$@" ;;
  production) run docs/render_production.py -- "$@" ;;
  ui) # A real window: Blender on a virtual X display; a .blend on the command line skips the splash.
    command -v xvfb-run >/dev/null || { echo "ui needs Xvfb: apt-get install xvfb xauth"; exit 1; }
    blend="$scripts/start.blend"
    blender -b --factory-startup --python-expr "import bpy; bpy.ops.wm.save_as_mainfile(filepath='$blend')" >/dev/null
    BLENDER_USER_SCRIPTS="$scripts" BLENDER_USER_CONFIG="$scripts/config" BANYAN_LIB="$here/build/libbanyan.so" \
      xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup --enable-event-simulate \
      -p 0 0 1600 1000 "$blend" --addons banyan \
      --python docs/screenshots.py -- "$@" ;;
  all)
    run docs/render_gallery.py
    run docs/render_params.py
    run docs/render_getting_started.py
    run docs/render_hosts.py
    run docs/examples/render_avenue.py -- --out docs/img/avenue.png ;;
  *) echo "usage: tools/render_docs.sh [all|gallery|params|start|avenue|hosts|roots|ivy|keyaki|segments|ui] [script args]"; exit 2 ;;
esac

#!/usr/bin/env bash
# The modal run in a real Blender window under Xvfb (tests/blender/gui/*.py):
#   tests/blender/run_gui.sh <build_dir>
# Needs xvfb-run and a Blender binary (not the bpy module: it has no window).
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
build=$(cd "${1:?usage: run_gui.sh <build_dir>}" && pwd)
blender=${BLENDER:-blender}
command -v xvfb-run >/dev/null || { echo "xvfb-run not found"; exit 1; }
scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons" "$build/test_out/blender"
ln -s "$src/blender_addon/banyan" "$scripts/addons/banyan"
failed=0
for t in "$here"/gui/*.py; do
  name=$(basename "$t" .py)
  log="$build/test_out/blender/gui_$name.log"
  BLENDER_USER_SCRIPTS="$scripts" BLENDER_USER_CONFIG="$scripts/config" BANYAN_LIB="$build/libbanyan.so" timeout 600 \
    xvfb-run -a -s "-screen 0 1280x800x24" "$blender" --factory-startup --enable-event-simulate \
    --addons banyan --python "$t" >"$log" 2>&1
  summary=$(grep -E "^$name: [0-9]+ passed, [0-9]+ failed" "$log" | tail -1)
  if [ -z "$summary" ] || ! echo "$summary" | grep -q " 0 failed"; then
    failed=$((failed + 1))
    echo "FAILED $name: ${summary:-no summary line}"
    grep -E "^(FAIL|Traceback|  File|[A-Za-z]+Error)" "$log" | head -20 | sed 's/^/    /'
  else
    echo "ok     $summary"
  fi
  grep -E "^$name: (cancelled|[0-9]+ % done)" "$log" | sed 's/^/    /'
done
[ $failed -eq 0 ]

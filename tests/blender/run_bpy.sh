#!/usr/bin/env bash
# Runs the Blender suite (tests/blender/run.sh) inside each Blender that
# tools/blender_versions.sh installed as the bpy module from PyPI:
#   tests/blender/run_bpy.sh <build_dir> [--zip] [test_file...]
# BANYAN_BPY_VERSIONS picks the Blenders (default "4.2 4.5 5.0 5.1 5.2"), each the
# venv BANYAN_BPY_DIR/<series> (default ~/.cache/banyan/bpy/<series>).
# For each one a `blender` wrapper (venv python + tests/blender/bpy_blender.py,
# which takes the subset of Blender's command line run.sh uses) stands in
# for the binary; logs go to <build_dir>/test_out/blender/bpy-<series>/
# (<tag>-bpy-<series>/ when BANYAN_BLENDER_TAG=<tag> is set).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=${BANYAN_BPY_DIR:-$HOME/.cache/banyan/bpy}
build=${1:?usage: run_bpy.sh <build_dir> [--zip] [test_file...]}
shift
wrappers=$(mktemp -d)
trap 'rm -rf "$wrappers"' EXIT
failed=0
tag=${BANYAN_BLENDER_TAG:-}
for s in ${BANYAN_BPY_VERSIONS:-4.2 4.5 5.0 5.1 5.2}; do
  py="$root/$s/bin/python"
  if [ ! -x "$py" ]; then
    echo "FAILED bpy $s: no $py (run tools/blender_versions.sh $s)"
    failed=$((failed + 1))
    continue
  fi
  mkdir -p "$wrappers/$s"
  printf '#!/bin/sh\nexec "%s" "%s" "$@"\n' "$py" "$here/bpy_blender.py" >"$wrappers/$s/blender"
  chmod +x "$wrappers/$s/blender"
  echo "== Blender $("$py" -c "import bpy; print(bpy.app.version_string)" 2>/dev/null | tail -1) (bpy $s)"
  BLENDER="$wrappers/$s/blender" BANYAN_BLENDER_TAG="${tag:+$tag-}bpy-$s" bash "$here/run.sh" "$build" "$@" ||
    failed=$((failed + 1))
done
[ $failed -eq 0 ]

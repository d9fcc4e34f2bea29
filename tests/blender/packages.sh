#!/usr/bin/env bash
# The packages as a user gets them, with the build folder moved away:
#   tests/blender/packages.sh <build_dir>
# Copies banyan.zip and banyan_extension.zip to a temporary folder, renames
# <build_dir> (restored on exit, whatever happens), and runs
# test_packages.py (ldd inside the unpacked zip; install, enable and grow
# in a child Blender with empty user folders) in Debian's Blender and in
# every bpy Blender (run_bpy.sh), each loading the add-on from the zip.
# Logs: <build_dir>/test_out/packages/.
set -u
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: packages.sh <build_dir>}" && pwd)
tmp=$(mktemp -d)
away="$build.away.$$"
restore() {
  [ -d "$away" ] && mv "$away" "$build"
  mkdir -p "$build/test_out/packages"
  cp -r "$tmp/test_out/." "$build/test_out/packages/" 2>/dev/null
  rm -rf "$tmp"
}
trap restore EXIT
for z in banyan.zip banyan_extension.zip; do
  cp "$build/$z" "$tmp/" || { echo "FAILED packages: no $build/$z"; exit 1; }
done
mv "$build" "$away" || exit 1
echo "packages: $build moved away; zips in $tmp"
failed=0
BANYAN_ZIP_DIR="$tmp" bash "$here/run.sh" "$tmp" --zip "$here/test_packages.py" || failed=1
BANYAN_ZIP_DIR="$tmp" bash "$here/run_bpy.sh" "$tmp" --zip "$here/test_packages.py" || failed=1
[ $failed -eq 0 ]

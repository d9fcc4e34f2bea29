#!/usr/bin/env bash
# Runs every tests/blender/test_*.py in real headless Blender against the
# library in <build_dir>:   tests/blender/run.sh <build_dir> [test_file...]
# The add-on is loaded straight from the repository through a temporary
# BLENDER_USER_SCRIPTS whose addons/banyan links to blender_addon/banyan,
# with BANYAN_LIB=<build_dir>/libbanyan.so.
#   tests/blender/run.sh <build_dir> --zip [test_file...]
# instead unpacks <build_dir>/banyan.zip as the add-on and leaves BANYAN_LIB
# unset, so the library is the zip's banyan/lib/libbanyan.so.
set -u
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
build=$(cd "${1:?usage: run.sh <build_dir> [test_file...]}" && pwd)
shift
zip=0
if [ "${1:-}" = "--zip" ]; then zip=1; shift; fi
blender=${BLENDER:-blender}
command -v "$blender" >/dev/null || { echo "blender not found (tools/setup.sh installs it)"; exit 1; }

scripts=$(mktemp -d)
trap 'rm -rf "$scripts"' EXIT
mkdir -p "$scripts/addons"
out="$build/test_out/blender${BANYAN_BLENDER_TAG:+/$BANYAN_BLENDER_TAG}"
mkdir -p "$out"
# The Blender that tests starting a child Blender run (bt.BLENDER).
export BANYAN_BLENDER="$(command -v "$blender")"
export BLENDER_USER_SCRIPTS="$scripts"
if [ $zip = 1 ]; then
  [ -f "$build/banyan.zip" ] || { echo "no $build/banyan.zip (build the banyan_addon_zip target)"; exit 1; }
  python3 -c "import zipfile, sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])" "$build/banyan.zip" "$scripts/addons"
  unset BANYAN_LIB
  export BANYAN_EXPECT_LIB="$scripts/addons/banyan/lib/libbanyan.so"
  out="$out/zip"; mkdir -p "$out"
else
  ln -s "$src/blender_addon/banyan" "$scripts/addons/banyan"
  export BANYAN_LIB="$build/libbanyan.so"
  export BANYAN_EXPECT_LIB="$BANYAN_LIB"
fi
export BANYAN_SOURCE_DIR="$src"
export BANYAN_BUILD_DIR="$build"
export BANYAN_TEST_OUT="$out"
export PYTHONDONTWRITEBYTECODE=1

echo "blender tests: library $BANYAN_EXPECT_LIB"
python3 -c "import sys; sys.path.insert(0, '$here'); import config
m = config.EXPECTED_MISSING
print('expected missing generators (tests/blender/config.py):', ', '.join('%s (%s)' % kv for kv in m.items()) if m else 'none')"

if [ $# -gt 0 ]; then tests=("$@"); else tests=("$here"/test_*.py); fi
failed=0
# One line per file, with the Blender it ran on, for tools/test.sh to print
# (ctest shows a passing test's output only with -V).
summary_file="$out/summary.txt"
: >"$summary_file"
for t in "${tests[@]}"; do
  name=$(basename "$t" .py)
  log="$out/$name.log"
  "$blender" -b --factory-startup --addons banyan --python-exit-code 1 --python "$t" >"$log" 2>&1
  rc=$?
  summary=$(grep -E "^$name: [0-9]+ passed, [0-9]+ failed" "$log" | tail -1)
  version=$(grep -m1 -oE "^Blender [0-9]+\.[0-9]+\.[0-9]+" "$log")
  if [ $rc -ne 0 ] || [ -z "$summary" ]; then
    failed=$((failed + 1))
    echo "FAILED $name (exit $rc): ${summary:-no summary line} [${version:-Blender ?}]" | tee -a "$summary_file"
    grep -E "^(FAIL|SKIP|Traceback|  File|[A-Za-z]+Error)" "$log" | head -40 | sed 's/^/    /'
  else
    echo "ok     $summary [${version:-Blender ?}]" | tee -a "$summary_file"
    grep -E "^SKIP" "$log" | sort -u | sed 's/^/    /'
  fi
done
echo "blender tests${BANYAN_BLENDER_TAG:+ ($BANYAN_BLENDER_TAG)}: ${#tests[@]} files, $failed failed"
[ $failed -eq 0 ]

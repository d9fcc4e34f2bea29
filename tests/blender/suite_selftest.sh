#!/usr/bin/env bash
# The shared-Blender runner itself (tests/blender/run.sh + suite.py):
#   tests/blender/suite_selftest.sh <build_dir>
# runs the files of tests/blender/suite_selftest/ through run.sh (BLENDER
# picks the Blender, as for run.sh) and checks its report: a passing file,
# an exception, a failed check, a file without bt.done(), a file that leaves
# state behind and one that must not see it, a crash (reported failed, the
# file after it run in a new Blender). Logs: <build_dir>/test_out/blender/suite_selftest/.
set -u
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: suite_selftest.sh <build_dir>}" && pwd)
files=("$here"/suite_selftest/s*.py)
report=$(BANYAN_BLENDER_TAG=suite_selftest bash "$here/run.sh" "$build" "${files[@]}" 2>&1)
rc=$?
echo "$report"
bad=0
want() {  # a line of the report that must be there (an extended regex)
  if ! grep -qE "$1" <<<"$report"; then
    echo "SELFTEST: missing from the report: $1"
    bad=1
  fi
}
want '^ok     s1_pass: 1 passed, 0 failed \[Blender [0-9.]+, [0-9.]+ s\]$'
want '^FAILED s2_raise \(exit 1\): no summary line '
want 'ValueError: s2_raise: raised on purpose'
want '^FAILED s3_fail \(exit 1\): s3_fail: 0 passed, 1 failed '
want '^FAILED s4_nodone \(exit 0\): no summary line '
want '^ok     s5_dirty: 1 passed, 0 failed '
want '^ok     s6_clean: 9 passed, 0 failed '
want '^FAILED s7_crash \(exit (13[49]|[1-9][0-9]*)\): no summary line '
want 'the shared Blender ended \(exit [0-9]+\) inside this file'
want '^ok     s8_after: 1 passed, 0 failed '
want "^blender tests \(suite_selftest\): ${#files[@]} files, 4 failed$"
out="$build/test_out/blender/suite_selftest"
if grep -q "AFTER DONE" "$out/s3_fail.log"; then
  echo "SELFTEST: s3_fail.py ran on after bt.done()"
  bad=1
fi
if [ $rc -eq 0 ]; then
  echo "SELFTEST: run.sh exited 0 with failed files"
  bad=1
fi
[ $(wc -l <"$out/summary.txt") -eq ${#files[@]} ] || { echo "SELFTEST: summary.txt has not one line per file"; bad=1; }
[ $bad -eq 0 ] && echo "suite selftest: ok" || echo "suite selftest: FAILED"
[ $bad -eq 0 ]

#!/usr/bin/env bash
# Writes every preset's .glb with the Linux CLI and with the Windows CLI
# (under wine64) and compares them byte for byte, at 1 and 2 threads.
#   compare_presets.sh LINUX_BUILD WIN_BUILD OUT_DIR
# Prints one line per preset and thread count ("same" or "DIFFERS" with
# the first differing byte), then "N passed, N failed"; exits 1 when any
# file differs or a run fails. The files are removed after the comparison
# unless KEEP is set. THREADS (default "1 2") gives the thread counts.
set -uo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
linux=$(cd "$1" && pwd)
win=$(cd "$2" && pwd)
out=$3
mkdir -p "$out"
out=$(cd "$out" && pwd)
# shellcheck source=tools/win/wine_env.sh
. "$repo/tools/win/wine_env.sh"
export BANYAN_TEXTURE_CACHE=off
pass=0 fail=0
for p in "$repo"/presets/*.json; do
  n=$(basename "$p" .json)
  gen=$(python3 -c "import json,sys;print(json.load(open(sys.argv[1]))['generator'])" "$p")
  for t in ${THREADS:-1 2}; do
    a=$out/$n.t$t.linux.glb b=$out/$n.t$t.win.glb
    "$linux/banyan" "$gen" --preset "$p" --threads "$t" -o "$a" >/dev/null 2>"$out/$n.t$t.linux.err"
    ra=$?
    wine64 "$win/banyan.exe" "$gen" --preset "Z:$p" --threads "$t" -o "Z:$b" >/dev/null 2>"$out/$n.t$t.win.err"
    rb=$?
    if [ $ra -ne 0 ] || [ $rb -ne 0 ]; then
      echo "FAILED  $n t$t (linux exit $ra, windows exit $rb; $out/$n.t$t.*.err)"
      fail=$((fail + 1))
    elif cmp -s "$a" "$b"; then
      echo "same    $n t$t"
      pass=$((pass + 1))
    else
      echo "DIFFERS $n t$t: $(cmp "$a" "$b" 2>&1 | head -1) (sizes $(stat -c %s "$a") $(stat -c %s "$b"))"
      fail=$((fail + 1))
    fi
    [ -n "${KEEP:-}" ] || rm -f "$a" "$b" # an avenue's file is 0.5 GB
  done
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]

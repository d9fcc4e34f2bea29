#!/bin/sh
# The CLI end to end: help, refusals with clear messages and non-zero
# exits, and generators that are not built yet saying so.
bin="$1"; src="$2"; out="$3"
pass=0; fail=0
expect() { # expect CODE NEEDLE -- command...
  code="$1"; needle="$2"; shift 3
  msg=$("$@" 2>&1); rc=$?
  if [ "$rc" = "$code" ] && echo "$msg" | grep -qF -- "$needle"; then pass=$((pass+1))
  else fail=$((fail+1)); echo "FAIL: $* -> rc $rc (want $code), output: $msg"; fi
}
expect 0 "usage: banyan" -- "$bin" --help
expect 2 "unknown command" -- "$bin" oak
expect 0 "banyan 0." -- "$bin" --version
expect 0 '"triangles"' -- "$bin" tube --stats
expect 0 '"vertices": 332' -- "$bin" tube --set sides=4 --stats -o "$out/cli_tube_square.gltf"
expect 1 "sides = '2' must be a whole number within [3, 256]" -- "$bin" tube --set sides=2
expect 1 "must look like key=value" -- "$bin" tube --set sides
expect 1 "writing $out/x.obj" -- "$bin" tube -o "$out/x.obj"
expect 2 "unexpected argument" -- "$bin" tube --bogus
expect 1 "cannot read preset" -- "$bin" tube --preset /nonexistent.json
# Every generator: defaults write a glb, stats are JSON, --list documents
# the table, and --set refuses unknown keys and out-of-range values.
for g in roots keyaki avenue ivy segments; do
  expect 0 '"triangles"' -- "$bin" "$g" --stats -o "$out/cli_$g.glb"
  expect 0 "seed" -- "$bin" "$g" --list
  expect 1 "unknown $g parameter 'bogus'" -- "$bin" "$g" --set bogus=1
  expect 1 "must be finite" -- "$bin" "$g" --set max_vertices=nan
done
expect 1 "must be within" -- "$bin" roots --set sides=2
expect 1 "roots_trunk.json" -- "$bin" keyaki --preset "$src/presets/roots_trunk.json"
expect 0 '"unattached": 0' -- "$bin" segments --preset "$src/presets/segments_paper.json" --stats
# Every shipped preset loads and generates with its own command.
for p in "$src"/presets/*.json; do
  g=$(sed -n 's/.*"generator": *"\([a-z]*\)".*/\1/p' "$p" | head -1)
  expect 0 '"triangles"' -- "$bin" "$g" --preset "$p" --stats
done
echo "cli: $pass passed, $fail failed"
[ $fail = 0 ]

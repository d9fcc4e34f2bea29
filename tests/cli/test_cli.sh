#!/bin/sh
# The CLI end to end: help, refusals with clear messages and non-zero
# exits, every preset, and mesh hosts (--host and presets' "mesh").
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
expect 2 "-o $out/x.obj: must end in .glb" -- "$bin" tube -o "$out/x.obj"
expect 2 "unexpected argument" -- "$bin" tube --bogus
expect 1 "cannot read preset" -- "$bin" tube --preset /nonexistent.json
# The CLI's ivy (the step API) keeps max_vertices while it
# grows and every run keeps its time budget.
expect 1 "over max_vertices = 200000" -- "$bin" ivy --set t0=1000000 --set steps=100000 --set max_vertices=200000
expect 1 "past max_seconds = 1" -- "$bin" ivy --set t0=1000000 --set steps=100000 --set max_vertices=1000000000 \
  --set max_buds=50000000 --set max_seconds=1
expect 1 "past max_seconds = 1" -- "$bin" roots --set growth_points=10000 --set moves=100 --set main_roots=64 \
  --set max_vertices=1000000000 --set ground=0 --set max_seconds=1
# Textures: every PNG written, bad sizes refused by the library's message.
expect 0 "keyaki_leaf_summer_color.png" -- "$bin" textures -o "$out" --size 64
expect 1 "size = 1000 must be a power of two within [64, 8192]" -- "$bin" textures -o "$out" --size 1000
expect 2 "usage: banyan textures" -- "$bin" textures --size 64
expect 2 "--size 'big' must be a whole number" -- "$bin" textures -o "$out" --size big
expect 2 "--size ' 64' must be a whole number" -- "$bin" textures -o "$out" --size " 64"
expect 2 "--seed '-1' must be a whole number in [0, 2^64-1]" -- "$bin" textures -o "$out" --seed -1
# Every generator: defaults write a glb, stats are JSON, --list documents
# the table, and --set refuses unknown keys and out-of-range values.
for g in roots keyaki avenue ivy segments; do
  expect 0 '"triangles"' -- "$bin" "$g" --stats -o "$out/cli_$g.glb"
  expect 0 "seed" -- "$bin" "$g" --list
  expect 1 "unknown $g parameter 'bogus'" -- "$bin" "$g" --set bogus=1
  expect 1 "must be finite" -- "$bin" "$g" --set max_vertices=nan
done
expect 1 "must be within" -- "$bin" roots --set sides=2
# Far from the origin: the mesh's origin in the stats, the glb's node moved there.
expect 0 '"origin": [999999, -500000, 5000]' -- "$bin" keyaki --set position=999999.25,-500000,5000 --set levels=8 \
  --textures off --stats -o "$out/cli_keyaki_far.glb"
expect 1 "roots_trunk.json" -- "$bin" keyaki --preset "$src/presets/roots_trunk.json"
# Textures: on by default, size and on/off checked, named.
expect 2 "--textures 'maybe' must be on or off" -- "$bin" keyaki --textures maybe
for n in 0 100 32 16384 -64 1e3 64x; do
  expect 2 "--texture-size '$n' must be a power of two in [64, 8192]" -- "$bin" keyaki --texture-size "$n"
done
expect 0 '"triangles"' -- "$bin" keyaki --set levels=8 --set season=autumn --texture-size 64 --stats \
  -o "$out/cli_keyaki_autumn.glb"
grep -q 'image/png' "$out/cli_keyaki_autumn.glb" && grep -q 'keyaki_leaf_autumn' "$out/cli_keyaki_autumn.glb" &&
  pass=$((pass+1)) || { fail=$((fail+1)); echo "FAIL: --texture-size 64: no autumn leaf PNG in the file"; }
expect 0 '"triangles"' -- "$bin" ivy --set steps=30 --textures off --stats -o "$out/cli_ivy_flat.glb"
grep -q 'image/png' "$out/cli_ivy_flat.glb" && { fail=$((fail+1)); echo "FAIL: --textures off wrote an image"; } ||
  pass=$((pass+1))
expect 1 "season = 'winter' must be one of summer|autumn" -- "$bin" ivy --set season=winter
expect 0 '"unattached": 0' -- "$bin" segments --preset "$src/presets/segments_paper.json" --stats
# Every shipped preset loads and generates with its own command; those
# with mesh hosts grow on a host set of their meshes and their output goes
# to the glTF validator.
for p in "$src"/presets/*.json; do
  g=$(sed -n 's/.*"generator": *"\([a-z]*\)".*/\1/p' "$p" | head -1)
  if grep -q '"mesh"' "$p"; then
    n=$(basename "$p" .json)
    expect 0 '"host_set": {"boxes": 0, "meshes": 1' -- "$bin" "$g" --preset "$p" --stats -o "$out/cli_preset_$n.glb"
  else
    case "$p" in
      # A *_large preset is a benchmark (ivy_wall_large: 7 M vertices): its first 300 steps
      *_large.json) expect 0 '"triangles"' -- "$bin" "$g" --preset "$p" --set steps=300 --stats ;;
      *) expect 0 '"triangles"' -- "$bin" "$g" --preset "$p" --stats ;;
    esac
  fi
done

# --host: a glTF mesh as a host, placed with @x,y,z, added to the preset's.
hosts="$src/presets/hosts"
expect 0 '"host_set": {"boxes": 0, "meshes": 1, "triangles": 3456}' -- "$bin" roots --host "$hosts/column.glb@1.5,0,0" \
  --set growth_points=12 --stats -o "$out/cli_host_column.glb"
expect 0 '"host_set": {"boxes": 1, "meshes": 1' -- "$bin" ivy --preset "$src/presets/ivy_wall.json" \
  --host "$hosts/rock.glb@0,-2.5,0" --set steps=40 --stats
expect 0 '"host_set": {"boxes": 0, "meshes": 2' -- "$bin" roots --preset "$src/presets/roots_column.json" \
  --host "$hosts/rock.glb@3,0,0" --set growth_points=12 --stats
expect 2 "expected FILE.glb or FILE.glb@x,y,z" -- "$bin" roots --host "$hosts/rock.glb@1,2"
expect 1 "this command takes no hosts" -- "$bin" keyaki --host "$hosts/rock.glb"

# Bad mesh files are refused, naming the host, before anything grows. They
# live in a folder of their own: the validator reads every .glb in $out.
bad="$out/cli_bad_hosts"
mkdir -p "$bad"
le32() { printf "$(printf '\\%03o\\%03o\\%03o\\%03o' $(($1 & 255)) $(($1 >> 8 & 255)) $(($1 >> 16 & 255)) $(($1 >> 24 & 255)))"; }
glb() { # glb FILE JSON [BINFILE]: a glTF binary from a JSON text and a binary chunk
  js="$2"; while [ $(( $(printf '%s' "$js" | wc -c) % 4 )) != 0 ]; do js="$js "; done
  jl=$(printf '%s' "$js" | wc -c); bl=0; [ -n "$3" ] && bl=$(wc -c < "$3")
  total=$((12 + 8 + jl)); [ -n "$3" ] && total=$((total + 8 + bl))
  { printf 'glTF'; le32 2; le32 $total; le32 $jl; printf 'JSON'; printf '%s' "$js"
    if [ -n "$3" ]; then le32 $bl; printf 'BIN\000'; cat "$3"; fi; } > "$1"
}
# A tetrahedron whose last vertex has a NaN coordinate (0x7fc00000).
{ for v in 0 0 0 1065353216 0 0 0 1065353216 0 0 0 2143289344; do le32 $v; done
  for i in 0 2 1 0 1 3 0 3 2 1 2 3; do le32 $i; done; } > "$bad/tet_nan.bin"
acc='"buffers":[{"byteLength":96}],"bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":48}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},{"bufferView":1,"componentType":5125,"count":12,"type":"SCALAR"}]'
glb "$bad/nan.glb" '{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],'"$acc"'}' "$bad/tet_nan.bin"
glb "$bad/points.glb" '{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":0}]}],'"$acc"'}' "$bad/tet_nan.bin"
glb "$bad/empty.glb" '{"asset":{"version":"2.0"},"scenes":[{"nodes":[]}]}'
printf 'solid cube\nendsolid cube\n' > "$bad/cube.glb"
expect 2 "--host $bad/nan.glb: BANYAN_E_BAD_HOST: $bad/nan.glb: mesh 0" -- "$bin" roots --host "$bad/nan.glb"
expect 2 "vertex 3 is not finite" -- "$bin" ivy --host "$bad/nan.glb"
expect 2 "$bad/points.glb: has no triangles" -- "$bin" roots --host "$bad/points.glb"
expect 2 "$bad/empty.glb: has no triangles" -- "$bin" ivy --host "$bad/empty.glb"
expect 2 "$bad/cube.glb: not a glTF binary (.glb) file" -- "$bin" roots --host "$bad/cube.glb"
expect 2 "cannot open" -- "$bin" roots --host "$bad/missing.glb"
# The same files named by a preset: the message names the preset's host.
for f in nan points empty cube missing; do
  printf '{\n "generator": "roots",\n "hosts": [\n  { "center": [0, 0, 1], "half": [1, 1, 1] },\n  { "mesh": "%s.glb" }\n ]\n}\n' "$f" > "$bad/$f.json"
  expect 2 "$bad/$f.json:5: hosts[1]: $bad/$f.glb:" -- "$bin" roots --preset "$bad/$f.json"
done
printf '{ "generator": "roots", "hosts": [ { "mesh": "nan.glb", "scale": 0 } ] }\n' > "$bad/scale.json"
expect 2 "hosts[0].scale[0] = 0 must be within" -- "$bin" roots --preset "$bad/scale.json"
printf '{ "generator": "roots", "hosts": [ { "mesh": "nan.glb", "half": [1, 1, 1] } ] }\n' > "$bad/half.json"
expect 2 "hosts[0].half is unknown or malformed for a mesh host" -- "$bin" roots --preset "$bad/half.json"
# Wherever the checkout sits, a long path gives up its middle and the cause stays whole.
deep="$bad/a-directory-name-long-enough/to-stand-for/a-farm-checkout/somewhere-deep"
mkdir -p "$deep" && cp "$bad/half.json" "$deep/half.json"
expect 2 "hosts[0].half is unknown or malformed for a mesh host (keys: mesh, translation or center [3], rotation [9] or rotation_euler_deg [3], scale, closed, name)" -- "$bin" roots --preset "$deep/half.json"
# Ivy's start: on the wall's bottom face it moves to a side a
# stem can grow from; boxed in a closed 2 cm cavity it cannot grow, the
# output is still written and the exit code is 3 with a warning naming why.
expect 0 '"cannot_grow": 0' -- "$bin" ivy --preset "$src/presets/ivy_wall.json" --set start=0,0.1,0 --set steps=60 --stats
cave="$out/cli_ivy_boxed_in.json"
cat > "$cave" <<'JSON'
{ "generator": "ivy", "params": { "start": [0, 0, 1], "steps": 40 }, "hosts": [
  { "center": [0, 0, 0.985], "half": [0.05, 0.05, 0.005] }, { "center": [0, 0, 1.015], "half": [0.05, 0.05, 0.005] },
  { "center": [-0.015, 0, 1], "half": [0.005, 0.05, 0.05] }, { "center": [0.015, 0, 1], "half": [0.005, 0.05, 0.05] },
  { "center": [0, -0.015, 1], "half": [0.05, 0.005, 0.05] }, { "center": [0, 0.015, 1], "half": [0.05, 0.005, 0.05] } ] }
JSON
rm -f "$out/cli_ivy_boxed_in.glb"
expect 3 "banyan ivy: warning: the ivy could not grow: every direction from its start is blocked" -- \
  "$bin" ivy --preset "$cave" -o "$out/cli_ivy_boxed_in.glb"
if [ -s "$out/cli_ivy_boxed_in.glb" ]; then pass=$((pass+1)); else fail=$((fail+1)); echo "FAIL: boxed-in ivy not written"; fi
expect 3 '"cannot_grow": 1' -- "$bin" ivy --preset "$cave" --stats
# The progress line: only when stderr is a terminal (script gives one).
msg=$("$bin" ivy --set steps=30 -o "$out/cli_ivy_quiet.glb" 2>&1 >/dev/null)
if [ -z "$msg" ]; then pass=$((pass+1)); else fail=$((fail+1)); echo "FAIL: progress on a non-terminal: $msg"; fi
if command -v script >/dev/null; then
  for g in "ivy --set steps=30" "avenue --set count=4"; do
    msg=$(script -qec "'$bin' $g -o '$out/cli_tty.glb'" /dev/null 2>&1)
    g=${g%% *}
    if printf '%s' "$msg" | grep -q "$g *100 %"; then pass=$((pass+1))
    else fail=$((fail+1)); echo "FAIL: no progress line for $g on a terminal: $msg"; fi
  done
fi
# Strict flags: the whole token a base-10 number in range, the
# range in the message; no spaces, no sign where negative is invalid.
expect 2 "--threads 'abc' must be a whole number in [0, 64]" -- "$bin" avenue --threads abc
expect 2 "--threads '-1' must be a whole number in [0, 64]" -- "$bin" avenue --threads -1
expect 2 "--threads ' 2' must be a whole number in [0, 64]" -- "$bin" avenue --threads " 2"
expect 2 "--threads '2x' must be a whole number in [0, 64]" -- "$bin" avenue --threads 2x
expect 2 "--threads '65' must be a whole number in [0, 64]" -- "$bin" avenue --threads 65
expect 0 '"command": "avenue"' -- "$bin" avenue --threads 1 --set tree.levels=4 --stats
# Instanced avenue: the writer places the variants; --stats counts them.
expect 0 '"variants": 3, "instances": 16' -- "$bin" avenue --set variants=3 --set tree.levels=4 --texture-size 64 --stats \
  -o "$out/cli_avenue_variants.glb"
# Levels of detail: --lod writes MSFT_lod; the first level's triangles are about half.
expect 0 '"lod_triangles": [' -- "$bin" keyaki --set levels=8 --texture-size 64 --lod 0.5,0.15,billboard --stats \
  -o "$out/cli_keyaki_lod.glb"
expect 0 '"lod_triangles": [' -- "$bin" avenue --set variants=2 --set tree.levels=4 --texture-size 64 --lod 0.3,billboard \
  --stats -o "$out/cli_avenue_variants_lod.glb"
expect 0 '"command": "ivy"' -- "$bin" ivy --set steps=40 --texture-size 64 --engine-uvs --stats -o "$out/cli_ivy_engine_uvs.glb"
# --pivot-painter: the two textures beside -o, counted by --stats; refused
# without a glTF -o, with --lod, and for a mesh without wind attributes
# (no texture left).
rm -f "$out"/cli_keyaki_pp2_*
expect 0 '"pivot_painter": [{"elements": ' -- "$bin" keyaki --set levels=8 --textures off --pivot-painter --stats \
  -o "$out/cli_keyaki_pp2.glb"
for f in PivotPos_Index.exr XVector_Extent.png; do
  if [ -s "$out/cli_keyaki_pp2_$f" ]; then pass=$((pass+1)); else fail=$((fail+1)); echo "FAIL: no cli_keyaki_pp2_$f"; fi
done
expect 2 "--pivot-painter needs -o out.glb or out.gltf and no --lod" -- "$bin" keyaki --pivot-painter
expect 2 "--pivot-painter needs -o out.glb or out.gltf and no --lod" -- "$bin" keyaki --pivot-painter -o "$out/x.usda"
expect 2 "--pivot-painter needs -o out.glb or out.gltf and no --lod" -- "$bin" keyaki --pivot-painter --lod 0.5 \
  -o "$out/x.glb"
rm -f "$out"/cli_keyaki_pp2_nowind*
expect 1 "has no wind_pivot_x attribute" -- "$bin" keyaki --set levels=6 --set wind=0 --textures off --pivot-painter \
  -o "$out/cli_keyaki_pp2_nowind.glb"
if [ -e "$out/cli_keyaki_pp2_nowind_PivotPos_Index.exr" ]; then fail=$((fail+1)); echo "FAIL: a texture without wind"
else pass=$((pass+1)); fi
# --fsync only syncs before the rename: the same bytes as without.
expect 0 '"command": "keyaki"' -- "$bin" keyaki --texture-size 64 --fsync --stats -o "$out/cli_keyaki_fsync.glb"
expect 0 '"command": "keyaki"' -- "$bin" keyaki --texture-size 64 --stats -o "$out/cli_keyaki_nofsync.glb"
if cmp -s "$out/cli_keyaki_fsync.glb" "$out/cli_keyaki_nofsync.glb"; then pass=$((pass+1))
else fail=$((fail+1)); echo "FAIL: --fsync changed the file's bytes"; fi
# --threads reaches one tree and the ivy too (their own threads param), and
# the bytes do not depend on it; out of range it is refused.
for g in keyaki ivy; do
    expect 0 "\"command\": \"$g\"" -- "$bin" $g --texture-size 64 --threads 1 --stats -o "$out/cli_${g}_t1.glb"
    expect 0 "\"command\": \"$g\"" -- "$bin" $g --texture-size 64 --threads 2 --stats -o "$out/cli_${g}_t2.glb"
    if cmp -s "$out/cli_${g}_t1.glb" "$out/cli_${g}_t2.glb"; then pass=$((pass+1))
    else fail=$((fail+1)); echo "FAIL: $g --threads changed the file's bytes"; fi
done
expect 2 "must be a whole number in [0, 64]" -- "$bin" keyaki --threads 65 -o "$out/cli_keyaki_t65.glb"
expect 2 "--lod '0.5,0.6' must be up to 7 falling ratios" -- "$bin" keyaki --lod 0.5,0.6
expect 2 "--lod 'billboard,0.5' must be up to 7 falling ratios" -- "$bin" keyaki --lod billboard,0.5
expect 2 "--lod '0.5,' must be up to 7 falling ratios" -- "$bin" keyaki --lod 0.5,
expect 2 "--lod 'nan' must be up to 7 falling ratios" -- "$bin" keyaki --lod nan
expect 1 "--seed: seed = ' -1' must be a whole number in [0, 2^64-1]" -- "$bin" roots --seed " -1"
expect 1 "--seed: seed = '-1' must be a whole number in [0, 2^64-1]" -- "$bin" roots --seed -1
expect 1 "--seed: seed = '18446744073709551616' must be a whole number" -- "$bin" roots --seed 18446744073709551616
expect 2 "--texture-size ' 64' must be a power of two in [64, 8192]" -- "$bin" tube --texture-size " 64"
expect 1 "sides = '+8' must be a whole number within [3, 256]" -- "$bin" tube --set sides=+8
expect 1 "radius = ' 0.5' is not a decimal number" -- "$bin" roots --set "radius= 0.5"
expect 1 "radius needs 1 number, got 2" -- "$bin" roots --set radius=0,5
expect 1 "radius = '0x1' has trailing text 'x1'" -- "$bin" roots --set radius=0x1
expect 2 "expected FILE.glb or FILE.glb@x,y,z" -- "$bin" roots --host "$out/x.glb@1,2,0x3"
# Numbers read the same under a comma-decimal locale (the CLI itself keeps
# the C locale; the library must not care either way).
if locale -a 2>/dev/null | grep -qi '^de_DE\.utf-\?8$'; then
  expect 0 '"triangles"' -- env LC_ALL=de_DE.UTF-8 "$bin" roots --set radius=0.5 --set forward_max=2.5 --stats
else
  echo "SKIP: de_DE.UTF-8 is not installed (tools/setup.sh generates it)"
fi
# Explicit empty lists are refused, naming the key; a missing key keeps
# the default.
printf '{"generator": "roots", "hosts": []}' > "$out/cli_empty_hosts.json"
expect 2 "cli_empty_hosts.json:1: hosts is an empty list" -- "$bin" roots --preset "$out/cli_empty_hosts.json"
expect 2 "hosts is an empty list" -- "$bin" roots --preset "$out/cli_empty_hosts.json" --host "$hosts/column.glb"
printf '{"generator": "ivy", "hosts": []}' > "$out/cli_empty_hosts_ivy.json"
expect 2 "hosts is an empty list" -- "$bin" ivy --preset "$out/cli_empty_hosts_ivy.json"
printf '{"generator": "segments",\n "segments": []}' > "$out/cli_empty_segments.json"
expect 1 "cli_empty_segments.json:2: segments is an empty list" -- "$bin" segments --preset "$out/cli_empty_segments.json"
# A huge preset is refused by size, naming the limit, not read whole.
truncate -s 200M "$out/cli_huge_preset.json"
expect 1 "cli_huge_preset.json is larger than the 4194304-byte limit for presets" -- \
  "$bin" roots --preset "$out/cli_huge_preset.json"
rm -f "$out/cli_huge_preset.json"
expect 1 "cannot read preset $out: Is a directory" -- "$bin" roots --preset "$out"
echo "cli: $pass passed, $fail failed"
[ $fail = 0 ]

#!/bin/sh
# Compact glTF (--compact) end to end: for keyaki_mature (at most 30 % of
# the plain file), ivy_wall, the default roots, a keyaki with levels of
# detail and a billboard, and avenue variants (instances, engine uv sets),
# the compact file decodes (meshoptimizer) to the plain one within the
# quantization (tests/c/io/compact_compare.c) and passes the Khronos
# validator; the compact bytes are the same on a second run on one thread.
#   test_compact.sh BANYAN_CLI COMPACT_COMPARE NODE SOURCE_DIR OUT_DIR
set -u
cli=$1 cmp=$2 node=$3 src=$4 out=$5/compact
mkdir -p "$out"
rm -f "$out"/*.glb "$out"/*.gltf
fail=0
run() { # name max_ratio compare-flag cli-args...
    name=$1 ratio=$2 flag=$3
    shift 3
    "$cli" "$@" -o "$out/$name.glb" >/dev/null || { echo "FAIL: $name: plain write"; fail=1; return; }
    "$cli" "$@" --compact -o "$out/${name}_compact.glb" >/dev/null || { echo "FAIL: $name: compact write"; fail=1; return; }
    "$cmp" $flag "$out/$name.glb" "$out/${name}_compact.glb" $ratio || { echo "FAIL: $name: compact_compare"; fail=1; }
    # The same bytes on a second run, on one thread.
    "$cli" "$@" --threads 1 --compact -o "$out/${name}_again.glb" >/dev/null
    cmp -s "$out/${name}_compact.glb" "$out/${name}_again.glb" || { echo "FAIL: $name: compact bytes differ between runs"; fail=1; }
    rm -f "$out/${name}_again.glb"
}
run keyaki_mature 0.30 "" keyaki --preset "$src/presets/keyaki_mature.json"
run ivy_wall "" "" ivy --preset "$src/presets/ivy_wall.json"
run roots "" "" roots
run keyaki_lod "" "" keyaki --preset "$src/presets/keyaki_young.json" --lod 0.5,0.15,billboard --texture-size 64
run avenue "" --engine-uvs avenue --preset "$src/presets/avenue_young.json" --engine-uvs --textures off
run avenue_instanced "" "" avenue --preset "$src/presets/avenue_young.json" --set end=18,0,0 --set variants=3 --texture-size 64
# A .gltf (JSON, data URI) compact file passes the validator too.
"$cli" roots --compact --textures off -o "$out/roots_compact.gltf" >/dev/null || { echo "FAIL: roots .gltf"; fail=1; }
# No leftover temporary file beside the targets.
left=$(ls -A "$out" | grep -v -E '^[a-z_]+\.(glb|gltf)$')
[ -z "$left" ] || { echo "FAIL: files left beside the targets: $left"; fail=1; }
rm -f "$out"/keyaki_mature.glb "$out"/ivy_wall.glb "$out"/roots.glb "$out"/keyaki_lod.glb "$out"/avenue.glb "$out"/avenue_instanced.glb
"$node" "$src/tests/gltf/validate.mjs" --no-warnings "$out" || { echo "FAIL: validator"; fail=1; }
[ $fail = 0 ] && echo "compact: all passed"
exit $fail

#!/bin/sh
# The OpenVDB module (csrc/roots/fused_vdb_module.c): libbanyan.so does not
# link OpenVDB; libbanyan_vdb.so, beside it, exports fused_vdb_mesh alone;
# a keyaki run never loads it and a fused roots run does; without the
# module a fused roots run fails with the error naming it, and tubes still
# grow. Usage: test_vdb_module.sh CLI LIB MODULE
set -u
cli=$1 lib=$2 module=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { if [ "$1" = 0 ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAILED: $2"; fi; }

readelf -d "$lib" | grep NEEDED | grep -qiE 'openvdb|boost|blosc|Imath'
ok $((1 - $?)) "libbanyan.so links OpenVDB or its dependencies: $(readelf -d "$lib" | grep NEEDED | tr -s ' ' | tr '\n' ' ')"
syms=$(nm -D --defined-only "$module" | awk '$2 ~ /[TDBRVW]/ {print $3}' | grep -vE '^(_init|_fini|_edata|_end|__bss_start)$')
[ "$syms" = fused_vdb_mesh ]
ok $? "libbanyan_vdb.so exports: $syms"

LD_DEBUG=files "$cli" keyaki --set levels=3 --textures off -o "$tmp/k.glb" 2>"$tmp/k.log" >/dev/null
ok $? "keyaki run"
! grep -qE 'libbanyan_vdb|libopenvdb' "$tmp/k.log"
ok $? "a keyaki run loaded OpenVDB"
LD_DEBUG=files "$cli" roots --set growth_points=10 --textures off -o "$tmp/r.glb" 2>"$tmp/r.log" >/dev/null
ok $? "fused roots run: $(grep -v '^ *[0-9]*:' "$tmp/r.log" | tail -2)"
grep -q 'libopenvdb' "$tmp/r.log"
ok $? "a fused roots run did not load OpenVDB"

# libbanyan.so alone in a folder (LD_LIBRARY_PATH is searched before the CLI's RUNPATH).
mkdir "$tmp/alone"
cp "$lib" "$tmp/alone/"
LD_LIBRARY_PATH="$tmp/alone" "$cli" roots --set growth_points=10 --textures off -o "$tmp/a.glb" >"$tmp/a.out" 2>&1
rc=$?
[ $rc != 0 ] && grep -q 'libbanyan_vdb.so' "$tmp/a.out" && [ ! -e "$tmp/a.glb" ]
ok $? "fused roots without the module: exit $rc, $(cat "$tmp/a.out" | tail -1)"
LD_LIBRARY_PATH="$tmp/alone" "$cli" roots --set growth_points=10 --set surface=tubes --textures off -o "$tmp/t.glb" >/dev/null 2>&1
ok $? "tube roots without the module"
cp "$module" "$tmp/alone/"
LD_LIBRARY_PATH="$tmp/alone" "$cli" roots --set growth_points=10 --textures off -o "$tmp/b.glb" >/dev/null 2>&1 && cmp -s "$tmp/b.glb" "$tmp/r.glb"
ok $? "fused roots with the module copied beside the library: the same bytes"

echo "vdb_module: $pass passed, $fail failed"
[ $fail = 0 ]

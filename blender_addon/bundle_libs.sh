#!/bin/sh
# bundle_libs.sh LIB DIR: copies into DIR every shared library that LIB
# needs (as ldd resolves them here) except glibc's and the C++ runtime's,
# which every Linux that runs Blender has, sets the RUNPATH of LIB's copy
# in DIR and of every copied library to $ORIGIN (patchelf), so the dynamic
# linker finds them beside each other on a machine without Debian's
# libcjson, Embree, TBB or tinygltf, and writes DIR/bundled.txt with their
# names, dependencies first (tests and docs read it). A library of the
# same soname that the process already loaded is used instead (Blender
# 4.5+ ships its own libtbb.so.12): one TBB runtime per process.
set -eu
lib=$1
dir=$2
: >"$dir/bundled.txt"
ldd "$lib" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' |
  grep -vE '^(libc|libm|libdl|libpthread|librt|libutil|libstdc\+\+|libgcc_s|ld-linux[^ ]*)\.so' |
  tac | while read -r soname path; do
    cp -L "$path" "$dir/$soname"
    chmod u+w "$dir/$soname"
    patchelf --set-rpath '$ORIGIN' "$dir/$soname"
    echo "$soname" >>"$dir/bundled.txt"
  done
patchelf --set-rpath '$ORIGIN' "$dir/$(basename "$lib")"

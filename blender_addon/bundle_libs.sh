#!/bin/sh
# bundle_libs.sh LIB DIR: copies into DIR every shared library that LIB
# needs (as ldd resolves them here) except glibc's and the C++ runtime's,
# which every Linux that runs Blender has, and writes DIR/bundled.txt with
# their names in an order that loads dependencies first (core/lib.py
# loads them before LIB, so a machine without Debian's libcjson, Embree,
# TBB or tinygltf still loads the add-on's library).
set -eu
lib=$1
dir=$2
: >"$dir/bundled.txt"
ldd "$lib" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' |
  grep -vE '^(libc|libm|libdl|libpthread|librt|libutil|libstdc\+\+|libgcc_s|ld-linux[^ ]*)\.so' |
  tac | while read -r soname path; do
    cp -L "$path" "$dir/$soname"
    echo "$soname" >>"$dir/bundled.txt"
  done

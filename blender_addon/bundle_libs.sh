#!/bin/sh
# bundle_libs.sh DIR LIB...: copies into DIR every shared library that the
# LIBs need (as ldd resolves them here) except glibc's and the C++
# runtime's, which every Linux that runs Blender has, sets the RUNPATH of
# the LIBs' copies in DIR and of every copied library to $ORIGIN
# (patchelf), so the dynamic linker finds them beside each other on a
# machine without Debian's libcjson, Embree, TBB, tinygltf or OpenVDB, and
# writes DIR/bundled.txt with their names, dependencies first (tests and
# docs read it). The LIBs are libbanyan.so and the module it loads
# (libbanyan_vdb.so), already copied into DIR. A library of the same
# soname that the process already loaded is used instead (Blender 4.5+
# ships its own libtbb.so.12): one TBB runtime per process.
set -eu
dir=$1
shift
: >"$dir/bundled.txt"
for lib in "$@"; do
  ldd "$lib" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' |
    grep -vE '^(libc|libm|libdl|libpthread|librt|libutil|libstdc\+\+|libgcc_s|ld-linux[^ ]*)\.so' |
    tac | while read -r soname path; do
      grep -qxF "$soname" "$dir/bundled.txt" && continue
      cp -L "$path" "$dir/$soname"
      chmod u+w "$dir/$soname"
      patchelf --set-rpath '$ORIGIN' "$dir/$soname"
      echo "$soname" >>"$dir/bundled.txt"
    done
  patchelf --set-rpath '$ORIGIN' "$dir/$(basename "$lib")"
done

#!/bin/sh
# The shared library exports banyan_* symbols only, including the ABI calls.
lib="$1"
syms=$(nm -D --defined-only "$lib" | awk '$2 ~ /[TDBRVW]/ {print $3}')
bad=$(echo "$syms" | grep -vE '^(banyan_|_init$|_fini$|_edata$|_end$|__bss_start$)')
fail=0
if [ -n "$bad" ]; then echo "exported outside banyan_*:"; echo "$bad" | head -20; fail=1; fi
for s in banyan_abi_version banyan_sizeof_mesh banyan_sizeof_box banyan_sizeof_error banyan_mesh_free banyan_gltf_write \
         banyan_texture_generate banyan_image_png banyan_sizeof_image banyan_sizeof_texture_params; do
  echo "$syms" | grep -qx "$s" || { echo "missing export: $s"; fail=1; }
done
n=$(echo "$syms" | grep -c '^banyan_')
if [ $fail = 0 ]; then echo "exported_symbols: 1 passed, 0 failed ($n banyan_* symbols)"; else echo "exported_symbols: 0 passed, 1 failed"; fi
exit $fail

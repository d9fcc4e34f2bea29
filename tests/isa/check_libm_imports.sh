#!/bin/sh
# No object of the library (its static archive) and not the CLI calls a libm
# function that glibc picks per CPU: those go through csrc/base/dmath.h.
# Allowed: OpenVDB's header code compiled into the fused-surface shim
# (AffineMap::hasUniformScale's pow, Mat4's rotations' sincos), which
# checks transforms and does not make geometry.
archive="$1"
cli="$2"
dispatched='^(sin|cos|tan|sincos|asin|acos|atan|atan2|exp|exp2|exp10|log|log2|log10|pow|sinf|cosf|tanf|sincosf|asinf|acosf|atanf|atan2f|expf|exp2f|logf|log2f|log10f|powf)$'
# nm -A prints archive:member:; keep the member name only.
bad=$(nm -A --undefined-only "$archive" 2>/dev/null | sed -E 's/^[^:]*:([^:]*):.* U /\1 /' |
      awk -v re="$dispatched" '$2 ~ re' | grep -v -E '^fused_vdb\.cpp\.o (pow|sincos)$')
bad_cli=$(nm --undefined-only "$cli" | awk '{print $NF}' | sed 's/@.*//' | grep -E "$dispatched")
n=$(nm -A --undefined-only "$archive" | grep -c -E ' U Sleef_')
fail=0
if [ -n "$bad" ]; then echo "library objects calling glibc's CPU-dispatched libm:"; echo "$bad" | head -40; fail=1; fi
if [ -n "$bad_cli" ]; then echo "the CLI calls glibc's CPU-dispatched libm:"; echo "$bad_cli"; fail=1; fi
if [ "$n" -eq 0 ]; then echo "no object calls SLEEF: is csrc/base/dmath.h in use?"; fail=1; fi
if [ $fail = 0 ]; then echo "deterministic_math: 1 passed, 0 failed ($n calls to SLEEF)"; else echo "deterministic_math: 0 passed, 1 failed"; fi
exit $fail

#!/bin/sh
# No object of the library (its static archive) and not the CLI calls a libm
# function that glibc picks per CPU: those go through csrc/base/dmath.h.
# Allowed: OpenVDB's header code compiled into the fused-surface shim
# (AffineMap::hasUniformScale's pow, Mat4's rotations' sincos), which
# checks transforms and does not make geometry.
# The SLEEF functions they call are SLEEF's compiled from third_party/sleef
# into the archive and the CLI, none of a SLEEF library of the system's:
# every Sleef_ name an object needs is defined in the archive, and the CLI
# needs none from outside.
archive="$1"
cli="$2"
dispatched='^(sin|cos|tan|sincos|asin|acos|atan|atan2|exp|exp2|exp10|log|log2|log10|pow|sinf|cosf|tanf|sincosf|asinf|acosf|atanf|atan2f|expf|exp2f|logf|log2f|log10f|powf)$'
# nm -A prints archive:member:; keep the member name only.
bad=$(nm -A --undefined-only "$archive" 2>/dev/null | sed -E 's/^[^:]*:([^:]*):.* U /\1 /' |
      awk -v re="$dispatched" '$2 ~ re' | grep -v -E '^fused_vdb\.cpp\.o (pow|sincos)$')
bad_cli=$(nm --undefined-only "$cli" | awk '{print $NF}' | sed 's/@.*//' | grep -E "$dispatched")
n=$(nm -A --undefined-only "$archive" | grep -c -E ' U Sleef_')
defined=$(nm --defined-only "$archive" 2>/dev/null | awk '$2 == "T" && $3 ~ /^Sleef_/ {print $3}' | sort -u)
outside=$(nm --undefined-only "$archive" 2>/dev/null | awk '$1 == "U" && $2 ~ /^Sleef_/ {print $2}' | sort -u |
          while read -r f; do echo "$defined" | grep -qxF "$f" || echo "$f"; done)
outside_cli=$(nm --undefined-only "$cli" | awk '{print $NF}' | sed 's/@.*//' | grep -E '^Sleef_')
fail=0
if [ -n "$bad" ]; then echo "library objects calling glibc's CPU-dispatched libm:"; echo "$bad" | head -40; fail=1; fi
if [ -n "$bad_cli" ]; then echo "the CLI calls glibc's CPU-dispatched libm:"; echo "$bad_cli"; fail=1; fi
if [ -n "$outside" ]; then echo "SLEEF functions the archive calls but does not hold (third_party/sleef):"; echo "$outside"; fail=1; fi
if [ -n "$outside_cli" ]; then echo "SLEEF functions the CLI takes from a shared library:"; echo "$outside_cli"; fail=1; fi
if [ "$n" -eq 0 ]; then echo "no object calls SLEEF: is csrc/base/dmath.h in use?"; fail=1; fi
if [ $fail = 0 ]; then echo "deterministic_math: 1 passed, 0 failed ($n calls to SLEEF)"; else echo "deterministic_math: 0 passed, 1 failed"; fi
exit $fail

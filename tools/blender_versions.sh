#!/usr/bin/env bash
# Installs the Blenders beyond Debian's 3.4 as the `bpy` module from PyPI,
# one virtual environment per Blender, for tests/blender/run_bpy.sh:
#   tools/blender_versions.sh [4.2 4.5 5.0 5.1 5.2]      (default: all five)
# Each venv is BANYAN_BPY_DIR/<series> (default ~/.cache/banyan/bpy/4.2 ...),
# made with the CPython that series' wheels are built for and holding the
# latest bpy patch release of that series: Debian's /usr/bin/python3.11 up to
# 5.0, CPython 3.13 from 5.1 on (pyenv's ~/.pyenv/versions/3.13.*, which the
# machine image has; the bare `python3.13` shim refuses without PYENV_VERSION,
# so the interpreter is called by its path; BANYAN_PY313 overrides). Idempotent:
# a venv whose `import bpy` already reports the series is left as it is, so
# the wheels (300-400 MB each) are downloaded once; remove the folder to
# upgrade. Also installs (apt-get, only when missing) the X/GL client
# libraries that `import bpy` loads even with no window.
set -eu
series=("$@")
[ ${#series[@]} -gt 0 ] || series=(4.2 4.5 5.0 5.1 5.2)
root=${BANYAN_BPY_DIR:-$HOME/.cache/banyan/bpy}
log() { echo "blender_versions: $*"; }

# The CPython a series' wheels need: 3.11 up to 5.0, 3.13 from 5.1 on.
python_for() {
  case "$1" in
    [0-4].*|5.0) echo /usr/bin/python3.11 ;;
    *)
      if [ -n "${BANYAN_PY313:-}" ]; then echo "$BANYAN_PY313"; return; fi
      local c
      for c in "${PYENV_ROOT:-$HOME/.pyenv}"/versions/3.13.*/bin/python3.13 /usr/bin/python3.13 /usr/local/bin/python3.13; do
        [ -x "$c" ] && { echo "$c"; return; }
      done
      echo "blender_versions: bpy $1 needs CPython 3.13: none in ${PYENV_ROOT:-$HOME/.pyenv}/versions/3.13.*," \
           "/usr/bin or /usr/local/bin (set BANYAN_PY313)" >&2
      return 1 ;;
  esac
}

# Debian packages: python3.11 + venv, and the system libraries that
# bpy/__init__.so links (ldd, mapped with dpkg -S; everything else ships in
# the wheel's bpy/lib): X11 and GL client libraries even with no window.
# libxxf86vm1 and libgomp1 are 4.2's only.
debs=(python3.11 python3.11-venv libx11-6 libxrender1 libxxf86vm1 libxfixes3 libxi6 libxkbcommon0 libsm6 libice6
      libgl1 libglx0 libxext6 libgomp1)
missing=()
for d in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$d" 2>/dev/null | grep -q "install ok installed" || missing+=("$d")
done
if [ ${#missing[@]} -gt 0 ]; then
  log "apt-get install ${missing[*]}"
  if [ "$(id -u)" = 0 ]; then sudo=; else sudo=sudo; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

mkdir -p "$root"
no_python=()
for s in "${series[@]}"; do
  venv="$root/$s"
  if [ -x "$venv/bin/python" ] &&
     v=$("$venv/bin/python" -c "import bpy; print('%d.%d.%d' % bpy.app.version)" 2>/dev/null | tail -1) &&
     [ "${v%.*}" = "$s" ]; then
    log "$s: bpy $v in $venv (cached)"
    continue
  fi
  if ! py=$(python_for "$s"); then
    no_python+=("$s")
    continue
  fi
  rm -rf "$venv"
  t0=$(date +%s)
  "$py" -m venv "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check "bpy==$s.*"
  t1=$(date +%s)
  v=$("$venv/bin/python" -c "import bpy; print('%d.%d.%d' % bpy.app.version)" | tail -1)
  size=$(du -sm "$venv" | cut -f1)
  log "$s: bpy $v installed in $venv in $((t1 - t0)) s ($size MB)"
done
if [ ${#no_python[@]} -gt 0 ]; then
  log "not installed, no CPython for them: ${no_python[*]}"
  exit 1
fi

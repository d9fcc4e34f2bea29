#!/usr/bin/env bash
# Installs pinned PyPI tools into one cached virtual environment outside
# the repository and prints its folder on its last line:
#   tools/py_venv.sh VENV REQUIREMENTS CHECK
# VENV the venv's folder, REQUIREMENTS a file with every version pinned,
# CHECK a Python statement the installed tools must pass ("import ...").
# Made with BANYAN_VENV_PYTHON (default Debian's /usr/bin/python3, else
# python3). Idempotent: a venv whose stamp holds the requirements file's
# SHA-256 is left as it is; a changed requirements file rebuilds it; one
# install at a time (tests run in parallel). Installs python3-venv
# (apt-get) only when the interpreter cannot make a venv. Exits non-zero
# when it cannot install. Used by tools/farm/farm_venv.sh and
# tools/usd/usd_venv.sh.
set -eu
venv=$1 req=$2 check=$3
py=${BANYAN_VENV_PYTHON:-}
if [ -z "$py" ]; then
  if [ -x /usr/bin/python3 ]; then py=/usr/bin/python3; else py=$(command -v python3); fi
fi
name=$(basename "$venv")
log() { echo "py_venv ($name): $*" >&2; }
want=$(sha256sum "$req" | cut -d' ' -f1)
mkdir -p "$(dirname "$venv")"
exec 9>"$venv.lock"
flock 9
stamp="$venv/.banyan-requirements.sha256"
if [ -x "$venv/bin/python" ] && [ "$(cat "$stamp" 2>/dev/null)" = "$want" ]; then
  log "cached in $venv"
  echo "$venv"
  exit 0
fi
if ! "$py" -c "import ensurepip, venv" 2>/dev/null; then
  log "apt-get install python3-venv"
  if [ "$(id -u)" = 0 ]; then sudo=; else sudo=sudo; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends python3-venv
fi
rm -rf "$venv"
t0=$(date +%s)
"$py" -m venv "$venv"
"$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$req"
"$venv/bin/python" -c "$check"
echo "$want" > "$stamp"
log "installed $(grep -c '==' "$req") pinned packages in $venv in $(( $(date +%s) - t0 )) s"
echo "$venv"

#!/usr/bin/env bash
# Installs the PyPI tools of the farm tests into one cached virtual
# environment, outside the repository:
#   tools/farm/farm_venv.sh            prints the venv's folder on its last line
# The venv is BANYAN_FARM_VENV (default ~/.cache/banyan/farm-venv), made
# with BANYAN_FARM_PYTHON (default Debian's /usr/bin/python3, else python3)
# and holding tools/farm/farm_requirements.txt, every version pinned:
# openjd-cli (Open Job Description's `openjd check` / `openjd run`) and
# dask + distributed (tools/farm/dask/submit.py). Idempotent: a venv whose
# stamp holds the requirements file's SHA-256 is left as it is; a changed
# requirements file rebuilds it. Installs python3-venv (apt-get) only when
# the interpreter cannot make a venv. Exits non-zero when it cannot install.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
req="$here/farm_requirements.txt"
venv=${BANYAN_FARM_VENV:-$HOME/.cache/banyan/farm-venv}
py=${BANYAN_FARM_PYTHON:-}
if [ -z "$py" ]; then
  if [ -x /usr/bin/python3 ]; then py=/usr/bin/python3; else py=$(command -v python3); fi
fi
log() { echo "farm_venv: $*" >&2; }
want=$(sha256sum "$req" | cut -d' ' -f1)
mkdir -p "$(dirname "$venv")"
exec 9>"$venv.lock" # one install at a time (tests run in parallel)
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
"$venv/bin/python" -c "import dask.distributed, openjd.cli" # the installed tools load
echo "$want" > "$stamp"
log "installed $(grep -c '==' "$req") pinned packages in $venv in $(( $(date +%s) - t0 )) s"
echo "$venv"

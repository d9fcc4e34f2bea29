#!/usr/bin/env bash
# OpenUSD's Python library (tools/usd/usd_requirements.txt) in one cached
# venv, BANYAN_USD_VENV (default ~/.cache/banyan/usd-venv), by
# tools/py_venv.sh; prints its folder on its last line.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
exec bash "$here/../py_venv.sh" "${BANYAN_USD_VENV:-$HOME/.cache/banyan/usd-venv}" "$here/usd_requirements.txt" \
  "from pxr import Usd, UsdValidation"

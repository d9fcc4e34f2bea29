#!/usr/bin/env bash
# The farm tests' PyPI tools (tools/farm/farm_requirements.txt: openjd-cli
# for `openjd check` / `openjd run`, dask + distributed for
# tools/farm/dask/submit.py) in one cached venv, BANYAN_FARM_VENV (default
# ~/.cache/banyan/farm-venv), by tools/py_venv.sh; prints its folder on its
# last line.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
exec bash "$here/../py_venv.sh" "${BANYAN_FARM_VENV:-$HOME/.cache/banyan/farm-venv}" "$here/farm_requirements.txt" \
  "import dask.distributed, openjd.cli"

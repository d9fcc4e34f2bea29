"""What the batch runner's python3 tests share: the paths (the repository,
the add-on's runner, the tiny avenue preset, the build folder from
argv[1]; BANYAN_LIB defaults to its library), the check tally, file
hashes and the farm venv of tools/farm/farm_venv.sh."""
import glob
import hashlib
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "..", ".."))
ADDON = os.path.join(SRC, "blender_addon", "banyan")
RUNNER = os.path.join(ADDON, "batch_run.py")
PRESET = os.path.join(HERE, "avenue_batch_tiny.json")
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(SRC, "build"))
os.environ.setdefault("BANYAN_LIB", os.path.join(BUILD, "libbanyan.so"))
sys.path.insert(0, os.path.join(SRC, "tests", "pycommon"))
from tally import check, finish  # noqa: E402,F401  (the batch tests take them from here)

def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def outputs(folder, pattern="*"):
    """{name: sha256} of the runner's files in folder matching pattern,
    manifest.json left out (the records hold times and hosts)."""
    return {os.path.basename(p): sha(p) for p in sorted(glob.glob(os.path.join(folder, pattern)))
            if os.path.isfile(p) and not p.endswith("manifest.json")}


def manifest_files(folder):
    """{name: sha256} of the files manifest.json lists, or None."""
    try:
        with open(os.path.join(folder, "manifest.json")) as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return None
    return {e["name"]: e["sha256"] for r in doc["records"] for e in r["files"]}


def farm_venv():
    """The farm venv's folder (tools/farm/farm_venv.sh installs it on first
    use); exits 1 when it cannot be installed."""
    r = subprocess.run(["bash", os.path.join(SRC, "tools", "farm", "farm_venv.sh")], stdout=subprocess.PIPE,
                       text=True, timeout=900)
    if not check(r.returncode == 0 and r.stdout.strip(),
                 "tools/farm/farm_venv.sh installs the farm venv (exit %d)" % r.returncode):
        sys.exit(1)
    return r.stdout.strip().splitlines()[-1]

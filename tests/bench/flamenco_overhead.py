#!/usr/bin/env python3
"""Per-task overhead of the Flamenco job type (tools/farm/flamenco/banyan-batch.js).

What a farm adds per task is (1) the engine's own overhead: dispatch, status
updates, log upload, from submit to done, and (2) the command's fixed cost:
one Blender start and one library load per task, whatever K. (1) needs a
Flamenco Manager and Workers, which cannot be installed on banyan's build
machines (tools/farm/flamenco/install.sh exits 3 there), so this script only
reports it as not measured. (2) is measured here, with the job
type's own command lines (compile_job.mjs, variables expanded for this
machine), in turn, medians:

  empty task  a seed task whose seeds are all done (the runner skips them):
              process start + runner + library load + checks, no generation;
              through Blender (blender-render) and with Python 3 (exec)
  seed task   the Python task on an empty folder: K seeds made
  per seed    (seed task - empty Python task) / K

and the fixed cost's share of a task for several K.
    flamenco_overhead.py --lib build/libbanyan.so [--runs 5] [--k 5] [--write tests/bench/peers/flamenco.md]
"""
import argparse
import datetime
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from machine_info import cpu_model  # noqa: E402  (tests/bench/)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
COMPILE = os.path.join(ROOT, "tools", "farm", "flamenco", "compile_job.mjs")
JOBTYPE = os.path.join(ROOT, "tools", "farm", "flamenco", "banyan-batch.js")
ADDON = os.path.join(ROOT, "blender_addon", "banyan")
PRESET = os.path.join(ROOT, "tests", "batch", "avenue_batch_tiny.json")
FLAMENCO_BIN = os.environ.get("FLAMENCO_BIN", os.path.expanduser("~/.cache/banyan/flamenco/bin"))



def task_argv(blender, k, out, python):
    """The job type's command line for one glTF-only task of k seeds:
    exec with Python 3, or Blender when python is empty."""
    settings = {"preset": PRESET, "first_seed": 0, "seed_count": k, "seeds_per_task": k,
                "output_dir": out, "threads": 1, "merge_manifest": False, "python": python}
    p = subprocess.run(["node", COMPILE, JOBTYPE, "--settings", json.dumps(settings),
                        "--var", "blender=" + blender, "--var", "blenderArgs=-b -y", "--var", "banyan=" + ADDON],
                       capture_output=True, text=True, check=True)
    tasks = json.loads(p.stdout)["tasks"]
    assert len(tasks) == 1
    return tasks[0]["commands"][0]["argv"]


def timed(argv, env):
    t0 = time.perf_counter()
    subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lib", required=True)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--k", type=int, default=5, help="seeds in the measured task")
    ap.add_argument("--write", help="write the results as Markdown here")
    a = ap.parse_args()
    blender = shutil.which(a.blender) or a.blender
    env = dict(os.environ, BANYAN_LIB=os.path.abspath(a.lib))
    have_flamenco = all(os.access(os.path.join(FLAMENCO_BIN, b), os.X_OK)
                        for b in ("flamenco-manager", "flamenco-worker"))

    py = sys.executable
    work = tempfile.mkdtemp(prefix="banyan-flamenco-bench-")
    try:
        done_dir = os.path.join(work, "done")
        subprocess.run(task_argv(blender, a.k, done_dir, py), env=env, stdout=subprocess.DEVNULL, check=True)
        empty_b, empty_p, full = [], [], []
        for i in range(a.runs):  # in turn: the machine's load drifts
            empty_b.append(timed(task_argv(blender, a.k, done_dir, ""), env))
            empty_p.append(timed(task_argv(blender, a.k, done_dir, py), env))
            fresh = os.path.join(work, "fresh%d" % i)
            full.append(timed(task_argv(blender, a.k, fresh, py), env))
            shutil.rmtree(fresh)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    eb, ep, f = statistics.median(empty_b), statistics.median(empty_p), statistics.median(full)
    per_seed = (f - ep) / a.k
    load = os.getloadavg()

    def runs(xs):
        return ", ".join("%.2f" % x for x in xs)
    lines = [
        "## Flamenco: per-task overhead (issue #24)",
        "",
        "Written by `tests/bench/flamenco_overhead.py` on %s. Machine: %s, %d cores, load average %.1f at "
        "the end; %d runs each, in turn, medians. The machine was shared: compare the rows with each other, "
        "not with another day's." % (datetime.date.today().isoformat(), cpu_model(), os.cpu_count(), load[0],
                                     a.runs),
        "",
        "- Flamenco's own overhead (submit to done, beyond the tasks' run time): **not measured**. "
        + ("Flamenco is installed in %s but this script does not drive it yet." % FLAMENCO_BIN if have_flamenco else
           "Flamenco cannot be installed on this machine (the Go module proxy refuses its module; "
           "`tools/farm/flamenco/install.sh` exits 3)."),
        "- The job type's fixed cost per task, measured on tasks whose %d seeds are already done (the runner "
        "checks and skips them), with the command lines the job type authors:" % a.k,
        "  - through Blender (`blender-render`; every task when `python` is empty, else only tasks that "
        "render): **%.2f s** (runs: %s);" % (eb, runs(empty_b)),
        "  - with Python 3 (`exec`, glTF-only tasks): **%.2f s** (runs: %s)." % (ep, runs(empty_p)),
        "- A Python task making %d seeds of `tests/batch/avenue_batch_tiny.json` (glTF only, 1 thread): "
        "%.2f s (runs: %s), so **%.2f s per seed**." % (a.k, f, runs(full), per_seed),
        "",
        "Share of a glTF-only task spent on its fixed cost:",
        "",
        "| K (seeds per task) | Python task | share | through Blender | share |",
        "| --- | --- | --- | --- | --- |",
    ]
    for k in (1, 2, 5, 10, 20, 50):
        tp, tb = ep + k * per_seed, eb + k * per_seed
        lines.append("| %d | %.1f s | %.0f %% | %.1f s | %.0f %% |" % (k, tp, 100 * ep / tp, tb, 100 * eb / tb))
    text = "\n".join(lines) + "\n"
    print(text)
    if a.write:
        with open(a.write, "w") as fh:
            fh.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

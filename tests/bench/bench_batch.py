"""Batch runner throughput: seeds per second for 1 and 2 workers, as a
local loop and through Slurm, and Slurm's per-task overhead.

    python3 tests/bench/bench_batch.py [BUILD_DIR] [--seeds 40] [--rounds 3] [--write]

The work: tests/batch/avenue_batch_tiny.json (3 small keyaki a seed),
glTF only (plain python3 runner, textures at 64), tasks of 10 seeds.
  local, 1 worker   one runner, seeds 0:N
  local, 2 workers  two runners at once, 0:N/2 and N/2:N
  slurm, W workers  submit.sh --per-task 10 --workers W (array of N/10
                    tasks, W at once), submit to the last task's end
  slurm overhead    an array of 10 empty tasks (sbatch --wrap true), one
                    at a time: wall time / 10, and the array tasks' time
                    beyond the local loop's per task
Each round runs every case once, the order alternating between rounds;
the medians are printed (and, with --write, written to
tests/bench/peers/batch.md, which peers.py copies into docs/benchmarks.md).
Needs root for the one-node cluster (tools/farm/slurm); without Slurm the
Slurm rows say so.
"""
import argparse
import datetime
import os
import shutil
import statistics
import subprocess
import sys
import time

from machine_info import cpu_model  # noqa: E402  (tests/bench/)

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "..", ".."))
RUNNER = os.path.join(SRC, "blender_addon", "banyan", "batch_run.py")
SLURM = os.path.join(SRC, "tools", "farm", "slurm")
PRESET = os.path.join(SRC, "tests", "batch", "avenue_batch_tiny.json")
PER_TASK = 10

ap = argparse.ArgumentParser()
ap.add_argument("build", nargs="?", default=os.path.join(SRC, "build"))
ap.add_argument("--seeds", type=int, default=40)
ap.add_argument("--rounds", type=int, default=3)
ap.add_argument("--write", action="store_true", help="write tests/bench/peers/batch.md")
args = ap.parse_args()
BUILD = os.path.abspath(args.build)
OUT = os.path.join(BUILD, "bench_batch")
N = args.seeds
os.environ.setdefault("BANYAN_LIB", os.path.join(BUILD, "libbanyan.so"))
os.environ["BANYAN_SLURM_DIR"] = os.path.join(OUT, "slurm-state")
os.environ["BANYAN_SLURM_PORT"] = os.environ.get("BANYAN_BENCH_SLURM_PORT", "6927")
os.environ["SLURM_CONF"] = os.path.join(OUT, "slurm-state", "slurm.conf")
COMMON = ["--preset", PRESET, "--texture-size", "64", "--quiet"]



def fresh(name):
    d = os.path.join(OUT, name)
    shutil.rmtree(d, ignore_errors=True)
    shutil.rmtree(d + ".slurm-logs", ignore_errors=True)
    return d


def local(workers):
    out = fresh("local%d" % workers)
    step = N // workers
    t0 = time.perf_counter()
    procs = [subprocess.Popen([sys.executable, RUNNER, "--", "--seeds", "%d:%d" % (i * step, N if i == workers - 1
                                                                                    else (i + 1) * step),
                               "--out", out] + COMMON) for i in range(workers)]
    if any(p.wait() for p in procs):
        raise SystemExit("bench_batch: a local runner failed")
    return time.perf_counter() - t0


def _wait(ids):
    while True:
        r = subprocess.run(["squeue", "-h", "-o", "%i"], capture_output=True, text=True)
        if not any(line.split("_")[0] in ids for line in r.stdout.split()):
            return
        time.sleep(0.05)


def slurm(workers):
    out = fresh("slurm%d" % workers)
    t0 = time.perf_counter()
    r = subprocess.run(["sh", os.path.join(SLURM, "submit.sh"), "--per-task", str(PER_TASK), "--workers",
                        str(workers), "--seeds", "0:%d" % N, "--out", out] + COMMON, capture_output=True, text=True)
    if r.returncode:
        raise SystemExit("bench_batch: submit.sh failed: %s" % r.stderr)
    array, merge = r.stdout.split()
    _wait([array])
    dt = time.perf_counter() - t0
    _wait([merge])
    return dt


def empty_tasks(count=10):
    t0 = time.perf_counter()
    r = subprocess.run(["sbatch", "--parsable", "--array=0-%d%%1" % (count - 1), "--output=/dev/null",
                        "--wrap", "true"], capture_output=True, text=True)
    if r.returncode:
        raise SystemExit("bench_batch: sbatch failed: %s" % r.stderr)
    _wait([r.stdout.strip()])
    return (time.perf_counter() - t0) / count


def local_tasks():
    """The Slurm split without Slurm: N/10 runners of 10 seeds, one after another."""
    out = fresh("localtasks")
    t0 = time.perf_counter()
    for a in range(0, N, PER_TASK):
        subprocess.run([sys.executable, RUNNER, "--", "--seeds", "%d:%d" % (a, min(N, a + PER_TASK)), "--out", out]
                       + COMMON, check=True)
    return time.perf_counter() - t0


have_slurm = shutil.which("sbatch") is not None and os.geteuid() == 0
if have_slurm:
    r = subprocess.run(["sh", os.path.join(SLURM, "cluster_start.sh")], capture_output=True, text=True)
    have_slurm = r.returncode == 0
    if not have_slurm:
        print("bench_batch: no Slurm cluster: %s" % r.stderr.strip())
cases = [("local, 1 worker", lambda: local(1)), ("local, 2 workers", lambda: local(2)),
         ("local, tasks of 10 one after another", local_tasks)]
if have_slurm:
    cases += [("slurm, 1 worker", lambda: slurm(1)), ("slurm, 2 workers", lambda: slurm(2)),
              ("slurm, empty task", empty_tasks)]
times = {name: [] for name, _ in cases}
try:
    for rnd in range(args.rounds):
        order = cases if rnd % 2 == 0 else cases[::-1]
        for name, fn in order:
            times[name].append(fn())
            print("round %d: %-40s %.2f s" % (rnd + 1, name, times[name][-1]), flush=True)
finally:
    if have_slurm:
        subprocess.run(["sh", os.path.join(SLURM, "cluster_stop.sh")], capture_output=True)
    shutil.rmtree(OUT, ignore_errors=True)  # a few hundred MB of .glb
med = {k: statistics.median(v) for k, v in times.items()}

rows = []
for name in ("local, 1 worker", "local, 2 workers", "slurm, 1 worker", "slurm, 2 workers"):
    if name in med:
        rows.append("| %s | %.2f s | %.1f |" % (name, med[name], N / med[name]))
tasks = N // PER_TASK
lines = [
    "## Batch runner and Slurm (issue #24)",
    "",
    "<!-- kept in tests/bench/peers/batch.md, written by tests/bench/bench_batch.py --write; "
    "peers.py copies it in -->",
    "",
    "`python3 tests/bench/bench_batch.py [BUILD_DIR] --write`: %d seeds of tests/batch/avenue_batch_tiny.json "
    "(3 small keyaki a seed), glTF only (the plain-python runner, textures at 64), medians of %d rounds, the "
    "cases' order alternating. Slurm: the one-node cluster of tools/farm/slurm on 127.0.0.1, arrays of %d "
    "tasks of %d seeds (submit.sh), timed from sbatch to the last task's end. Machine: %s, %d cores; "
    "measured %s, load average %.1f at the end (a shared machine: compare the rows with each other):"
    % (N, args.rounds, tasks, PER_TASK, cpu_model(), os.cpu_count(), datetime.date.today().isoformat(),
       os.getloadavg()[0]),
    "",
    "| case | %d seeds | seeds/s |" % N,
    "| --- | --- | --- |",
] + rows + [""]
if "slurm, empty task" in med:
    extra = (med["slurm, 1 worker"] - med["local, tasks of 10 one after another"]) / tasks
    lines += [
        "Slurm's per-task overhead: an empty array task (`sbatch --array=0-9%%1 --wrap true`) takes %.2f s "
        "from queue to end, one after another; the %d runner tasks took %.2f s more each through Slurm than "
        "the same tasks run one after another by hand (%.2f s in all). Each task also pays the runner's own "
        "start (python and libbanyan loaded: the local loop's %d tasks take %.2f s against %.2f s for one "
        "runner over all %d seeds)."
        % (med["slurm, empty task"], tasks, extra, med["local, tasks of 10 one after another"], tasks,
           med["local, tasks of 10 one after another"], med["local, 1 worker"], N),
        ""]
else:
    lines += ["Slurm was not available here (not root, or slurm-wlm missing): no Slurm rows.", ""]
text = "\n".join(lines)
print(text)
if args.write:
    with open(os.path.join(HERE, "peers", "batch.md"), "w") as f:
        f.write(text)

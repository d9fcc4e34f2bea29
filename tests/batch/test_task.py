"""The scheduler-neutral entry (blender_addon/banyan/batch_task.py) in plain
python3: refusals (exit 2 naming the argument, nothing written), the task
count, task I's seeds A + I*K .. min(A + (I+1)*K, B) covering A:B exactly
once, the tasks' folder byte-identical to one run of the runner, and
--parent-pid: an entry whose parent is killed with SIGKILL stops at once.

    python3 tests/batch/test_task.py BUILD_DIR
(ctest sets BANYAN_LIB to BUILD_DIR's library.)"""
import glob
import importlib.util
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import farm_common
from farm_common import ADDON, PRESET, RUNNER, check, finish

ENTRY = os.path.join(ADDON, "batch_task.py")


def entry(*args):
    r = subprocess.run([sys.executable, ENTRY, "--"] + [str(a) for a in args], capture_output=True, text=True,
                       timeout=300)
    return r.returncode, r.stdout + r.stderr


def outputs(folder):
    """{name: sha256} of the .glb files (the records hold times and hosts)."""
    return farm_common.outputs(folder, "*.glb")


def seeds_of(folder):
    return sorted(int(re.search(r"-s(\d+)\.glb$", n).group(1)) for n in outputs(folder))


spec = importlib.util.spec_from_file_location("batch_task_under_test", ENTRY)
bt = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bt)

tmp = tempfile.mkdtemp(prefix="banyan_task_")
try:
    out = os.path.join(tmp, "out")
    run_args = ["--preset", PRESET, "--out", out, "--texture-size", 64]
    # --- refusals: exit 2, the argument named, nothing written
    for seeds in ("5", "5:5", "7:3", "-1:3", "+1:3", " 1:3", "1:3 ", "0x1:4", "1.0:4", "1e1:40", "\u0661:4",
                  "1:2:3", "0:4294967297", ""):
        rc, log = entry("--task-index", 0, "--per-task", 2, "--seeds", seeds, *run_args)
        check(rc == 2 and "--seeds" in log, "--seeds %r: exit 2 naming --seeds (exit %d: %s)" % (seeds, rc, log[-200:]))
    for k in ("0", "-1", "+2", "1.5", "two", "\u0662", "2 "):
        rc, log = entry("--task-index", 0, "--per-task", k, "--seeds", "0:10", *run_args)
        check(rc == 2 and "--per-task" in log, "--per-task %r: exit 2 naming it (exit %d: %s)" % (k, rc, log[-200:]))
    for i in ("5", "6", "-1", "+0", "0x0", "1.0", ""):  # seeds 0:10 by 2: tasks 0 .. 4
        rc, log = entry("--task-index", i, "--per-task", 2, "--seeds", "0:10", *run_args)
        check(rc == 2 and "--task-index" in log, "--task-index %r: exit 2 naming it (exit %d: %s)" % (i, rc, log[-200:]))
    rc, log = entry("--per-task", 2, "--seeds", "0:10", *run_args)
    check(rc == 2 and "--task-index" in log, "no --task-index: exit 2 naming it (%s)" % log[-200:])
    rc, log = entry("--task-index", 0, "--seeds", "0:10", *run_args)
    check(rc == 2 and "--per-task" in log, "no --per-task: exit 2 naming it (%s)" % log[-200:])
    rc, log = entry("--task-index", 0, "--per-task", 2, *run_args)
    check(rc == 2 and "--seeds" in log, "no --seeds: exit 2 naming it (%s)" % log[-200:])
    rc, log = entry("--task-index", 0, "--task-index", 1, "--per-task", 2, "--seeds", "0:10", *run_args)
    check(rc == 2 and "--task-index" in log, "--task-index twice: exit 2 (%s)" % log[-200:])
    rc, log = entry("--task-index", 0, "--per-task", 2, "--seeds", "0:10", "--parent-pid", "x1", *run_args)
    check(rc == 2 and "--parent-pid" in log, "--parent-pid x1: exit 2 naming it (%s)" % log[-200:])
    rc, log = entry("--task-index", 0, "--per-task", 2, "--seeds", "0:10", "--preset", PRESET, "--bogus")
    check(rc == 2 and "--bogus" in log, "a bad runner argument: the runner's exit 2 naming it (%s)" % log[-200:])
    rc, log = entry("--task-count", "--task-index", 0, "--per-task", 2, "--seeds", "0:10")
    check(rc == 2 and "--task-count" in log, "--task-count with --task-index: exit 2 (%s)" % log[-200:])
    check(not os.path.exists(out), "refused tasks write nothing")

    # --- the task count, and the ranges cover A:B exactly once, in order
    for a, b, k in ((0, 10, 2), (0, 10, 3), (3, 10, 3), (7, 8, 1), (7, 8, 5), (0, 40, 5), (5, 45, 7),
                    (4294967290, 4294967296, 4)):
        rc, log = entry("--task-count", "--seeds", "%d:%d" % (a, b), "--per-task", k)
        n = -(-(b - a) // k)
        check(rc == 0 and log.strip() == str(n), "--task-count %d:%d by %d prints %d (exit %d: %s)"
              % (a, b, k, n, rc, log.strip()))
        cover = []
        for i in range(n):
            lo, hi = bt.task_seeds(a, b, k, n, str(i))
            check(lo == a + i * k and hi == min(a + (i + 1) * k, b) and lo < hi,
                  "%d:%d by %d: task %d is %d:%d" % (a, b, k, i, lo, hi))
            cover += range(lo, hi)
        check(cover == list(range(a, b)), "%d:%d by %d: the tasks cover every seed once" % (a, b, k))

    # --- tasks of 3:10 by 3 (3:6, 6:9, 9:10), run out of order, equal one runner run
    ref = os.path.join(tmp, "ref")
    r = subprocess.run([sys.executable, RUNNER, "--", "--preset", PRESET, "--seeds", "3:10", "--out", ref,
                        "--texture-size", "64", "--quiet"], capture_output=True, text=True, timeout=300)
    check(r.returncode == 0 and len(outputs(ref)) == 7, "reference run 3:10 (exit %d)" % r.returncode)
    for i, want in ((2, "9:10"), (0, "3:6"), (1, "6:9")):
        rc, log = entry("--task-index", i, "--per-task", 3, "--seeds", "3:10", *run_args)
        check(rc == 0 and ("seeds %s:" % want) in log, "task %d runs seeds %s (exit %d: %s)" % (i, want, rc, log[-300:]))
    check(seeds_of(out) == list(range(3, 10)), "the three tasks made seeds 3 .. 9 (%s)" % seeds_of(out))
    check(outputs(out) == outputs(ref), "the tasks' .glb files equal one runner run byte for byte")
    rc, log = entry("--task-index", 1, "--per-task", 3, "--seeds", "3:10", *run_args)
    check(rc == 0 and "0 made, 3 skipped" in log, "a task run again skips its seeds (%s)" % log[-200:])
    r = subprocess.run([sys.executable, RUNNER, "--", "--merge-manifest", out, "--seeds", "3:10", "--verify"],
                       capture_output=True, text=True, timeout=300)
    check(r.returncode == 0, "merge --verify of the tasks' folder (%s)" % (r.stdout + r.stderr)[-300:])

    # --- --parent-pid: a parent that is gone already; a parent killed mid-task
    rc, log = entry("--task-index", 0, "--per-task", 2, "--seeds", "0:10", "--parent-pid", 1, *run_args)
    check(rc == 1 and "parent" in log, "--parent-pid of another process: exit 1 at once (exit %d: %s)" % (rc, log))
    slow = os.path.join(tmp, "slow")  # 1024-pixel textures: each seed takes a while
    parent = subprocess.Popen(
        [sys.executable, "-c", "import os, subprocess, sys; p = subprocess.Popen([sys.executable, %r, '--', "
         "'--task-index', '0', '--per-task', '30', '--seeds', '0:30', '--parent-pid', str(os.getpid()), "
         "'--preset', %r, '--out', %r, '--quiet']); print(p.pid, flush=True); p.wait()" % (ENTRY, PRESET, slow)],
        stdout=subprocess.PIPE, text=True)
    child = int(parent.stdout.readline())
    t0 = time.time()
    while not glob.glob(os.path.join(slow, "*.glb")) and time.time() - t0 < 60:
        time.sleep(0.01)
    os.kill(parent.pid, signal.SIGKILL)
    parent.wait()

    def alive(pid):
        try:
            with open("/proc/%d/status" % pid) as f:
                return "\nState:\tZ" not in f.read()
        except OSError:
            return False
    t1 = time.time()
    while alive(child) and time.time() - t1 < 5:
        time.sleep(0.01)
    made = len(outputs(slow))
    check(not alive(child), "the entry died with its parent (pid %d still running)" % child)
    check(time.time() - t1 < 1.0 and 1 <= made < 30,
          "it stopped at once, mid-task (%.2f s after its parent; %d of 30 seeds made)" % (time.time() - t1, made))
finally:
    shutil.rmtree(tmp, ignore_errors=True)
finish("test_task")

"""tools/farm/dask/submit.py on a Dask LocalCluster of 2 worker processes
(dask + distributed installed by tools/farm/farm_venv.sh into a cached
venv): a run makes a folder whose .glb files equal a single run of the
runner byte for byte, with a verified manifest; then a killed worker: the
worker process running a task is killed with SIGKILL after the task wrote
a seed, the runner it started dies with it at once (no orphan writing on),
the scheduler runs the task again, and the folder is again complete and
byte-identical; no runner process is left (a /proc scan). Bad seeds are
refused before a cluster starts.

    python3 tests/batch/test_dask.py BUILD_DIR
(ctest sets BANYAN_LIB to BUILD_DIR's library.)"""
import glob
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from farm_common import ADDON, PRESET, RUNNER, SRC, check, farm_venv, finish, manifest_files, outputs

SUBMIT = os.path.join(SRC, "tools", "farm", "dask", "submit.py")
SEEDS, PER_TASK = "0:24", 8  # 3 tasks on 2 workers; 1024-pixel textures: a task runs long enough to be killed


def proc_status(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            return dict(line.split(":\t", 1) for line in f.read().splitlines() if ":\t" in line)
    except OSError:
        return None


def alive(pid):
    st = proc_status(pid)
    return st is not None and not st.get("State", "").startswith("Z")


def entries_of(out):
    """{pid: task index} of the live batch_task.py processes writing to `out` (a /proc scan)."""
    found = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open("/proc/%s/cmdline" % d, "rb") as f:
                    cmd = f.read().decode(errors="replace").split("\0")
            except OSError:
                continue
            if any(c.endswith("batch_task.py") for c in cmd) and out in cmd and alive(int(d)):
                found[int(d)] = int(cmd[cmd.index("--task-index") + 1])
    return found


PY = os.path.join(farm_venv(), "bin", "python")


def submit(out, *extra, seeds=SEEDS):
    return [PY, SUBMIT, "--local", "2", "--addon", ADDON, "--python", sys.executable, "--seeds", seeds,
            "--per-task", str(PER_TASK)] + list(extra) + ["--", "--preset", PRESET, "--out", out]


tmp = tempfile.mkdtemp(prefix="banyan_dask_")
try:
    ref = os.path.join(tmp, "ref")
    r = subprocess.run([sys.executable, RUNNER, "--", "--preset", PRESET, "--seeds", SEEDS, "--out", ref, "--quiet"],
                       capture_output=True, text=True, timeout=600)
    REF = outputs(ref)
    check(r.returncode == 0 and len(REF) == 24, "reference: one runner run of %s (exit %d)" % (SEEDS, r.returncode))

    r = subprocess.run(submit(os.path.join(tmp, "bad"), seeds="0:x"), capture_output=True, text=True, timeout=120)
    check(r.returncode == 2 and "--seeds" in r.stderr and not os.path.exists(os.path.join(tmp, "bad")),
          "bad --seeds: exit 2 naming it, before a cluster starts (exit %d: %s)" % (r.returncode, r.stderr[-300:]))

    # --- a run on 2 workers
    out = os.path.join(tmp, "run")
    t0 = time.time()
    r = subprocess.run(submit(out), capture_output=True, text=True, timeout=600)
    check(r.returncode == 0 and "24 records, 24 files" in r.stdout, "submit.py --local 2: exit %d (%s)"
          % (r.returncode, (r.stdout + r.stderr)[-800:]))
    check(outputs(out) == REF, "the folder equals one runner run byte for byte (differ: %s)"
          % sorted(set(REF.items()) ^ set(outputs(out).items()))[:4])
    check(manifest_files(out) == REF, "the manifest lists exactly the reference's files")
    print("dask: %s in tasks of %d on 2 workers, %.1f s" % (SEEDS, PER_TASK, time.time() - t0), flush=True)

    # --- a killed worker
    out = os.path.join(tmp, "kill")
    p = subprocess.Popen(submit(out, "--retries", "3"), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    killed = None  # (worker pid, runner pid, task index, seeds recorded at the kill)
    t0 = time.time()
    while killed is None and p.poll() is None and time.time() - t0 < 120:
        for pid, index in entries_of(out).items():
            lo = index * PER_TASK
            done = sum(os.path.exists(os.path.join(out, "manifest", n[:-4] + ".json")) for n in REF
                       if lo <= int(n.rsplit("-s", 1)[1][:-4]) < lo + PER_TASK)
            st = proc_status(pid)
            if st and 1 <= done <= 3:
                worker = int(st["PPid"])
                if worker in (p.pid, os.getpid(), 1):
                    continue
                os.kill(worker, signal.SIGKILL)
                killed = (worker, pid, index, done)
                t_kill = time.time()
                break
        time.sleep(0.005)
    if check(killed is not None, "a worker running a task was found and killed"):
        worker, runner, index, done = killed
        while alive(runner) and time.time() - t_kill < 5:
            time.sleep(0.005)
        gone = time.time() - t_kill
        check(not alive(runner), "the killed worker's runner (pid %d) died with it" % runner)
        check(gone < 0.5, "at once (%.2f s after the worker), while task %d had %d of %d seeds left"
              % (gone, index, PER_TASK - done, PER_TASK))
    try:
        log = p.communicate(timeout=600)[0]
    except subprocess.TimeoutExpired:
        p.kill()
        log = p.communicate()[0]
    if killed:
        line = [ln for ln in log.splitlines() if ln.startswith("submit: LocalCluster")]
        check(line and str(killed[0]) in line[0].split("workers", 1)[1],
              "the killed process (pid %d) was one of the cluster's workers (%s)" % (killed[0], line))
    check(p.returncode == 0 and "24 records, 24 files" in log, "the run completes after the kill (exit %s: %s)"
          % (p.returncode, log[-1500:]))
    check(outputs(out) == REF, "after the kill the folder equals one runner run byte for byte (differ: %s)"
          % sorted(set(REF.items()) ^ set(outputs(out).items()))[:4])
    check(manifest_files(out) == REF, "after the kill: the manifest lists exactly the reference's files")
    check(not glob.glob(os.path.join(out, ".*")) and not glob.glob(os.path.join(out, "manifest", ".*")),
          "no temporary file is left")
    check(not entries_of(out), "no runner process is left (%s)" % entries_of(out))
finally:
    shutil.rmtree(tmp, ignore_errors=True)
finish("test_dask")

"""The Open Job Description template (tools/farm/openjd/banyan_batch.yaml)
run locally by `openjd` (openjd-cli, installed by tools/farm/farm_venv.sh
into a cached venv): `openjd check` passes it; `openjd run` of its Merge
step with the Seeds step before it makes a folder whose .glb files equal a
single run of the runner byte for byte, with a verified manifest. Then a
killed worker: one task's process is killed with SIGKILL after it wrote its
first seed, openjd reports the task failed, the task is run again as a
retry would, the other tasks and the merge run, and the folder is again
complete and byte-identical. A task count too small (LastTaskIndex) fails
the merge step, naming the missing seeds. Format=usda makes USD layers.

    python3 tests/batch/test_openjd.py BUILD_DIR
(ctest sets BANYAN_LIB to BUILD_DIR's library.)"""
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from farm_common import ADDON, PRESET, RUNNER, SRC, check, farm_venv, finish, manifest_files, outputs

TEMPLATE = os.path.join(SRC, "tools", "farm", "openjd", "banyan_batch.yaml")
SEEDS, PER_TASK, TASKS = "0:20", 5, 4  # default 1024-pixel textures: a task takes long enough to be killed


OPENJD = os.path.join(farm_venv(), "bin", "openjd")


def params(out, last=TASKS - 1):
    p = {"Addon": ADDON, "Python": sys.executable, "Preset": PRESET, "Out": out, "Seeds": SEEDS,
         "PerTask": PER_TASK, "LastTaskIndex": last}
    return sum((["-p", "%s=%s" % kv] for kv in p.items()), [])


def openjd(*args, **kw):
    return subprocess.run([OPENJD] + list(args), capture_output=True, text=True, timeout=600, **kw)


def entries_of(out):
    """Processes of batch_task.py writing to `out` (a /proc scan)."""
    pids = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open("/proc/%s/cmdline" % d, "rb") as f:
                    cmd = f.read().split(b"\0")
            except OSError:
                continue
            if any(c.endswith(b"batch_task.py") for c in cmd) and out.encode() in cmd:
                pids.append(int(d))
    return pids


tmp = tempfile.mkdtemp(prefix="banyan_openjd_")
try:
    r = openjd("check", "--extensions", "", TEMPLATE)  # the 2023-09 specification without extensions
    check(r.returncode == 0 and "passes validation" in r.stdout, "openjd check (%s)" % (r.stdout + r.stderr)[-400:])

    ref = os.path.join(tmp, "ref")
    r = subprocess.run([sys.executable, RUNNER, "--", "--preset", PRESET, "--seeds", SEEDS, "--out", ref, "--quiet"],
                       capture_output=True, text=True, timeout=600)
    check(r.returncode == 0 and len(outputs(ref)) == 20, "reference: one runner run of %s (exit %d)"
          % (SEEDS, r.returncode))
    r = subprocess.run([sys.executable, RUNNER, "--", "--merge-manifest", ref, "--seeds", SEEDS], capture_output=True,
                       text=True, timeout=600)
    REF = outputs(ref)

    # --- the whole job: Seeds (4 tasks), then Merge
    out = os.path.join(tmp, "job")
    t0 = time.time()
    r = openjd("run", TEMPLATE, "--step", "Merge", "--run-dependencies", *params(out))
    log = r.stdout + r.stderr
    check(r.returncode == 0 and "Session ended successfully" in log, "openjd run: exit %d (%s)"
          % (r.returncode, log[-800:]))
    check(log.count("--task-index") >= TASKS or "Chunks run: %d" % (TASKS + 1) in log,
          "openjd ran %d seed tasks and the merge" % TASKS)
    check("manifest %s: 20 records, 20 files" % os.path.join(out, "manifest.json") in log,
          "the Merge step merged 20 records")
    check(outputs(out) == REF, "openjd run: the folder equals one runner run byte for byte (differ: %s)"
          % sorted(set(REF.items()) ^ set(outputs(out).items()))[:4])
    check(manifest_files(out) == REF, "openjd run: the manifest lists exactly the reference's files")
    print("openjd run: 20 seeds in %d tasks and a merge, %.1f s" % (TASKS, time.time() - t0), flush=True)

    # --- a task count too small: the merge step fails, naming the seeds
    short = os.path.join(tmp, "short")
    r = openjd("run", TEMPLATE, "--step", "Merge", "--run-dependencies", *params(short, last=TASKS - 2))
    check(r.returncode != 0 and "seeds without a record: 15:20" in r.stdout + r.stderr,
          "LastTaskIndex too small: the merge fails naming seeds 15:20 (exit %d)" % r.returncode)

    # --- a killed worker: task 1 (seeds 5 .. 9) killed once its first seed is recorded
    out = os.path.join(tmp, "kill")
    first = os.path.join(out, "manifest", [n for n in REF if n.endswith("-s5.glb")][0][:-4] + ".json")
    p = subprocess.Popen([OPENJD, "run", TEMPLATE, "--step", "Seeds", "--no-run-dependencies", "--task-param",
                          "Index=1"] + params(out), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    killed = None
    t0 = time.time()
    while killed is None and p.poll() is None and time.time() - t0 < 120:
        if os.path.exists(first):
            pids = entries_of(out)
            if pids:
                os.kill(pids[0], signal.SIGKILL)
                killed = pids[0]
        time.sleep(0.005)
    log = p.communicate(timeout=300)[0]
    done = len(glob.glob(os.path.join(out, "manifest", "*.json")))  # seeds complete with their record
    check(killed is not None, "task 1's process was found and killed")
    check(p.returncode != 0, "openjd reports the killed task failed (exit %d: %s)" % (p.returncode, log[-300:]))
    check(1 <= done < PER_TASK, "the kill came mid-task (%d of %d seeds recorded)" % (done, PER_TASK))
    # the retry of task 1, then the other tasks and the merge
    r = openjd("run", TEMPLATE, "--step", "Seeds", "--no-run-dependencies", "--task-param", "Index=1", *params(out))
    check(r.returncode == 0 and "%d made, %d skipped" % (PER_TASK - done, done) in r.stdout,
          "the retried task makes only the seeds the killed one had not (exit %d: %s)"
          % (r.returncode, (r.stdout + r.stderr)[-500:]))
    r = openjd("run", TEMPLATE, "--step", "Seeds", "--no-run-dependencies", "--tasks",
               json.dumps([{"Index": i} for i in range(TASKS) if i != 1]), *params(out))
    check(r.returncode == 0, "the other tasks (exit %d: %s)" % (r.returncode, (r.stdout + r.stderr)[-500:]))
    r = openjd("run", TEMPLATE, "--step", "Merge", "--no-run-dependencies", *params(out))
    check(r.returncode == 0 and "20 records, 20 files" in r.stdout, "the merge after the retry (exit %d: %s)"
          % (r.returncode, (r.stdout + r.stderr)[-500:]))
    check(outputs(out) == REF, "after the kill and the retry the folder equals one runner run byte for byte "
          "(differ: %s)" % sorted(set(REF.items()) ^ set(outputs(out).items()))[:4])
    check(manifest_files(out) == REF, "after the kill: the manifest lists exactly the reference's files")
    check(not glob.glob(os.path.join(out, ".*")) and not glob.glob(os.path.join(out, "manifest", ".*")),
          "no temporary file is left")
    check(not entries_of(out), "no task process is left running")

    # Format=usda: the runner's --format, two seeds in one task and the merge.
    usd = os.path.join(tmp, "usd")
    p_usd = params(usd, last=0)
    p_usd = [("Seeds=0:2" if a.startswith("Seeds=") else "PerTask=2" if a.startswith("PerTask=") else a)
             for a in p_usd] + ["-p", "Format=usda"]
    r = openjd("run", TEMPLATE, "--step", "Merge", "--run-dependencies", *p_usd)
    layers = glob.glob(os.path.join(usd, "*.usda"))
    check(r.returncode == 0 and len(layers) == 2 and not glob.glob(os.path.join(usd, "*.glb"))
          and "2 records, 2 files" in r.stdout,
          "Format=usda: two USD layers and their merge (exit %d, %s: %s)" % (r.returncode, layers,
                                                                          (r.stdout + r.stderr)[-400:]))
    check(all(open(f).read(10) == "#usda 1.0\n" for f in layers), "Format=usda: the files are USD text layers")
finally:
    shutil.rmtree(tmp, ignore_errors=True)
finish("test_openjd")

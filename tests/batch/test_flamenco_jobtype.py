#!/usr/bin/env python3
"""Tests the Flamenco job type tools/farm/flamenco/banyan-batch.js without a
Flamenco install (the Go module proxy here refuses Flamenco's module host).

compile: compileJob() runs in node under tools/farm/flamenco/compile_job.mjs,
which stands in for the Manager's job compiler and the Worker's blender-render
argv. Checks that the tasks cover the seed range exactly once in runs of at
most K, hand each task its own share of the render range, end in a merge task
that depends on every seed task, and that bad settings are refused by name.

run (--blender, --lib): the compiled tasks' argv, with the Manager variables
expanded for this machine, are run by two stand-in Workers sharing a task
queue on one output folder, like a Manager with two Workers; worker-1's
task process (Blender or Python) is killed (SIGKILL, its whole process group)
in the middle of its first task, once that task has written a seed but not
all; the task goes back on the queue, to be run again by whichever Worker
asks first (worker-1 comes back a second later, like a rebooted machine). The folder must then hold every seed's .glb
byte-identical to a single-machine run of the runner, the same renders, a
complete merged manifest, and pass the Khronos validator.

    test_flamenco_jobtype.py compile
    test_flamenco_jobtype.py run --blender /usr/bin/blender --lib build/libbanyan.so [--seeds 40]

Exit 0 when every check passed, 1 otherwise.
"""
import argparse
import hashlib
import json
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
JOBTYPE = os.path.join(ROOT, "tools", "farm", "flamenco", "banyan-batch.js")
COMPILE = os.path.join(ROOT, "tools", "farm", "flamenco", "compile_job.mjs")
ADDON = os.path.join(ROOT, "blender_addon", "banyan")
PRESET = os.path.join(ROOT, "tests", "batch", "avenue_batch_tiny.json")
VALIDATE = os.path.join(ROOT, "tests", "gltf", "validate.mjs")
SEED_END_MAX = 1 << 32

failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL: " + msg, flush=True)
    return cond


def compile_job(settings, variables=None, expect_ok=True):
    cmd = ["node", COMPILE, JOBTYPE, "--settings", json.dumps(settings)]
    for k, v in (variables or {}).items():
        cmd += ["--var", "%s=%s" % (k, v)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    if expect_ok:
        if p.returncode != 0:
            raise AssertionError("compileJob(%s) failed: %s" % (settings, p.stderr.strip()))
        return json.loads(p.stdout)
    return p


def job_type_info():
    p = subprocess.run(["node", COMPILE, JOBTYPE, "--job-type-info"], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        raise AssertionError("job type info: " + p.stderr)
    return json.loads(p.stdout)


def runner_args(task):
    """The runner's own arguments of a task's single command (blender-render
    or exec: both end in RUNNER -- ARGS)."""
    cmds = task["commands"]
    assert len(cmds) == 1, task
    c = cmds[0]
    assert c["name"] in ("blender-render", "exec"), c
    args = c["parameters"]["args"]
    return args[args.index("--") + 1:]


def opt(args, name):
    return args[args.index(name) + 1] if name in args else None


def half_open(text):
    a, b = text.split(":")
    return int(a), int(b)


# ------------------------------------------------------------------ compile
def check_job_type_info():
    info = job_type_info()
    keys = [s["key"] for s in info["settings"]]
    check(len(keys) == len(set(keys)), "setting keys are unique: %s" % keys)
    types = {"string": str, "int32": int, "bool": bool, "float": (int, float)}
    for s in info["settings"]:
        check(s.get("type") in types, "setting %s has a Flamenco type, not %r" % (s["key"], s.get("type")))
        if "default" in s and s.get("type") in types:
            check(isinstance(s["default"], types[s["type"]]), "setting %s: default %r is a %s"
                  % (s["key"], s["default"], s["type"]))
        if "choices" in s:
            check(s.get("default") in s["choices"], "setting %s: default among its choices" % s["key"])
    for k in ("preset", "first_seed", "seed_count", "seeds_per_task", "output_dir", "render_seeds",
              "size", "engine"):
        check(k in keys, "the job type has a %s setting" % k)
    return {s["key"]: s.get("default") for s in info["settings"]}


def check_split(first, count, per_task, render=None, extra=None):
    settings = {"preset": "p", "first_seed": first, "seed_count": count, "seeds_per_task": per_task,
                "output_dir": "/out"}
    if render:
        settings["render_seeds"] = "%d:%d" % render
    settings.update(extra or {})
    job = compile_job(settings)
    label = "split %d:%d K=%d render=%s" % (first, first + count, per_task, render)
    tasks = job["tasks"]
    names = [t["name"] for t in tasks]
    check(len(names) == len(set(names)), label + ": task names are unique")
    seed_tasks = [t for t in tasks if "--seeds" in runner_args(t) and "--merge-manifest" not in runner_args(t)]
    merge_tasks = [t for t in tasks if "--merge-manifest" in runner_args(t)]
    n = -(-count // per_task)
    check(len(seed_tasks) == n, label + ": %d seed tasks, expected ceil(N/K) = %d" % (len(seed_tasks), n))
    ranges = sorted(half_open(opt(runner_args(t), "--seeds")) for t in seed_tasks)
    pos = first
    for i, (a, b) in enumerate(ranges):
        check(a == pos, label + ": seed ranges are contiguous and disjoint (%d:%d after %d)" % (a, b, pos))
        check(0 < b - a <= per_task, label + ": task %d:%d has at most K seeds" % (a, b))
        if i < len(ranges) - 1:
            check(b - a == per_task, label + ": every task but the last has exactly K seeds")
        pos = b
    check(pos == first + count, label + ": the tasks end at first + count (%d)" % pos)
    rendered = []
    for t in seed_tasks:
        args = runner_args(t)
        a, b = half_open(opt(args, "--seeds"))
        check(t["commands"][0]["totalStepCount"] == b - a, label + ": a task's steps are its seeds")
        check(opt(args, "--out") == "/out" and opt(args, "--preset") == "p", label + ": preset and out passed")
        check(opt(args, "--texture-size") == str((extra or {}).get("texture_size", 1024)),
              label + ": texture size passed")
        check(("--no-textures" in args) == ((extra or {}).get("textures") is False),
              label + ": --no-textures exactly when textures is false")
        rs = opt(args, "--render-seeds")
        kind = (t["type"], t["commands"][0]["name"])
        check(kind == (("misc", "exec") if rs is None else ("blender", "blender-render")),
              label + ": %s: Blender only for a task that renders, Python (exec) otherwise: %s" % (t["name"], kind))
        if rs is None:
            check(opt(args, "--size") is None and opt(args, "--engine") is None,
                  label + ": no render options on a task that renders nothing")
            continue
        ra, rb = half_open(rs)
        check(a <= ra < rb <= b, label + ": render seeds %s within the task's %d:%d" % (rs, a, b))
        check(opt(args, "--size") is not None and opt(args, "--engine") is not None,
              label + ": a rendering task passes --size and --engine")
        rendered.extend(range(ra, rb))
    want = [s for s in range(first, first + count) if render and render[0] <= s < render[1]]
    check(sorted(rendered) == want, label + ": the tasks render exactly render_seeds within the seeds")
    check(len(merge_tasks) == 1, label + ": one merge task")
    if merge_tasks:
        m = merge_tasks[0]
        check(sorted(m["dependencies"]) == sorted(t["name"] for t in seed_tasks),
              label + ": the merge task depends on every seed task")
        check(opt(runner_args(m), "--seeds") == "%d:%d" % (first, first + count),
              label + ": the merge checks the whole seed range")
        check(tasks[-1] is m, label + ": the merge task comes last")
    return job


def check_command_shape(defaults):
    variables = {"blender": "/opt/blender 4/blender", "blenderArgs": "-b -y", "banyan": "/addons/banyan",
                 "jobs": "/shared"}
    for python in ("python3", "", "{py}"):
        settings = {"output_dir": "{jobs}/banyan", "render_seeds": "0:7"}
        if python != "python3":
            settings["python"] = python
        job = compile_job(settings, dict(variables, py="/venv/bin/python"))
        seed_tasks = [t for t in job["tasks"] if t["name"] != "merge-manifest"]
        check(len(seed_tasks) == -(-defaults["seed_count"] // defaults["seeds_per_task"]),
              "defaults: seed_count / seeds_per_task tasks")
        for t in job["tasks"]:
            label = "python=%r: %s" % (python, t["name"])
            c = t["commands"][0]
            p, argv = c["parameters"], c["argv"]
            check(not any("{" in a for a in argv), label + ": every variable expanded: %s" % argv)
            check(opt(argv, "--out") == "/shared/banyan" or opt(argv, "--merge-manifest") == "/shared/banyan",
                  label + ": {jobs} expanded in the output folder")
            check(opt(argv, "--preset") in (None, defaults["preset"]), label + ": default preset")
            if c["name"] == "exec":
                check(python != "", label + ": no exec task when python is empty")
                check(t["type"] == "misc", label + ": exec runs as task type misc")
                check(argv[0] == ("/venv/bin/python" if python == "{py}" else python), label + ": argv[0] is python")
                check(argv[1] == "/addons/banyan/batch_run.py" and argv[2] == "--", label + ": python RUNNER --")
                check("--render-seeds" not in argv, label + ": Python tasks render nothing")
                continue
            check(c["name"] == "blender-render" and t["type"] == "blender", label + ": blender-render")
            check(python == "" or "--render-seeds" in argv, label + ": Blender only where a task renders")
            check(p["blendfile"] == "", label + ": no blend file (the runner builds its scene)")
            check(argv[0] == "/opt/blender 4/blender", label + ": argv[0] is the {blender} variable, spaces kept")
            check(argv[1:3] == ["-b", "-y"], label + ": {blenderArgs} split into words")
            check("--python-exit-code" in argv and argv.index("--python-exit-code") < argv.index("--python"),
                  label + ": --python-exit-code before --python (else a failing runner exits 0)")
            check(argv[argv.index("--python") + 1] == "/addons/banyan/batch_run.py", label + ": runner path")
            check(argv.index("--factory-startup") < argv.index("--python"), label + ": factory startup")
            check(argv[argv.index("--python") + 2] == "--", label + ": -- after the runner")


def check_refusals():
    base = {"output_dir": "/o"}
    bad = [
        ("seed_count", 0), ("seed_count", -3), ("seed_count", 1.5), ("seed_count", "40"),
        ("seeds_per_task", 0), ("first_seed", -1), ("first_seed", SEED_END_MAX),
        ("engine", "CYCLES"), ("render_seeds", "4:2"), ("render_seeds", "4:4"), ("render_seeds", "x"),
        ("render_seeds", "1:"), ("output_dir", ""), ("output_dir", "   "), ("preset", ""), ("size", 8),
        ("size", 5000), ("threads", -1), ("merge_manifest", "yes"), ("runner", ""), ("python", 3),
        ("texture_size", 100), ("texture_size", 32), ("texture_size", 16384), ("textures", 0),
    ]
    for key, value in bad:
        p = compile_job(dict(base, **{key: value}), expect_ok=False)
        check(p.returncode == 2 and ("setting " + key) in p.stderr,
              "%s=%r is refused naming the setting (exit %d: %s)" % (key, value, p.returncode, p.stderr.strip()))
    # first + count past the seed space: the count is the one out of range.
    p = compile_job(dict(base, first_seed=SEED_END_MAX - 5, seed_count=6), expect_ok=False)
    check(p.returncode == 2 and "setting seed_count" in p.stderr, "first + count > 2^32 refused: " + p.stderr)
    job = compile_job(dict(base, first_seed=SEED_END_MAX - 5, seed_count=5, seeds_per_task=2))
    check(opt(runner_args(job["tasks"][-2]), "--seeds") == "%d:%d" % (SEED_END_MAX - 1, SEED_END_MAX),
          "the last seed 2^32-1 is reachable")
    job = compile_job(dict(base, merge_manifest=False))
    check(all(t["name"] != "merge-manifest" for t in job["tasks"]), "merge_manifest=false: no merge task")
    # Huge task counts are refused with the way out; so are more seeds than a merge takes.
    p = compile_job(dict(base, seed_count=200000, seeds_per_task=5), expect_ok=False)
    check(p.returncode == 2 and "setting seeds_per_task" in p.stderr and "40000 tasks" in p.stderr
          and "at least 20" in p.stderr, "200000 seeds in tasks of 5 refused, naming seeds_per_task: " + p.stderr)
    job = compile_job(dict(base, seed_count=200000, seeds_per_task=20, merge_manifest=False))
    check(len(job["tasks"]) == 10000, "200000 seeds in tasks of 20: 10000 tasks, allowed")
    p = compile_job(dict(base, seed_count=10000001, seeds_per_task=10000), expect_ok=False)
    check(p.returncode == 2 and "setting seed_count" in p.stderr and "10000000" in p.stderr,
          "more than 10^7 seeds refused: " + p.stderr)
    # The merge checks the preset's hash: it gets the preset and the glTF options.
    job = compile_job(dict(base, textures=False, texture_size=64))
    m = runner_args(job["tasks"][-1])
    check(opt(m, "--preset") == "avenue_batch_tiny" and opt(m, "--texture-size") == "64" and "--no-textures" in m,
          "the merge task gets --preset and the glTF options: %s" % m)


def run_compile_checks():
    defaults = check_job_type_info()
    for first, count, k, render in [(0, 40, 5, (0, 4)), (0, 41, 5, (3, 12)), (7, 3, 10, None),
                                    (100, 1, 1, (100, 101)), (0, 40, 40, (38, 60)), (5, 17, 4, (0, 6)),
                                    (0, 12, 5, (20, 30))]:
        check_split(first, count, k, render)
    check_split(0, 10, 3, (2, 5), {"textures": False, "texture_size": 64})
    check_command_shape(defaults)
    check_refusals()


# ---------------------------------------------------------------------- run
def seed_of(name):
    m = re.search(r"-s(\d+)\.(glb|png)$", name)
    return int(m.group(1)) if m else None


def outputs(folder):
    if not os.path.isdir(folder):
        return []
    return sorted(f for f in os.listdir(folder) if f.endswith((".glb", ".png")) and not f.startswith("."))


class Farm:
    """Two stand-in Workers taking tasks from one queue, as a Manager hands
    them out; a task whose Worker dies goes back on the queue."""

    def __init__(self, tasks, env, out, log_dir, kill_worker, kill_on_task, task_timeout):
        self.pending = queue.Queue()
        self.seed_tasks = [t for t in tasks if t["name"] != "merge-manifest"]
        self.after = [t for t in tasks if t["name"] == "merge-manifest"]
        for t in self.seed_tasks:
            self.pending.put(t)
        self.env, self.out, self.log_dir = env, out, log_dir
        self.kill_worker, self.kill_on_task = kill_worker, kill_on_task
        self.taken = {}
        self.task_timeout = task_timeout
        self.lock = threading.Lock()
        self.done, self.runs, self.errors = [], [], []
        self.done_by = {}
        self.killed = None
        self.procs = set()

    def _run(self, worker, task):
        argv = task["commands"][0]["argv"]
        log = open(os.path.join(self.log_dir, "%s-%s-%d.log" % (worker, task["name"], len(self.runs))), "w")
        p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, env=self.env, start_new_session=True)
        with self.lock:
            self.procs.add(p)
            self.runs.append((worker, task["name"]))
        return p, log

    def _kill_mid_task(self, p, task):
        """SIGKILL the task's whole process group once it has written a seed
        of its range but not all of them: the machine died mid-task."""
        a, b = half_open(opt(runner_args(task), "--seeds"))
        deadline = time.monotonic() + self.task_timeout
        while time.monotonic() < deadline and p.poll() is None:
            made = {seed_of(f) for f in outputs(self.out) if f.endswith(".glb")}
            made = {s for s in made if s is not None and a <= s < b}
            if 1 <= len(made) < b - a:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
                return sorted(made)
            time.sleep(0.02)
        return None

    def worker(self, name):
        while True:
            try:
                task = self.pending.get_nowait()
            except queue.Empty:
                return
            p, log = self._run(name, task)
            self.taken[name] = self.taken.get(name, 0) + 1
            if name == self.kill_worker and self.killed is None and self.taken[name] == self.kill_on_task:
                made = self._kill_mid_task(p, task)
                log.close()
                if made is None:
                    self.errors.append("%s: could not kill %s mid-task (it ended first)" % (name, task["name"]))
                    p.wait()
                    continue
                self.killed = (name, task["name"], made)
                print("killed %s running %s after seeds %s were written; requeued" % (name, task["name"], made),
                      flush=True)
                self.pending.put(task)  # the Manager requeues the dead Worker's task;
                time.sleep(1.0)         # the machine comes back and its Worker asks for work
                continue
            try:
                rc = p.wait(timeout=self.task_timeout)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
                rc = "timeout"
            log.close()
            if rc != 0:
                self.errors.append("%s: task %s exited %s (see %s)" % (name, task["name"], rc, self.log_dir))
            else:
                self.done.append(task["name"])
                self.done_by[name] = self.done_by.get(name, 0) + 1

    def run(self):
        threads = [threading.Thread(target=self.worker, args=(w,)) for w in ("worker-1", "worker-2")]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for task in self.after:  # dependencies met: every seed task done
            p, log = self._run("worker-2", task)
            rc = p.wait(timeout=self.task_timeout)
            log.close()
            if rc != 0:
                self.errors.append("merge task exited %s" % rc)
            else:
                self.done.append(task["name"])

    def kill_all(self):
        for p in list(self.procs):
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                p.wait()


def run_farm_checks(blender, lib, seeds, per_task, renders, workdir):
    env = dict(os.environ, BANYAN_LIB=os.path.abspath(lib))
    runner = os.path.join(ADDON, "batch_run.py")
    if not check(os.path.isfile(runner), "the batch runner exists: " + runner):
        return
    ref, out, logs = (os.path.join(workdir, d) for d in ("ref", "farm", "logs"))
    os.makedirs(logs)
    settings = {"preset": PRESET, "first_seed": 0, "seed_count": seeds, "seeds_per_task": per_task,
                "output_dir": "{jobs}/farm", "render_seeds": "0:%d" % renders, "size": 64,
                "engine": "WORKBENCH", "threads": 1, "texture_size": 64}
    job = compile_job(settings, {"blender": blender, "blenderArgs": "-b -y", "banyan": ADDON, "jobs": workdir})

    t0 = time.monotonic()
    ref_argv = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", runner, "--",
                "--preset", PRESET, "--seeds", "0:%d" % seeds, "--out", ref, "--render-seeds", "0:%d" % renders,
                "--size", "64", "--engine", "WORKBENCH", "--threads", "1", "--texture-size", "64"]
    with open(os.path.join(logs, "reference.log"), "w") as log:
        rc = subprocess.run(ref_argv, stdout=log, stderr=subprocess.STDOUT, env=env, timeout=900).returncode
    if not check(rc == 0, "the single-machine reference run exits 0 (see %s/reference.log)" % logs):
        return
    print("reference run: %d seeds in %.1f s" % (seeds, time.monotonic() - t0), flush=True)

    farm = Farm(job["tasks"], env, out, logs, kill_worker="worker-1", kill_on_task=1, task_timeout=600)
    t0 = time.monotonic()
    try:
        farm.run()
    finally:
        farm.kill_all()
    print("farm run: %d tasks (%d runs) in %.1f s" % (len(job["tasks"]), len(farm.runs), time.monotonic() - t0),
          flush=True)
    for e in farm.errors:
        check(False, e)
    check(farm.killed is not None, "a Worker was killed mid-task")
    print("tasks done by each Worker: %s" % farm.done_by, flush=True)
    check({w for w, _ in farm.runs} == {"worker-1", "worker-2"}, "both Workers ran tasks: %s" % farm.runs)
    if farm.killed:
        name = farm.killed[1]
        check(sum(1 for _, n in farm.runs if n == name) == 2, "the killed task ran again: %s" % name)
    check(sorted(farm.done) == sorted(t["name"] for t in job["tasks"]), "every task done once")

    ref_files, farm_files = outputs(ref), outputs(out)
    glbs = [f for f in ref_files if f.endswith(".glb")]
    pngs = [f for f in ref_files if f.endswith(".png")]
    check(len(glbs) == seeds, "reference: one .glb per seed (%d)" % len(glbs))
    check(sorted(seed_of(f) for f in pngs) == list(range(renders)), "reference: a render per render seed")
    check(farm_files == ref_files, "the farm made the same files as the reference (%d vs %d)"
          % (len(farm_files), len(ref_files)))
    # Renders too: Workbench on one machine and build renders the same pixels.
    for f in glbs + pngs:
        fp = os.path.join(out, f)
        if os.path.exists(fp):
            with open(fp, "rb") as x, open(os.path.join(ref, f), "rb") as y:
                check(x.read() == y.read(), "%s: farm bytes == single-machine bytes" % f)
    leftovers = [f for f in os.listdir(out) if f.startswith(".") and f.endswith(".tmp")]
    check(not leftovers, "no temporary files left after the merge: %s" % leftovers)

    man = os.path.join(out, "manifest.json")
    if check(os.path.isfile(man), "the merge task wrote manifest.json"):
        with open(man) as f:
            doc = json.load(f)
        recs = doc.get("records", [])
        check(sorted(r.get("seed") for r in recs) == list(range(seeds)), "manifest: one record per seed")
        names = sorted(x["name"] for r in recs for x in r.get("files", []))
        check(names == farm_files, "manifest: lists every output file once")
        for r in recs:
            for x in r.get("files", []):
                with open(os.path.join(out, x["name"]), "rb") as f:
                    check(hashlib.sha256(f.read()).hexdigest() == x.get("sha256"),
                          "manifest: %s's checksum matches the file" % x["name"])

    p = subprocess.run(["node", VALIDATE, "--no-warnings", out], capture_output=True, text=True, timeout=600)
    check(p.returncode == 0, "Khronos validator on the farm's .glb files: " + (p.stdout + p.stderr)[-2000:])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mode", choices=["compile", "run"])
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--lib", help="libbanyan.so (BANYAN_LIB for the runner)")
    ap.add_argument("--seeds", type=int, default=40)
    ap.add_argument("--per-task", type=int, default=5)
    ap.add_argument("--renders", type=int, default=4)
    ap.add_argument("--keep", action="store_true", help="keep the work folder")
    a = ap.parse_args()

    if a.mode == "compile":
        run_compile_checks()
    else:
        if not a.lib:
            ap.error("run needs --lib")
        workdir = tempfile.mkdtemp(prefix="banyan-flamenco-")
        try:
            run_farm_checks(shutil.which(a.blender) or a.blender, a.lib, a.seeds, a.per_task, a.renders, workdir)
        finally:
            if a.keep or failures:
                print("work folder kept: " + workdir)
            else:
                shutil.rmtree(workdir, ignore_errors=True)
    print("%d passed, %d failed" % (0 if failures else 1, 1 if failures else 0))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

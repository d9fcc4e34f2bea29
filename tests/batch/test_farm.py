"""The batch runner on a farm engine: 40 seeds of a small avenue, glTF for
all and 64 x 64 Workbench renders for 4.

    python3 tests/batch/test_farm.py BUILD_DIR reference   single machine (Blender): the reference
    python3 tests/batch/test_farm.py BUILD_DIR start|stop  a one-node Slurm cluster (tools/farm/slurm)
    python3 tests/batch/test_farm.py BUILD_DIR slurm       Slurm, 2 workers: == the reference, valid glTF
    python3 tests/batch/test_farm.py BUILD_DIR kill        Slurm, a task's Blender killed mid-task: retried, == reference

Exit 77 (ctest: skipped) with the reason when Blender or Slurm is not
installed or the test is not root (slurmd must be). Outputs go to
BUILD_DIR/batch_out/<mode>.
"""
import glob
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "..", ".."))
ADDON = os.path.join(SRC, "blender_addon", "banyan")
RUNNER = os.path.join(ADDON, "batch_run.py")
SLURM = os.path.join(SRC, "tools", "farm", "slurm")
PRESET = os.path.join(HERE, "avenue_batch_tiny.json")
SEEDS, RENDERS, PER_TASK, WORKERS = "0:40", "0:4", 10, 2
COMMON = ["--preset", PRESET, "--texture-size", "64", "--size", "64", "--engine", "WORKBENCH"]

BUILD = os.path.abspath(sys.argv[1])
MODE = sys.argv[2]
OUT = os.path.join(BUILD, "batch_out")
REF = os.path.join(OUT, "reference")
os.environ.setdefault("BANYAN_LIB", os.path.join(BUILD, "libbanyan.so"))
# The tests' own cluster (state, port) beside any other.
os.environ["BANYAN_SLURM_DIR"] = os.path.join(OUT, "slurm-state")
# The port follows the build folder, so two build folders' tests can run at once.
os.environ["BANYAN_SLURM_PORT"] = os.environ.get(
    "BANYAN_TEST_SLURM_PORT", str(7000 + 2 * (int(hashlib.sha256(BUILD.encode()).hexdigest(), 16) % 1000)))
os.environ["SLURM_CONF"] = os.path.join(OUT, "slurm-state", "slurm.conf")
BLENDER = shutil.which("blender")

failed = 0


def check(ok, what):
    global failed
    print(("ok: " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failed += 1
    return ok


def skip(why):
    print("SKIPPED: " + why, flush=True)
    sys.exit(77)


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def outputs(folder):
    """{name: sha256} of the runner's outputs (.glb, .png) in folder."""
    return {os.path.basename(p): sha(p) for p in sorted(glob.glob(os.path.join(folder, "*.glb"))
                                                        + glob.glob(os.path.join(folder, "*.png")))}


def need_slurm():
    if not all(shutil.which(t) or os.path.exists("/usr/sbin/" + t) for t in ("sbatch", "slurmctld", "slurmd",
                                                                            "munged")):
        skip("Slurm is not installed (apt-get install slurm-wlm munge: tools/setup.sh)")
    if os.geteuid() != 0:
        skip("a one-node Slurm cluster needs root (slurmd); run the tests as root")
    if not BLENDER:
        skip("blender is not installed (tools/setup.sh)")
    if not os.path.isfile(os.path.join(REF, "manifest.json")):
        check(False, "the reference run (batch_farm_reference) has not finished: %s" % REF)
        sys.exit(1)


def check_manifest(folder, what):
    """The merged manifest: one record per seed, 40 .glb and 4 .png with
    the files' checksums; returns {name: sha256} of the files it lists."""
    try:
        with open(os.path.join(folder, "manifest.json")) as f:
            man = json.load(f)
    except (OSError, ValueError) as e:
        check(False, "%s: manifest.json: %s" % (what, e))
        return {}
    seeds = [r["seed"] for r in man["records"]]
    check(seeds == list(range(40)), "%s: the manifest has one record per seed 0..39" % what)
    listed = {f["name"]: f["sha256"] for r in man["records"] for f in r["files"]}
    glb = [n for n in listed if n.endswith(".glb")]
    png = sorted(n for n in listed if n.endswith(".png"))
    check(len(glb) == 40 and len(png) == 4 and all(p.rsplit("-s", 1)[1] in ("0.png", "1.png", "2.png", "3.png")
                                                   for p in png),
          "%s: 40 .glb and 4 .png (seeds 0-3) listed (%d, %s)" % (what, len(glb), png))
    check(listed == outputs(folder), "%s: the manifest's checksums are the folder's files" % what)
    check(all(r["banyan_version"] and r["seconds"] >= 0 and len(r["params_hash"]) == 64 for r in man["records"]),
          "%s: every record has version, time and parameter hash" % what)
    check(all(r["blender_version"] for r in man["records"] if any(f["name"].endswith(".png") for f in r["files"])),
          "%s: the rendered seeds' records name Blender's version" % what)
    check(not glob.glob(os.path.join(folder, ".*")) and not glob.glob(os.path.join(folder, "manifest", ".*")),
          "%s: no temporary file left" % what)
    return listed


def reference():
    if not BLENDER:
        skip("blender is not installed (tools/setup.sh)")
    shutil.rmtree(REF, ignore_errors=True)
    t0 = time.time()
    r = subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1", "--python", RUNNER, "--",
                        "--seeds", SEEDS, "--render-seeds", RENDERS, "--out", REF, "--quiet"] + COMMON,
                       capture_output=True, text=True, timeout=1200)
    check(r.returncode == 0, "reference run: exit %d (%s)" % (r.returncode, (r.stdout + r.stderr)[-800:]))
    print("reference: 40 seeds, 4 renders in %.1f s (one Blender)" % (time.time() - t0))
    r = subprocess.run([sys.executable, RUNNER, "--", "--merge-manifest", REF, "--seeds", SEEDS, "--verify"],
                       capture_output=True, text=True, timeout=600)
    check(r.returncode == 0, "reference merge: exit %d (%s)" % (r.returncode, (r.stdout + r.stderr)[-400:]))
    check_manifest(REF, "reference")
    # The renders are pictures: 64 x 64 PNGs, not one flat colour.
    import zlib
    for p in sorted(glob.glob(os.path.join(REF, "*.png"))):
        with open(p, "rb") as f:
            data = f.read()
        check(data[:8] == b"\x89PNG\r\n\x1a\n" and data[16:24] == (64).to_bytes(4, "big") * 2,
              "%s: a 64 x 64 PNG" % os.path.basename(p))
        raw = zlib.decompress(b"".join(_chunks(data, b"IDAT")))
        check(len(set(raw)) > 16, "%s: not a flat picture (%d distinct bytes)" % (os.path.basename(p), len(set(raw))))


def _chunks(data, kind):
    i = 8
    while i < len(data):
        n = int.from_bytes(data[i:i + 4], "big")
        if data[i + 4:i + 8] == kind:
            yield data[i + 8:i + 8 + n]
        i += 12 + n


def cluster(action):
    if action == "start":
        need_slurm()
    elif not os.path.isdir(os.environ["BANYAN_SLURM_DIR"]):
        return
    r = subprocess.run(["sh", os.path.join(SLURM, "cluster_%s.sh" % action)], capture_output=True, text=True,
                       timeout=300)
    check(r.returncode == 0, "cluster_%s.sh: exit %d (%s)" % (action, r.returncode, (r.stdout + r.stderr)[-600:]))
    if action == "start":  # idempotent: a second start leaves it running
        r = subprocess.run(["sh", os.path.join(SLURM, "cluster_start.sh")], capture_output=True, text=True,
                           timeout=300)
        check(r.returncode == 0, "cluster_start.sh again: exit %d" % r.returncode)
        r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T %c"], capture_output=True, text=True)
        check(r.returncode == 0 and r.stdout.split()[:2] in (["idle", "2"], ["mixed", "2"]),
              "one node with 2 CPUs (%s)" % r.stdout.strip())


def _squeue():
    r = subprocess.run(["squeue", "-h", "-o", "%i %T"], capture_output=True, text=True)
    return [line.split() for line in r.stdout.splitlines() if line.strip()]


def _pids_of(pattern_a, pattern_b):
    """Processes whose command line holds both strings (ours: this test's
    output folder is in it)."""
    out = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % d, "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if pattern_a in cmd and pattern_b in cmd:
            out.append(int(d))
    return out


def farm(kill):
    need_slurm()
    name = "kill" if kill else "slurm"
    out = os.path.join(OUT, name)
    logs = out + ".slurm-logs"
    shutil.rmtree(out, ignore_errors=True)
    shutil.rmtree(logs, ignore_errors=True)
    t0 = time.time()
    r = subprocess.run(["sh", os.path.join(SLURM, "submit.sh"), "--per-task", str(PER_TASK), "--workers",
                        str(WORKERS), "--seeds", SEEDS, "--render-seeds", RENDERS, "--out", out, "--quiet"]
                       + COMMON, capture_output=True, text=True, timeout=120)
    if not check(r.returncode == 0 and len(r.stdout.split()) == 2,
                 "submit.sh: exit %d (%s)" % (r.returncode, (r.stdout + r.stderr)[-400:])):
        return
    array, merge = r.stdout.split()
    running_max, killed = 0, None
    first = os.path.join(out, sorted(n for n in outputs(REF) if n.endswith("-s0.glb"))[0])
    while True:
        q = [j for j in _squeue() if j[0].split("_")[0] in (array, merge)]
        running_max = max(running_max, sum(1 for j in q if j[1] == "RUNNING" and j[0].startswith(array + "_")))
        if kill and killed is None and os.path.exists(first):
            # Task 0 (seeds 0-9, renders 0-3) runs in Blender; its seed 0
            # .glb is out, its render not yet: kill -9 its Blender.
            pids = [p for p in _pids_of("--out %s" % out, "--factory-startup") if p != os.getpid()]
            pids = [p for p in pids if b"blender" in open("/proc/%d/cmdline" % p, "rb").read().split(b"\0")[0]]
            if pids:
                os.kill(pids[0], signal.SIGKILL)
                killed = pids[0]
                print("killed task 0's Blender (pid %d) %.1f s after submitting" % (killed, time.time() - t0))
        if not q:
            break
        if time.time() - t0 > 1200:
            check(False, "%s: the jobs did not finish in 1200 s" % name)
            subprocess.run(["scancel", array, merge])
            return
        time.sleep(0.05)
    dt = time.time() - t0
    print("%s: 40 seeds, 4 renders through Slurm (%d workers, tasks of %d) in %.1f s" % (name, WORKERS, PER_TASK, dt))
    text = ""
    for p in sorted(glob.glob(os.path.join(logs, "*.out"))):
        with open(p, errors="replace") as f:
            text += f.read()
    check(running_max >= 2, "%s: two array tasks ran at once (at most %d seen)" % (name, running_max))
    check("seeds without a record" not in text and "manifest %s/manifest.json: 40 records, 44 files" % out in text,
          "%s: the merge job found every seed's record" % name)
    if kill:
        check(killed is not None, "kill: task 0's Blender was found and killed")
        check("runner exit 137: requeued" in text and "task 0 (restart 1)" in text,
              "kill: the killed task was requeued by Slurm and ran again (restart 1)")
    listed = check_manifest(out, name)
    ref = outputs(REF)
    mine = outputs(out)
    check(mine == ref, "%s: the folder's .glb and .png equal the single-machine run byte for byte (%d files; "
                       "differ: %s)" % (name, len(mine), sorted(set(ref.items()) ^ set(mine.items()))[:4]))
    check(listed == ref, "%s: the manifest lists exactly the reference's files" % name)
    if not kill:
        node = os.environ.get("BANYAN_NODE") or shutil.which("node")
        if check(node is not None, "node for the Khronos validator"):
            r = subprocess.run([node, os.path.join(SRC, "tests", "gltf", "validate.mjs"), "--no-warnings", out],
                               capture_output=True, text=True, timeout=1200)
            check(r.returncode == 0, "every .glb passes the Khronos validator (%s)" % (r.stdout + r.stderr)[-600:])
    # Idempotent through the engine too: the same submission again makes nothing.
    if not kill:
        def stamps():  # the runner's files and records (the merge rewrites manifest.json)
            return {p: os.stat(p).st_mtime_ns for p in glob.glob(os.path.join(out, "*-s*.*"))
                    + glob.glob(os.path.join(out, "manifest", "*.json"))}
        before = stamps()
        r = subprocess.run(["sh", os.path.join(SLURM, "submit.sh"), "--per-task", str(PER_TASK), "--workers",
                            str(WORKERS), "--seeds", SEEDS, "--render-seeds", RENDERS, "--out",
                            out] + COMMON, capture_output=True, text=True, timeout=120)
        if check(r.returncode == 0, "resubmit"):
            ids = r.stdout.split()
            t1 = time.time()
            while [j for j in _squeue() if j[0].split("_")[0] in ids] and time.time() - t1 < 600:
                time.sleep(0.2)
            after = stamps()
            text = ""
            for p in sorted(glob.glob(os.path.join(logs, "slurm-%s_*.out" % ids[0]))):
                with open(p, errors="replace") as f:
                    text += f.read()
            check(text.count("0 made, 10 skipped, 0 failed") == 4 and before == after and len(before) == 84,
                  "a second submission skips all 40 seeds and rewrites no file (%d skip lines, %d files, %d "
                  "changed)" % (text.count("0 made, 10 skipped, 0 failed"), len(before),
                                sum(before.get(k) != v for k, v in after.items())))


if MODE == "reference":
    reference()
elif MODE in ("start", "stop"):
    cluster(MODE)
elif MODE in ("slurm", "kill"):
    farm(MODE == "kill")
else:
    print("usage: test_farm.py BUILD_DIR reference|start|stop|slurm|kill", file=sys.stderr)
    sys.exit(2)
print("test_farm %s: %s" % (MODE, "FAILED" if failed else "passed"))
sys.exit(1 if failed else 0)

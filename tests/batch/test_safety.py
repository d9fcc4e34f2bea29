"""The batch runner and its Slurm scripts on shared storage, safely
(docs/batch.md, "Locks, temporary files and symlinks", "Limits"): in
plain python3 with a fake `sbatch`, no Blender, no cluster.

- submit.sh passes --out and --seeds as data: injection strings create no
  file and the merge job (run from what the fake sbatch recorded, without
  a shell string) gets the literal path;
- seeds are decimal everywhere (010:020 is 10..19, 09:12 works), `1_0`
  and Arabic-Indic digits are refused, --per-task 0 is refused;
- two runners on overlapping seeds both finish and every file equals a
  single run's bytes; a symlink planted at the next output name leaves
  its target alone; a user's .thesis.tmp survives runs and merges;
- merges: mixed preset hashes fail naming the records and keep the old
  manifest.json; --hash/--preset choose; malformed records are named
  (file, field) with no traceback; a huge range is refused at once;
- --out naming a file, a 5 MiB preset (refused before it is read),
  "hosts" of a wrong type: exit 2 with a message;
- a runner whose parent is killed stops.

    python3 tests/batch/test_safety.py BUILD_DIR
"""
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from farm_common import ADDON, PRESET, RUNNER, SRC, check, finish, sha

SLURM = os.path.join(SRC, "tools", "farm", "slurm")
TS = ["--texture-size", "64"]


def runner(*args, timeout=300):
    try:
        r = subprocess.run([sys.executable, RUNNER, "--"] + [str(a) for a in args], capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired as e:
        return -1, "timed out after %d s: %s" % (timeout, (e.stdout or b"")[-300:])
    return r.returncode, r.stdout + r.stderr


def glbs(folder):
    return {os.path.basename(p): sha(p) for p in glob.glob(os.path.join(folder, "*.glb"))}


def no_traceback(out):
    return "Traceback" not in out


tmp = tempfile.mkdtemp(prefix="banyan_safety_")
try:
    # ------------------------------------------------------------ reference
    ref = os.path.join(tmp, "ref")
    rc, log = runner("--preset", PRESET, "--seeds", "0:12", "--out", ref, *TS)
    check(rc == 0, "reference run 0:12 (%s)" % log[-300:])
    REF = glbs(ref)
    prefix = sorted(REF)[0].rsplit("-s", 1)[0]  # <preset>-<hash12>
    HASH12 = prefix.rsplit("-", 1)[1]

    # ---------------------------------------------- submit.sh with a fake sbatch
    fake = os.path.join(tmp, "fakebin")
    os.makedirs(fake)
    calls = os.path.join(tmp, "sbatch_calls.jsonl")
    with open(os.path.join(fake, "sbatch"), "w") as f:
        f.write("""#!%s
import json, os, shutil, sys
argv = sys.argv[1:]
script, wrap, i = None, None, 0
while i < len(argv):
    a = argv[i]
    if a == "--wrap":  # Slurm runs it as the body of a /bin/sh script
        wrap = argv[i + 1]
        break
    if a.startswith("-"):
        i += 1
        continue
    script = a
    break
n = sum(1 for _ in open(%r)) if os.path.exists(%r) else 0
copy = os.path.join(%r, "script%%d" %% n)
if script:
    shutil.copy(script, copy)
elif wrap is not None:
    with open(copy, "w") as f:
        f.write("#!/bin/sh\\n" + wrap + "\\n")
with open(%r, "a") as f:
    f.write(json.dumps({"argv": argv, "script": script, "wrap": wrap, "copy": copy}) + "\\n")
print("%%d" %% (1000 + (sum(1 for _ in open(%r)))))
""" % (sys.executable, calls, calls, tmp, calls, calls))
    os.chmod(os.path.join(fake, "sbatch"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ["PATH"], BANYAN_ADDON=ADDON,
               BANYAN_PYTHON=sys.executable)
    work = os.path.join(tmp, "cwd")
    os.makedirs(work)

    def submit(*args):
        if os.path.exists(calls):
            os.remove(calls)
        r = subprocess.run(["sh", os.path.join(SLURM, "submit.sh")] + list(args), capture_output=True, text=True,
                           env=env, cwd=work, timeout=60)
        rec = []
        if os.path.exists(calls):
            with open(calls) as f:
                rec = [json.loads(line) for line in f]
        return r.returncode, r.stdout + r.stderr, rec

    def after(argv, script_name):
        """The arguments sbatch gives the batch script."""
        i = [k for k, a in enumerate(argv) if a.endswith(script_name)]
        return argv[i[0] + 1:] if i else None

    def pwned():
        return glob.glob(os.path.join(tmp, "**", "PWNED"), recursive=True) + glob.glob("PWNED")

    for label, name in (("command substitution", "o'$(touch PWNED)'x"), ("an apostrophe", "Bob's trees"),
                        ("backquotes and $HOME", 'q"`touch PWNED`$HOME %j x')):
        out = os.path.join(tmp, name)
        rc, log, rec = submit("--per-task", "2", "--workers", "1", "--seeds", "0:3", "--out", out,
                              "--preset", PRESET, *TS, "--quiet")
        check(rc == 0 and len(rec) == 2, "submit.sh --out with %s: exit 0, two sbatch calls (%s)" % (label, log))
        check(not pwned(), "submit.sh --out with %s: no file PWNED made" % label)
        if len(rec) != 2:
            continue
        arr, mrg = rec
        check("--wrap" not in " ".join(mrg["argv"]), "%s: the merge job is no --wrap string" % label)
        a_args = after(arr["argv"], "banyan_array.sbatch")
        m_args = after(mrg["argv"], "banyan_merge.sbatch")
        check(a_args is not None and a_args[a_args.index("--out") + 1] == out,
              "%s: the array job gets the literal --out (%s)" % (label, a_args))
        check(m_args is not None and m_args[:6] == ["--merge-manifest", out, "--seeds", "0:3", "--verify",
                                                    "--preset"],
              "%s: the merge job gets the literal path as argv (%s)" % (label, m_args))
        if m_args is None and mrg.get("wrap") is not None:  # a --wrap string: run it as Slurm does
            subprocess.run(["sh", mrg["copy"]], env=env, cwd=work, capture_output=True, timeout=300)
            check(not pwned(), "%s: the merge's --wrap string makes no file PWNED" % label)
        if m_args is None or a_args is None:
            continue
        # Run the array task and the merge from the recorded scripts and argv
        # (bash SCRIPT ARGS: no shell string).
        for task in (0, 1):
            r = subprocess.run(["bash", arr["copy"]] + a_args, env=dict(env, SLURM_ARRAY_TASK_ID=str(task)),
                               capture_output=True, text=True, cwd=work, timeout=300)
            check(r.returncode == 0, "%s: array task %d (%s)" % (label, task, (r.stdout + r.stderr)[-300:]))
        r = subprocess.run(["bash", mrg["copy"]] + m_args, env=env, capture_output=True, text=True, cwd=work,
                           timeout=300)
        check(r.returncode == 0 and os.path.isfile(os.path.join(out, "manifest.json")),
              "%s: the recorded merge runs and writes %s/manifest.json (%s)" % (label, out,
                                                                             (r.stdout + r.stderr)[-300:]))
        check(not pwned(), "%s: still no PWNED after running the jobs" % label)
        check(glbs(out) == {k: v for k, v in REF.items() if k.rsplit("-s", 1)[1] in ("0.glb", "1.glb", "2.glb")},
              "%s: the jobs' files are the reference's" % label)

    # Seeds: injection, decimal, refusals (submit.sh and the runner).
    out = os.path.join(tmp, "seeds")
    for seeds in ("0:x'$(touch PWNED)'y:10", "0:$(touch PWNED)", "1_0:2_0", "\u0660:\u0665", "0:4294967296",
                  "5:5", "09", ""):
        rc, log, rec = submit("--per-task", "2", "--seeds", seeds, "--out", out, "--preset", PRESET)
        check(rc == 2 and not rec and "--seeds" in log, "submit.sh --seeds %r refused, nothing queued (%d: %s)"
              % (seeds, rc, log))
    check(not pwned(), "no PWNED from --seeds")
    for per in ("0", "00", "-1", "x", "\u0662"):
        rc, log, rec = submit("--per-task", per, "--seeds", "0:4", "--out", out, "--preset", PRESET)
        check(rc == 2 and not rec and "--per-task" in log, "submit.sh --per-task %r refused (%s)" % (per, log))
    rc, log, rec = submit("--per-task", "1", "--workers", "0", "--seeds", "0:4", "--out", out)
    check(rc == 2 and not rec, "submit.sh --workers 0 refused")
    for seeds, per, norm, array in (("010:020", "02", "10:20", "0-4"), ("09:12", "1", "9:12", "0-2")):
        rc, log, rec = submit("--per-task", per, "--seeds", seeds, "--out", out, "--preset", PRESET, *TS)
        ok = rc == 0 and len(rec) == 2
        a_args = after(rec[0]["argv"], "banyan_array.sbatch") if ok else []
        m_args = after(rec[1]["argv"], "banyan_merge.sbatch") if ok else []
        check(ok and "--array=%s" % array in rec[0]["argv"] and a_args[a_args.index("--seeds") + 1] == norm
              and a_args[a_args.index("--per-task") + 1] == str(int(per, 10))
              and m_args[m_args.index("--seeds") + 1] == norm,
              "submit.sh --seeds %s: decimal %s, array %s (%s %s)" % (seeds, norm, array, log, rec))
    # The array script alone: decimal, refusals.
    arr_env = dict(env, BANYAN_PYTHON="echo")
    for task, seeds, per, want in (("1", "010:020", "05", "--seeds 15:20"), ("0", "09:12", "1", "--seeds 9:10"),
                                   ("2", "008:012", "2", "--seeds 12:12")):
        r = subprocess.run(["bash", os.path.join(SLURM, "banyan_array.sbatch"), "--per-task", per, "--seeds", seeds,
                            "--out", out], env=dict(arr_env, SLURM_ARRAY_TASK_ID=task), capture_output=True,
                           text=True, timeout=30)
        text = r.stdout + r.stderr
        if want.endswith("12:12"):
            check(r.returncode == 0 and "no seeds left" in text, "sbatch %s task %s: nothing left" % (seeds, task))
        else:
            check(r.returncode == 0 and want in text, "banyan_array.sbatch %s task %s K=%s: %s (%s)"
                  % (seeds, task, per, want, text))
    for per, seeds in (("0", "0:4"), ("1", "1_0:2_0"), ("1", "\u0660:\u0665"), ("1", "0:x$(touch PWNED)")):
        r = subprocess.run(["bash", os.path.join(SLURM, "banyan_array.sbatch"), "--per-task", per, "--seeds", seeds,
                            "--out", out], env=arr_env, capture_output=True, text=True, timeout=30, cwd=work)
        check(r.returncode == 2, "banyan_array.sbatch --per-task %s --seeds %r refused (%d)" % (per, seeds,
                                                                                                r.returncode))
    check(not pwned(), "no PWNED from the array script")
    # The runner.
    dec = os.path.join(tmp, "dec")
    rc, log = runner("--preset", PRESET, "--seeds", "010:012", "--out", dec, *TS)
    check(rc == 0 and sorted(glbs(dec)) == [prefix + "-s10.glb", prefix + "-s11.glb"],
          "runner --seeds 010:012 makes seeds 10 and 11 (%s)" % sorted(glbs(dec)))
    rc, log = runner("--preset", PRESET, "--seeds", "09:010", "--out", dec, *TS)
    check(rc == 0 and prefix + "-s9.glb" in glbs(dec), "runner --seeds 09:010 makes seed 9")
    for seeds in ("1_0:2_0", "\u0660:\u0662", "1:\uff12", " 1:2", "1:2\n", "+1:2"):
        rc, log = runner("--preset", PRESET, "--seeds", seeds, "--out", dec, *TS)
        check(rc == 2 and "--seeds" in log and no_traceback(log), "runner --seeds %r refused" % seeds)
    for opt, val in (("--size", "\u0666\u0664"), ("--threads", "1_0"), ("--texture-size", "\u0666\u0664")):
        rc, log = runner("--preset", PRESET, "--seeds", "0:1", "--out", dec, opt, val)
        check(rc == 2 and opt in log, "runner %s %r refused (%s)" % (opt, val, log[-200:]))
    # Caps: refused at once, naming the range and the cap.
    for args in (["--preset", PRESET, "--seeds", "0:4294967296", "--out", dec],
                 ["--merge-manifest", dec, "--seeds", "0:4294967296"]):
        t0 = time.time()
        rc, log = runner(*args, timeout=60)
        check(rc == 2 and "0:4294967296" in log and "10000000" in log and time.time() - t0 < 20,
              "%s %s refused at once naming the range and the cap (%d, %.1f s: %s)"
              % (args[0], "0:4294967296", rc, time.time() - t0, log[-200:]))

    # --out naming a file; a big preset; hosts of a wrong type.
    afile = os.path.join(tmp, "a_file")
    with open(afile, "w") as f:
        f.write("x")
    rc, log = runner("--preset", PRESET, "--seeds", "0:1", "--out", afile)
    check(rc == 2 and "a_file" in log and "not a folder" in log and no_traceback(log), "--out a file: exit 2 (%s)"
          % log[-200:])
    rc, log = runner("--merge-manifest", afile)
    check(rc == 2 and "not a folder" in log and no_traceback(log), "--merge-manifest a file: exit 2")
    big = os.path.join(tmp, "big.json")
    with open(big, "wb") as f:
        f.write(b'{"generator": "avenue", "schema": 1, "params": {}, "pad": "' + b"x" * (5 << 20) + b'"}')
    rc, log = runner("--preset", big, "--seeds", "0:1", "--out", dec)
    check(rc == 2 and "4194304" in log and no_traceback(log), "a 5 MiB preset refused naming the limit (%s)"
          % log[-200:])
    huge = os.path.join(tmp, "huge.json")  # sparse: reading it would take minutes and 16 GiB
    with open(huge, "wb") as f:
        f.truncate(16 << 30)
    t0 = time.time()
    rc, log = runner("--preset", huge, "--seeds", "0:1", "--out", dec, timeout=60)
    check(rc == 2 and "limit" in log and time.time() - t0 < 10, "a 16 GiB preset refused without reading it "
          "(%.1f s)" % (time.time() - t0))
    with open(PRESET) as f:
        pdoc = json.load(f)
    for hosts in ([], {}, 0, None, "wall"):
        bad = os.path.join(tmp, "hosts.json")
        with open(bad, "w") as f:
            json.dump(dict(pdoc, hosts=hosts), f)
        rc, log = runner("--preset", bad, "--seeds", "0:1", "--out", dec)
        check(rc == 2 and "hosts" in log and no_traceback(log), "\"hosts\": %r refused (%s)" % (hosts, log[-200:]))

    # ------------------------------------------ overlapping runners at once
    ov = os.path.join(tmp, "overlap")
    thesis = os.path.join(ov, ".thesis.tmp")
    os.makedirs(ov)
    with open(thesis, "w") as f:
        f.write("my thesis")
    procs = [subprocess.Popen([sys.executable, RUNNER, "--", "--preset", PRESET, "--seeds", s, "--out", ov] + TS,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
             for s in ("0:8", "2:10", "4:12", "0:12")]
    outs = [p.communicate(timeout=600)[0] for p in procs]
    check(all(p.returncode == 0 for p in procs), "four overlapping runners all exit 0 (%s)"
          % [(p.returncode, o[-200:]) for p, o in zip(procs, outs) if p.returncode])
    check(glbs(ov) == REF, "overlapping runners: every .glb equals the single run's bytes")
    check(not [n for n in os.listdir(ov) if n.startswith(".") and n != ".thesis.tmp"]
          and not [n for n in os.listdir(os.path.join(ov, "manifest")) if n.startswith(".")],
          "overlapping runners: no lock or temporary file left (%s)" % os.listdir(ov))
    rc, log = runner("--merge-manifest", ov, "--seeds", "0:12", "--verify")
    check(rc == 0, "merge of the overlapping runs (%s)" % log[-300:])
    check(os.path.isfile(thesis) and open(thesis).read() == "my thesis", "a user's .thesis.tmp survives runs and merge")

    # ---------------------------------------------- a planted symlink
    sl = os.path.join(tmp, "symlink")
    rc, log = runner("--preset", PRESET, "--seeds", "0:1", "--out", sl, *TS)
    victim = os.path.join(tmp, "victim.txt")
    victim2 = os.path.join(tmp, "victim2.txt")
    for v in (victim, victim2):
        with open(v, "w") as f:
            f.write("precious")
    os.symlink(victim, os.path.join(sl, prefix + "-s1.glb"))
    os.symlink(victim2, os.path.join(sl, "manifest", prefix + "-s1.json"))
    rc, log = runner("--preset", PRESET, "--seeds", "0:2", "--out", sl, *TS)
    check(rc == 0, "a run over planted symlinks (%s)" % log[-300:])
    check(open(victim, "rb").read() == b"precious" and open(victim2, "rb").read() == b"precious",
          "the symlinks' targets are untouched")
    g1 = os.path.join(sl, prefix + "-s1.glb")
    check(not os.path.islink(g1) and sha(g1) == REF[prefix + "-s1.glb"]
          and not os.path.islink(os.path.join(sl, "manifest", prefix + "-s1.json")),
          "the links were replaced by the seed's own files")
    # A link to a file with the right bytes is still not trusted.
    os.remove(g1)
    shutil.copy(os.path.join(ref, prefix + "-s1.glb"), os.path.join(tmp, "copy.glb"))
    os.symlink(os.path.join(tmp, "copy.glb"), g1)
    rc, log = runner("--preset", PRESET, "--seeds", "1:2", "--out", sl, *TS)
    check(rc == 0 and not os.path.islink(g1) and "made" in log, "a symlinked output is made again as a file")
    os.remove(os.path.join(sl, "manifest", prefix + "-s0.json"))
    os.symlink(victim, os.path.join(sl, "manifest.json"))
    rc, log = runner("--merge-manifest", sl)
    check(rc == 0 and open(victim, "rb").read() == b"precious" and not os.path.islink(os.path.join(sl, "manifest.json")),
          "manifest.json is written beside a planted link, not through it")
    os.remove(os.path.join(sl, "manifest.json"))
    os.symlink(victim, os.path.join(sl, "manifest", ".%s-s0.lock" % prefix))
    rc, log = runner("--preset", PRESET, "--seeds", "0:1", "--out", sl, *TS)
    check(rc == 1 and "symlink" in log and open(victim, "rb").read() == b"precious", "a symlinked lock file is refused")

    # -------------------------------------------------------- merges
    mx = os.path.join(tmp, "mixed")
    rc, log = runner("--preset", PRESET, "--seeds", "0:3", "--out", mx, *TS)
    rc, log = runner("--merge-manifest", mx, "--seeds", "0:3", "--verify")
    check(rc == 0, "merge of 0:3")
    man = os.path.join(mx, "manifest.json")
    good_manifest = open(man, "rb").read()
    vdir = os.path.join(tmp, "variant")
    os.makedirs(vdir)
    vdoc = json.loads(json.dumps(pdoc))
    vdoc["params"]["count"] = 1
    variant = os.path.join(vdir, "avenue_batch_tiny.json")  # the same preset name, another hash
    with open(variant, "w") as f:
        json.dump(vdoc, f)
    rc, log = runner("--preset", variant, "--seeds", "3:6", "--out", mx, *TS)
    vprefix = [n for n in glbs(mx) if not n.startswith(prefix)][0].rsplit("-s", 1)[0]
    rc, log = runner("--merge-manifest", mx, "--seeds", "0:6", "--verify")
    check(rc == 1 and "2 preset hashes" in log and prefix + "-s0.json" in log and vprefix + "-s3.json" in log,
          "mixed preset hashes fail the merge naming the records (%d: %s)" % (rc, log[-500:]))
    check(open(man, "rb").read() == good_manifest, "the failed merge leaves manifest.json as it was")
    rc, log = runner("--merge-manifest", mx, "--seeds", "0:6", "--verify", "--hash", HASH12)
    check(rc == 1 and "3:6" in log and HASH12 in log, "--hash: the other hash's seeds are missing (%s)" % log[-300:])
    rc, log = runner("--merge-manifest", mx, "--seeds", "3:6", "--verify", "--preset", variant, *TS)
    check(rc == 0, "--preset chooses the variant's hash: 3:6 complete (%s)" % log[-300:])
    rc, log = runner("--merge-manifest", mx, "--seeds", "0:6", "--preset", PRESET, "--texture-size", "128")
    check(rc == 1 and "0:6" in log, "--preset with other glTF options: another hash, nothing there")
    rc, log = runner("--merge-manifest", mx, "--hash", "xyz")
    check(rc == 2 and "--hash" in log, "a bad --hash refused")
    good_manifest = open(man, "rb").read()
    g = os.path.join(mx, prefix + "-s1.glb")
    with open(g, "ab") as f:
        f.write(b"x")
    rc, log = runner("--merge-manifest", mx, "--verify")
    check(rc == 1 and prefix + "-s1.json" in log and prefix + "-s1.glb" in log
          and open(man, "rb").read() == good_manifest, "a failed verify names the record and keeps manifest.json")
    shutil.copy(os.path.join(ref, prefix + "-s1.glb"), g)

    # Malformed records: named by file and field, never a traceback.
    rec_path = os.path.join(mx, "manifest", prefix + "-s2.json")
    with open(rec_path) as f:
        good = json.load(f)
    cases = [("files", 5), ("files", None), ("files", ["x"]), ("preset", "__drop__"), ("seed", "1"),
             ("seed", True), ("files", [{"name": "../../etc/passwd", "sha256": "0" * 64, "bytes": 1}]),
             ("files", [{"name": prefix + "-s2.glb", "sha256": "0" * 64, "bytes": "5"}]), ("name", "other"),
             ("preset_hash", 7), ("schema", "__drop__")]
    for field, value in cases:
        rec = dict(good)
        if value == "__drop__":
            del rec[field]
        else:
            rec[field] = value
        with open(rec_path, "w") as f:
            json.dump(rec, f)
        rc, log = runner("--merge-manifest", mx, "--seeds", "0:3")
        check(rc in (1, 2) and prefix + "-s2.json" in log and "'%s" % field in log and no_traceback(log),
              "merge: a record with %s=%r named by file and field, no traceback (%d: %s)"
              % (field, value, rc, log[-300:]))
        rc, log = runner("--preset", PRESET, "--seeds", "2:3", "--out", mx, *TS)
        check(rc == 0 and "malformed" in log and no_traceback(log), "runner: the record with %s=%r is made again "
              "(%d: %s)" % (field, value, rc, log[-300:]))
        check(json.load(open(rec_path))["files"] == good["files"], "runner: the record is whole again")
    for text in ("{", "[]", "null", "\"x\"", ""):
        with open(rec_path, "w") as f:
            f.write(text)
        rc, log = runner("--merge-manifest", mx)
        check(rc == 1 and prefix + "-s2.json" in log and no_traceback(log), "merge: a record %r named" % text)
        rc, log = runner("--preset", PRESET, "--seeds", "2:3", "--out", mx, *TS)
        check(rc == 0 and no_traceback(log), "runner: a record %r is made again" % text)

    # ------------------------------------------- a killed parent stops the runner
    orphan = os.path.join(tmp, "orphan")
    err = os.path.join(tmp, "orphan.err")
    parent = subprocess.Popen([sys.executable, "-c", """
import subprocess, sys
p = subprocess.Popen([sys.executable, %r, "--", "--preset", %r, "--seeds", "0:1000000", "--out", %r,
                      "--texture-size", "64"], stdout=subprocess.DEVNULL, stderr=open(%r, "w"))
print(p.pid, flush=True)
p.wait()
""" % (RUNNER, PRESET, orphan, err)], stdout=subprocess.PIPE, text=True)
    child = int(parent.stdout.readline())
    t0 = time.time()
    while time.time() - t0 < 30 and len(glob.glob(os.path.join(orphan, "*.glb"))) < 3:
        time.sleep(0.1)
    check(len(glob.glob(os.path.join(orphan, "*.glb"))) >= 3, "the runner under a parent makes seeds")
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    t0 = time.time()

    def alive(pid):
        try:
            with open("/proc/%d/stat" % pid) as f:
                return f.read().split(")")[-1].split()[0] not in ("Z", "X")
        except OSError:
            return False
    while time.time() - t0 < 15 and alive(child):
        time.sleep(0.1)
    stopped = not alive(child)
    if not stopped:
        os.kill(child, signal.SIGKILL)
    check(stopped, "the runner stops within 15 s of its parent's death (%.1f s)" % (time.time() - t0))
    check("parent process" in open(err).read(), "the orphaned runner says why it stopped")
    n = len(glob.glob(os.path.join(orphan, "*.glb")))
    # --no-parent-watch: the runner goes on without its parent.
    err2 = os.path.join(tmp, "orphan2.err")
    parent = subprocess.Popen([sys.executable, "-c", """
import subprocess, sys
p = subprocess.Popen([sys.executable, %r, "--", "--preset", %r, "--seeds", "0:1000000", "--out", %r,
                      "--texture-size", "64", "--no-parent-watch"], stdout=subprocess.DEVNULL, stderr=open(%r, "w"))
print(p.pid, flush=True)
p.wait()
""" % (RUNNER, PRESET, os.path.join(tmp, "orphan2"), err2)], stdout=subprocess.PIPE, text=True)
    child2 = int(parent.stdout.readline())
    time.sleep(1.0)
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    time.sleep(2.0)
    check(alive(child2), "--no-parent-watch: the runner goes on after its parent's death")
    os.kill(child2, signal.SIGKILL)
    # Its leftovers (lock file, private folder) belong to a dead owner: the
    # next run takes the seed over at once.
    rc, log = runner("--preset", PRESET, "--seeds", "%d:%d" % (max(0, n - 2), n + 2), "--out", orphan, *TS, timeout=60)
    check(rc == 0 and "waiting" not in log, "the next run is not held up by the dead runner's lock (%s)" % log[-300:])
    check(not [x for x in os.listdir(orphan) if x.startswith(".")]
          and not [x for x in os.listdir(os.path.join(orphan, "manifest")) if x.startswith(".")],
          "the dead runner's temporary files and lock are gone")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

finish("test_safety")

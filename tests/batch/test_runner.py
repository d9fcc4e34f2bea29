"""The batch runner (blender_addon/banyan/batch_run.py) in plain python3:
refusals (exit 2 naming the bad argument), names by (preset hash, seed),
the CLI's bytes, records that match their files, idempotence (a re-run
skips everything; a corrupted, missing or half-written file is made
again, nothing else is touched) and the merged manifest.

    python3 tests/batch/test_runner.py BUILD_DIR
(ctest sets BANYAN_LIB to BUILD_DIR's library.)"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

from farm_common import BUILD, PRESET, RUNNER, check, finish, sha

CLI = os.path.join(BUILD, "banyan")


def runner(*args, cwd=None):
    r = subprocess.run([sys.executable, RUNNER, "--"] + [str(a) for a in args], capture_output=True, text=True,
                       cwd=cwd, timeout=600)
    return r.returncode, r.stdout + r.stderr


def snapshot(folder):
    """{file: (sha256, mtime_ns)} of every file under folder."""
    out = {}
    for p in sorted(glob.glob(os.path.join(folder, "**"), recursive=True)):
        if os.path.isfile(p):
            out[os.path.relpath(p, folder)] = (sha(p), os.stat(p).st_mtime_ns)
    return out


def refused(args, words, what):
    rc, out = runner(*args)
    check(rc == 2 and all(w in out for w in words), "%s: exit 2 naming %s (exit %d: %s)" % (what, words, rc, out[-300:]))


tmp = tempfile.mkdtemp(prefix="banyan_batch_")
try:
    out = os.path.join(tmp, "out")
    # --- refusals: exit 2 and the bad argument named, nothing written
    refused(["--preset", os.path.join(tmp, "nope.json"), "--seeds", "0:2", "--out", out], ["--preset", "nope.json"],
            "a missing preset file")
    refused(["--preset", "no_such_preset", "--seeds", "0:2", "--out", out], ["--preset", "no_such_preset"],
            "an unknown preset name")
    bad = os.path.join(tmp, "bad.json")
    with open(bad, "w") as f:
        f.write("{ not json")
    refused(["--preset", bad, "--seeds", "0:2", "--out", out], ["--preset", "JSON"], "a preset that is not JSON")
    with open(bad, "w") as f:
        json.dump({"generator": "avenue", "schema": 1, "params": {"no_such_key": 1}}, f)
    refused(["--preset", bad, "--seeds", "0:2", "--out", out], ["--preset", "no_such_key"], "a preset's unknown key")
    with open(bad, "w") as f:
        json.dump({"generator": "avenue", "schema": 1, "params": {"spacing": -3}}, f)
    refused(["--preset", bad, "--seeds", "0:2", "--out", out], ["--preset", "spacing"], "a preset value out of range")
    with open(bad, "w") as f:
        json.dump({"generator": "tube", "schema": 1, "params": {}}, f)
    refused(["--preset", bad, "--seeds", "0:2", "--out", out], ["--preset", "tube"],
            "a generator the runner does not grow")
    for seeds in ("5", "5:5", "7:3", "-1:3", "a:b", "1:2:3", "0:4294967297"):
        refused(["--preset", PRESET, "--seeds", seeds, "--out", out], ["--seeds", seeds], "--seeds %s" % seeds)
    refused(["--preset", PRESET, "--out", out], ["--seeds"], "no --seeds")
    refused(["--preset", PRESET, "--seeds", "0:2"], ["--out"], "no --out")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--render-seeds", "1:3"],
            ["--render-seeds", "Blender"], "renders asked of plain python")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--render-seeds", "3:1"], ["--render-seeds"],
            "a bad --render-seeds")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--engine", "CYCLES"], ["--engine", "CYCLES"],
            "an unknown engine")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--size", "8"], ["--size", "8"], "a tiny --size")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--threads", "-1"], ["--threads"], "--threads -1")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--texture-size", "100"], ["--texture-size"],
            "a texture size that is not a power of two")
    refused(["--preset", PRESET, "--seeds", "0:2", "--out", out, "--bogus"], ["--bogus"], "an unknown option")
    refused(["--merge-manifest", os.path.join(tmp, "nothing")], ["--merge-manifest"], "merging a folder never run")
    check(not os.path.exists(out), "refused runs write nothing")

    # --- a run: names, the CLI's bytes, records
    rc, log = runner("--preset", PRESET, "--seeds", "3:6", "--out", out, "--texture-size", 64,
                     "--render-seeds", "10:12")  # renders outside the range: nothing to render, allowed
    check(rc == 0, "run 3:6 (exit %d: %s)" % (rc, log[-400:]))
    glbs = sorted(glob.glob(os.path.join(out, "*.glb")))
    check(len(glbs) == 3, "three .glb (%s)" % glbs)
    prefix = {os.path.basename(g).rsplit("-s", 1)[0] for g in glbs}
    check(len(prefix) == 1 and prefix.pop().startswith("avenue_batch_tiny-"), "one <preset>-<hash12> prefix")
    for s in (3, 4, 5):
        mine = [g for g in glbs if g.endswith("-s%d.glb" % s)]
        cli = os.path.join(tmp, "cli%d.glb" % s)
        r = subprocess.run([CLI, "avenue", "--preset", PRESET, "--set", "seed=%d" % s, "--texture-size", "64",
                            "-o", cli], capture_output=True, text=True)
        check(r.returncode == 0 and len(mine) == 1 and sha(mine[0]) == sha(cli),
              "seed %d: the runner's .glb is the CLI's, byte for byte" % s)
        recs = glob.glob(os.path.join(out, "manifest", "*-s%d.json" % s))
        check(len(recs) == 1, "seed %d: one record" % s)
        if recs and mine:
            with open(recs[0]) as f:
                rec = json.load(f)
            files = rec["files"]
            check(rec["seed"] == s and len(files) == 1 and files[0]["name"] == os.path.basename(mine[0])
                  and files[0]["sha256"] == sha(mine[0]) and files[0]["bytes"] == os.path.getsize(mine[0]),
                  "seed %d: the record names the file, its sha256 and size" % s)
            check(rec["banyan_version"] and rec["blender_version"] is None and rec["seconds"] >= 0
                  and len(rec["params_hash"]) == 64 and rec["preset_hash"][:12] in rec["name"],
                  "seed %d: the record's versions, time and hashes" % s)
    r = subprocess.run([CLI, "avenue", "--preset", PRESET, "--set", "seed=4", "--texture-size", "64", "-o",
                        os.path.join(tmp, "t2.glb")], capture_output=True)
    # threads do not change the bytes
    out_t = os.path.join(tmp, "threads")
    rc, log = runner("--preset", PRESET, "--seeds", "4:5", "--out", out_t, "--texture-size", 64, "--threads", 2)
    t_glb = glob.glob(os.path.join(out_t, "*.glb"))
    check(rc == 0 and len(t_glb) == 1 and sha(t_glb[0]) == sha(os.path.join(tmp, "t2.glb")),
          "--threads 2: the same bytes")

    # The name follows the preset's content, not its file's path: a copy
    # elsewhere hashes the same; a changed parameter or texture size does not.
    def name_of(preset, *extra):
        o = os.path.join(tmp, "n%d" % len(os.listdir(tmp)))
        rc, log = runner("--preset", preset, "--seeds", "0:1", "--out", o, "--texture-size", 64, *extra)
        g = glob.glob(os.path.join(o, "*.glb"))
        return os.path.basename(g[0]).split("-")[-2] if rc == 0 and g else None
    base = name_of(PRESET)
    copy_dir = os.path.join(tmp, "copy")
    os.makedirs(copy_dir)
    shutil.copy(PRESET, copy_dir)
    with open(PRESET) as f:
        doc = json.load(f)
    doc["params"]["seed"] = 999  # the seed is the runner's, not part of the hash
    doc["description"] = "another text"
    with open(os.path.join(copy_dir, "avenue_batch_tiny.json"), "w") as f:
        json.dump(doc, f)
    check(base is not None and name_of(os.path.join(copy_dir, "avenue_batch_tiny.json")) == base,
          "the same parameters elsewhere: the same hash")
    doc["params"]["count"] = 1
    changed = os.path.join(copy_dir, "changed.json")
    with open(changed, "w") as f:
        json.dump(doc, f)
    h2 = name_of(changed)
    check(h2 is not None and h2 != base, "another parameter: another hash (%s, %s)" % (base, h2))
    h3 = name_of(PRESET, "--no-textures")
    check(h3 is not None and h3 != base, "other glTF options: another hash")

    # --- idempotence
    before = snapshot(out)
    rc, log = runner("--preset", PRESET, "--seeds", "3:6", "--out", out, "--texture-size", 64)
    check(rc == 0 and log.count("skipped") >= 3 and snapshot(out) == before,
          "a re-run skips every seed and touches nothing (%s)" % log[-300:])
    glb4 = [g for g in glbs if g.endswith("-s4.glb")][0]
    glb5 = [g for g in glbs if g.endswith("-s5.glb")][0]
    good4 = sha(glb4)
    with open(glb4, "r+b") as f:  # one byte flipped in the middle
        f.seek(os.path.getsize(glb4) // 2)
        b = f.read(1)
        f.seek(-1, 1)
        f.write(bytes([b[0] ^ 0xFF]))
    os.remove(glb5)
    name3 = os.path.basename([g for g in glbs if g.endswith("-s3.glb")][0])
    stale = os.path.join(out, ".%s.AbC123.tmp" % name3)  # a killed writer's leftover
    with open(stale, "wb") as f:
        f.write(b"half a file")
    stale_png = os.path.join(out, ".%s.png.4242.tmp.png" % name3[:-4])  # a killed render's leftover
    with open(stale_png, "wb") as f:
        f.write(b"half a picture")
    os.remove(os.path.join(out, "manifest", name3[:-4] + ".json"))  # seed 3 lost its record
    rc, log = runner("--preset", PRESET, "--seeds", "3:6", "--out", out, "--texture-size", 64)
    after = snapshot(out)
    check(rc == 0 and sha(glb4) == good4, "a corrupted file is made again, the same bytes")
    check(os.path.isfile(glb5) and sha(glb5) == before[os.path.relpath(glb5, out)][0],
          "a deleted file is made again, the same bytes")
    check(not os.path.exists(stale) and not os.path.exists(stale_png), "stale temporary files are removed")
    check(os.path.isfile(os.path.join(out, "manifest", name3[:-4] + ".json")), "a lost record is written again")
    check(all(after[k][0] == before[k][0] for k in before if k.endswith(".glb")), "every .glb as before")
    rc, log = runner("--preset", PRESET, "--seeds", "3:6", "--out", out, "--texture-size", 64)
    check(rc == 0 and log.count("skipped") >= 3, "then everything is skipped again")
    # A record whose params differ (another texture size) is not trusted:
    # the file is made again with the new options (the name changes too).
    rc, log = runner("--preset", PRESET, "--seeds", "3:4", "--out", out, "--texture-size", 128)
    check(rc == 0 and len(glob.glob(os.path.join(out, "*-s3.glb"))) == 2, "other options: other files beside")
    os.remove([g for g in glob.glob(os.path.join(out, "*-s3.glb")) if not g.endswith(name3)][0])
    for j in glob.glob(os.path.join(out, "manifest", "*-s3.json")):
        if os.path.basename(j) != name3[:-4] + ".json":
            os.remove(j)

    # --- the merged manifest
    # A dead runner's leftover record temporary (seed 4's; its lock is free)
    # is removed; a user's own hidden .tmp files are not the runner's.
    with open(os.path.join(out, "manifest", ".%s.json.QwErTy.tmp" % os.path.basename(glb4)[:-4]), "w") as f:
        f.write("{")
    for mine_ in (os.path.join(out, ".thesis.tmp"), os.path.join(out, "manifest", ".notes.json.tmp")):
        with open(mine_, "w") as f:
            f.write("mine")
    rc, log = runner("--merge-manifest", out, "--seeds", "3:6", "--verify")
    check(rc == 0, "merge 3:6 (exit %d: %s)" % (rc, log[-300:]))
    check(not glob.glob(os.path.join(out, "manifest", ".*-s4.json.*.tmp")),
          "the merge removes a dead runner's leftover temporary file")
    check(os.path.isfile(os.path.join(out, ".thesis.tmp")) and os.path.isfile(os.path.join(out, "manifest",
                                                                                            ".notes.json.tmp")),
          "the merge leaves a user's own .tmp files")
    os.remove(os.path.join(out, ".thesis.tmp"))
    os.remove(os.path.join(out, "manifest", ".notes.json.tmp"))
    with open(os.path.join(out, "manifest.json")) as f:
        man = json.load(f)
    check(man["count"] == 3 and [r["seed"] for r in man["records"]] == [3, 4, 5] and man["files"] == 3,
          "the manifest: 3 records in seed order, 3 files")
    check(all(f["sha256"] == sha(os.path.join(out, f["name"])) for r in man["records"] for f in r["files"]),
          "the manifest's checksums are the files'")
    rc, log = runner("--merge-manifest", out, "--seeds", "0:8")
    check(rc == 1 and "0:3" in log and "6:8" in log, "merge names the seeds without a record (%s)" % log[-300:])
    with open(glb4, "ab") as f:
        f.write(b"x")
    rc, log = runner("--merge-manifest", out, "--verify")
    check(rc == 1 and os.path.basename(glb4) in log, "merge --verify names a changed file")

    # --- USD text layers (--format usda): the library's USD writer, the
    # textures shared in the preset hash's folder; without textures the
    # bytes of the CLI's -o X.usda; a name of their own; idempotent.
    out_u = os.path.join(tmp, "usd")
    rc, log = runner("--preset", PRESET, "--seeds", "4:6", "--out", out_u, "--texture-size", 64, "--format", "usda")
    layers = sorted(glob.glob(os.path.join(out_u, "*.usda")))
    check(rc == 0 and len(layers) == 2 and not glob.glob(os.path.join(out_u, "*.glb")),
          "--format usda: two layers (exit %d: %s)" % (rc, log[-300:]))
    shared = glob.glob(os.path.join(out_u, "*-textures", "keyaki_bark-64-s1.png"))
    text = open(layers[0]).read() if layers else ""
    check(len(shared) == 1 and "@%s/keyaki_bark-64-s1.png@" % os.path.basename(os.path.dirname(shared[0])) in text,
          "the layers' textures in the shared folder, referenced by it")
    check(layers and os.path.basename(layers[0]).split("-")[-2] != base, "USD: a preset hash of its own")
    before_u = snapshot(out_u)
    rc, log = runner("--preset", PRESET, "--seeds", "4:6", "--out", out_u, "--texture-size", 64, "--format", "usda")
    check(rc == 0 and log.count("skipped") >= 2 and snapshot(out_u) == before_u, "--format usda: a re-run skips")
    rc, log = runner("--merge-manifest", out_u, "--seeds", "4:6", "--verify")
    check(rc == 0, "--format usda: the merge verifies the layers (exit %d: %s)" % (rc, log[-300:]))
    out_n = os.path.join(tmp, "usd_flat")
    rc, log = runner("--preset", PRESET, "--seeds", "4:5", "--out", out_n, "--no-textures", "--format", "usda")
    r = subprocess.run([CLI, "avenue", "--preset", PRESET, "--set", "seed=4", "--textures", "off", "-o",
                        os.path.join(tmp, "cli4.usda")], capture_output=True)
    flat = glob.glob(os.path.join(out_n, "*.usda"))
    check(rc == 0 and r.returncode == 0 and len(flat) == 1 and sha(flat[0]) == sha(os.path.join(tmp, "cli4.usda")),
          "--format usda --no-textures: the CLI's -o X.usda bytes")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

finish("test_runner")

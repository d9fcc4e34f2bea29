"""The batch runner grows every preset the CLI grows, in plain python3:
roots_column (a mesh host beside the preset), ivy_statue (a mesh host) and
segments_bushy (the demo tree) equal the CLI byte for byte; --host equals
the CLI's --host (one file named twice, at two places); the preset hash
changes with a mesh host file's bytes and with libbanyan's version;
submit.sh refuses a bad preset without calling sbatch; --shared-textures
writes each texture once per preset hash, the files pass the Khronos
validator and hold the embedded model's geometry.

    python3 tests/batch/test_grow.py BUILD_DIR
(ctest sets BANYAN_LIB to BUILD_DIR's library.)"""
import glob
import importlib.util
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

from farm_common import BUILD, HERE, RUNNER, SRC, check, finish, sha

PRESETS = os.path.join(SRC, "presets")
TINY = os.path.join(HERE, "avenue_batch_tiny.json")
SUBMIT = os.path.join(SRC, "tools", "farm", "slurm", "submit.sh")
VALIDATE = os.path.join(SRC, "tests", "gltf", "validate.mjs")
CLI = os.path.join(BUILD, "banyan")


def runner(*args, cwd=None):
    r = subprocess.run([sys.executable, RUNNER, "--"] + [str(a) for a in args], capture_output=True, text=True,
                       cwd=cwd, timeout=600)
    return r.returncode, r.stdout + r.stderr


def cli(gen, preset, seed, out, *extra):
    r = subprocess.run([CLI, gen, "--preset", preset, "--set", "seed=%d" % seed, "--texture-size", "64"]
                       + list(extra) + ["-o", out], capture_output=True, text=True, timeout=600)
    return r.returncode, r.stderr


def glb_of(folder, seed):
    g = glob.glob(os.path.join(folder, "*-s%d.glb" % seed))
    return g[0] if len(g) == 1 else None


def preset_hash(*args):
    """The hash12 --check reports for the runner arguments."""
    rc, out = runner("--check", *args)
    word = [w for w in out.split() if w.endswith("-s<seed>")]
    return word[0].rsplit("-", 2)[-2] if rc == 0 and word else "(exit %d: %s)" % (rc, out[-300:])


def glb_chunks(path):
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + n])
    rest = data[20 + n:]
    binary = rest[8:8 + struct.unpack_from("<I", rest, 0)[0]] if rest else b""
    return doc, binary


def view_bytes(doc, binary, view):
    v = doc["bufferViews"][view]
    return binary[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]


tmp = tempfile.mkdtemp(prefix="banyan_grow_")
try:
    # --- every generator: the CLI's bytes (seed 2; 64-pixel textures)
    for preset, gen in (("roots_column", "roots"), ("ivy_statue", "ivy"), ("segments_bushy", "segments")):
        out = os.path.join(tmp, preset)
        rc, log = runner("--preset", preset, "--seeds", "2:3", "--out", out, "--texture-size", 64)
        mine = glb_of(out, 2)
        ref = os.path.join(tmp, "cli_%s.glb" % preset)
        crc, cerr = cli(gen, os.path.join(PRESETS, preset + ".json"), 2, ref)
        check(rc == 0 and crc == 0 and mine is not None and sha(mine) == sha(ref),
              "%s seed 2: the runner's .glb is the CLI's, byte for byte (runner exit %d: %s; CLI exit %d: %s)"
              % (preset, rc, log[-300:], crc, cerr[-300:]))

    # --- --host: the CLI's meaning (one file named twice, moved each time)
    rock = os.path.join(PRESETS, "hosts", "rock.glb")
    hosts = ["--host", rock + "@1.5,0,0", "--host", rock + "@-1.5,0.5,0"]
    out = os.path.join(tmp, "host")
    rc, log = runner("--preset", "roots_trunk", "--seeds", "0:1", "--out", out, "--texture-size", 64, *hosts)
    mine = glb_of(out, 0)
    ref = os.path.join(tmp, "cli_host.glb")
    crc, cerr = cli("roots", os.path.join(PRESETS, "roots_trunk.json"), 0, ref, *hosts)
    check(rc == 0 and crc == 0 and mine is not None and sha(mine) == sha(ref),
          "--host twice: the runner's .glb is the CLI's (runner exit %d: %s; CLI exit %d: %s)"
          % (rc, log[-300:], crc, cerr[-300:]))
    rc, log = runner("--preset", "keyaki_young", "--seeds", "0:1", "--out", out, "--host", rock)
    check(rc == 2 and "--host" in log, "--host on keyaki is refused, as the CLI does (exit %d: %s)" % (rc, log[-200:]))

    # --- the hash: a mesh host file's bytes, --host files, libbanyan's version
    own = os.path.join(tmp, "own")
    os.makedirs(os.path.join(own, "hosts"))
    shutil.copy(os.path.join(PRESETS, "roots_column.json"), own)
    shutil.copy(os.path.join(PRESETS, "hosts", "column.glb"), os.path.join(own, "hosts"))
    p_own = os.path.join(own, "roots_column.json")
    h1 = preset_hash("--preset", p_own)
    check(len(h1) == 12 and h1 == preset_hash("--preset", p_own), "--check gives a preset hash (%s)" % h1)
    check(h1 == preset_hash("--preset", os.path.join(PRESETS, "roots_column.json")),
          "the same preset and host bytes elsewhere: the same hash")
    shutil.copy(rock, os.path.join(own, "hosts", "column.glb"))  # another valid mesh under the same name
    h2 = preset_hash("--preset", p_own)
    check(len(h2) == 12 and h2 != h1, "a mesh host file's new bytes change the hash (%s, %s)" % (h1, h2))
    column = os.path.join(PRESETS, "hosts", "column.glb")
    ha, hb = (preset_hash("--preset", "roots_trunk", "--host", f) for f in (rock, column))
    hc = preset_hash("--preset", "roots_trunk", "--host", rock + "@0,0,1")
    check(len({ha, hb, hc}) == 3 and all(len(h) == 12 for h in (ha, hb, hc)),
          "--host's file bytes and placement are in the hash (%s %s %s)" % (ha, hb, hc))

    spec = importlib.util.spec_from_file_location("batch_run_under_test", RUNNER)
    br = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(br)
    args = br.make_parser().parse_args(["--preset", TINY, "--texture-size", "64"])
    lib = br._sub("core.lib")
    real = lib.version
    job = br.Job(args)
    try:
        lib.version = lambda: real() + "+other"
        other = br.Job(args)
    finally:
        lib.version = real
    again = br.Job(args)
    check(job.version == real() and other.version == real() + "+other", "the job records libbanyan's version")
    check(job.preset_hash != other.preset_hash and job.preset_hash == again.preset_hash,
          "another libbanyan version string gives another preset hash, the same one the same hash")
    check(br._render_settings(br.make_parser().parse_args([]))["blender"] is None,
          "a render's settings carry Blender's version (None in plain python)")

    # --- submit.sh checks the preset before anything is queued
    fake = os.path.join(tmp, "fakebin")
    os.makedirs(fake)
    calls = os.path.join(tmp, "sbatch_calls")
    with open(os.path.join(fake, "sbatch"), "w") as f:
        f.write('#!/bin/sh\necho "$*" >> "%s"\necho 4242\n' % calls)
    os.chmod(os.path.join(fake, "sbatch"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ["PATH"], BANYAN_PYTHON=sys.executable)

    def submit(*args):
        r = subprocess.run(["sh", SUBMIT, "--per-task", "2", "--workers", "2", "--seeds", "0:4",
                            "--out", os.path.join(tmp, "sub_out")] + list(args), capture_output=True, text=True,
                           env=env, timeout=300)
        return r.returncode, r.stdout + r.stderr

    bad = os.path.join(tmp, "bad.json")
    with open(bad, "w") as f:
        json.dump({"generator": "roots", "schema": 1, "params": {"no_such_key": 1}}, f)
    for args, why in (([ "--preset", bad], "an unknown key"), (["--preset", "no_such_preset"], "no such preset"),
                      (["--preset", "keyaki_young", "--host", rock], "--host on keyaki"),
                      (["--preset", "roots_trunk", "--host", os.path.join(tmp, "missing.glb")], "a missing --host")):
        rc, log = submit(*args)
        check(rc == 2 and not os.path.exists(calls) and "nothing queued" in log,
              "submit.sh refuses %s without calling sbatch (exit %d: %s)" % (why, rc, log[-300:]))
    rc, log = submit("--preset", "roots_column", "--texture-size", "64")
    with open(calls) if os.path.exists(calls) else open(os.devnull) as f:
        queued = f.read().splitlines()
    check(rc == 0 and len(queued) == 2 and "4242 4242" in log and "--preset roots_column" in queued[0],
          "submit.sh queues a good preset: the array and the merge (exit %d: %s; sbatch %s)" % (rc, log[-300:], queued))

    # --- shared textures: once per preset hash, valid files, the embedded model's geometry
    out = os.path.join(tmp, "shared")
    rc, log = runner("--preset", TINY, "--seeds", "0:1", "--out", out, "--texture-size", 64, "--shared-textures")
    tex = glob.glob(os.path.join(out, "*-textures"))
    pngs = sorted(glob.glob(os.path.join(tex[0], "*.png"))) if len(tex) == 1 else []
    g0 = glb_of(out, 0)
    check(rc == 0 and len(tex) == 1 and pngs and g0 and os.path.basename(tex[0]) ==
          os.path.basename(g0).rsplit("-s", 1)[0] + "-textures",
          "--shared-textures: DIR/<preset>-<hash12>-textures/*.png (exit %d: %s; %s)" % (rc, log[-300:], pngs))
    before = {p: (os.stat(p).st_mtime_ns, os.stat(p).st_ino) for p in pngs}
    rc, log = runner("--preset", TINY, "--seeds", "1:4", "--out", out, "--texture-size", 64, "--shared-textures")
    after = {p: (os.stat(p).st_mtime_ns, os.stat(p).st_ino)
             for p in glob.glob(os.path.join(tex[0] if tex else out, "*.png"))}
    check(rc == 0 and after == before and len(glob.glob(os.path.join(out, "*.glb"))) == 4,
          "seeds 1:4 reuse the textures: no texture written again, none added (exit %d)" % rc)
    check(not glob.glob(os.path.join(out, "*", ".*.tmp")) and not glob.glob(os.path.join(out, ".*.tmp")),
          "no temporary file left")
    node = shutil.which("node")
    if node and os.path.isdir(os.path.join(SRC, "tests", "gltf", "node_modules", "gltf-validator")):
        r = subprocess.run([node, VALIDATE, "--no-warnings", out], capture_output=True, text=True, timeout=300)
        check(r.returncode == 0 and "4 passed" in r.stdout,
              "the Khronos validator passes the .glb files and their textures (%s)" % r.stdout[-400:])
    else:
        print("note: the Khronos validator is not installed (npm ci --prefix tests/gltf): not run")
    emb = os.path.join(tmp, "embedded")
    rc, log = runner("--preset", TINY, "--seeds", "2:3", "--out", emb, "--texture-size", 64)
    e2, s2 = glb_of(emb, 2), glb_of(out, 2)
    ref = os.path.join(tmp, "cli_tiny.glb")
    crc, _ = cli("avenue", TINY, 2, ref)
    check(rc == 0 and crc == 0 and e2 and sha(e2) == sha(ref), "without --shared-textures: the CLI's bytes")
    if e2 and s2:
        de, be = glb_chunks(e2)
        ds, bs = glb_chunks(s2)
        same = all(de.get(k) == ds.get(k) for k in ("nodes", "meshes", "materials", "accessors", "textures",
                                                      "samplers", "scenes"))
        same = same and all(view_bytes(de, be, a["bufferView"]) == view_bytes(ds, bs, a["bufferView"])
                            for a in de["accessors"])
        check(same, "shared textures: the same nodes, meshes, materials and accessor bytes as embedded")
        imgs_ok = len(de["images"]) == len(ds["images"]) > 0
        for ie, is_ in zip(de.get("images", []), ds.get("images", [])):
            f = os.path.join(out, is_.get("uri", "?"))
            imgs_ok = imgs_ok and "bufferView" not in is_ and os.path.isfile(f) and \
                open(f, "rb").read() == view_bytes(de, be, ie["bufferView"])
        check(imgs_ok, "each image is a relative URI to a file holding the embedded image's bytes")
        check(os.path.getsize(s2) < os.path.getsize(e2) and len(bs) < len(be),
              "the shared .glb is smaller (%d < %d bytes)" % (os.path.getsize(s2), os.path.getsize(e2)))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

finish("test_grow")

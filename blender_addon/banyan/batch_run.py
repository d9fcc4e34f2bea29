"""banyan's batch runner: one preset, a range of seeds, one output folder.

    blender -b --factory-startup --python <addon>/banyan/batch_run.py -- \\
        --preset NAME_OR_PATH --seeds A:B --out DIR [--host FILE.glb[@x,y,z] ...]
        [--render-seeds C:D] [--size 64] [--engine WORKBENCH|EEVEE] [--threads N]
        [--texture-size 1024] [--no-textures] [--shared-textures]
    python3 <addon>/banyan/batch_run.py -- ...       (glTF only: no bpy; refuses a --render-seeds
                                                      range that meets --seeds)
    python3 <addon>/banyan/batch_run.py -- --merge-manifest DIR [--seeds A:B]
    python3 <addon>/banyan/batch_run.py -- --check --preset NAME_OR_PATH [--host ...]

Seeds are half-open (A:B is A .. B-1). For each seed the preset (any
generator the CLI grows; hosts and the hash: batch_job.py), with its
`seed` replaced, is grown and written by libbanyan's glTF writer (the bytes
of `banyan <gen> --preset P --set seed=S [--host ...] -o X.glb`) as
DIR/<preset>-<hash12>-s<seed>.glb, <hash12> the preset hash (the resolved
parameters but the seed, the preset's host and segment lists, the host
files' bytes, the glTF options, libbanyan's version); seeds in --render-seeds
are also rendered (DIR/...-s<seed>.png). A record of each seed goes to
DIR/manifest/<name>.json. Every file is written to a temporary name in its
folder and renamed, so a killed task leaves no cut file; a seed whose
files exist and match its record is skipped (re-running is free), a
missing or changed file is made again. Concurrent tasks must be given
disjoint seed ranges (a scheduler's array does that): each seed's files
belong to the one task that makes it. --merge-manifest gathers the
records into DIR/manifest.json (docs/batch.md).

Exit status: 0 done, 2 bad arguments or preset, 1 a seed failed.
The package's __init__ is never run: only banyan.core (ctypes, no bpy) is
loaded, plus build_mesh for renders inside Blender.
"""
import argparse
import ctypes as C
import glob
import hashlib
import importlib
import importlib.util
import json
import os
import platform
import sys
import time

RECORD_SCHEMA = 1
MANIFEST_DIR = "manifest"
MANIFEST_FILE = "manifest.json"
_PKG = "_banyan_batch"  # the add-on package loaded under a private name (its __init__ not run)


def _here():
    return os.path.dirname(os.path.abspath(__file__))


def _package():
    """The add-on folder as package _PKG without running its __init__
    (which registers Blender classes): submodules import as usual."""
    mod = sys.modules.get(_PKG)
    if mod is None:
        here = _here()
        spec = importlib.util.spec_from_file_location(_PKG, os.path.join(here, "__init__.py"),
                                                      submodule_search_locations=[here])
        mod = importlib.util.module_from_spec(spec)
        sys.modules[_PKG] = mod
    return mod


def _sub(name):
    _package()
    return importlib.import_module(_PKG + "." + name)


_job = _sub("batch_job")  # the preset, its hosts and hash, the writer's options (batch_job.py)
UsageError = _job.UsageError
Job = _job.Job
find_preset = _job.find_preset
_sha256, _file_sha256, _canonical = _job._sha256, _job._file_sha256, _job._canonical


def _in_blender():
    try:
        import bpy  # noqa: F401
    except ImportError:
        return False
    return True


# ---------------------------------------------------------------- arguments
def parse_range(text, what):
    """'A:B' (half-open, 0 <= A < B <= 2^32) -> (A, B); UsageError naming `what`."""
    parts = str(text).split(":")
    try:
        if len(parts) != 2:
            raise ValueError
        a, b = int(parts[0]), int(parts[1])
    except ValueError:
        raise UsageError("%s '%s' must look like A:B (half-open: seeds A .. B-1, whole numbers)" % (what, text))
    if not (0 <= a < b <= 2 ** 32):
        raise UsageError("%s '%s' must have 0 <= A < B <= 4294967296 (half-open: seeds A .. B-1)" % (what, text))
    return a, b


def _argv(argv):
    if argv is None:
        argv = sys.argv[1:]
        if "--" in sys.argv:
            argv = sys.argv[sys.argv.index("--") + 1:]
    elif "--" in argv:
        argv = argv[argv.index("--") + 1:]
    # "--seeds -1:3" would read as an option: keep such values with their option.
    out, it = [], iter(argv)
    for a in it:
        if a in _VALUE_OPTIONS:
            nxt = next(it, None)
            out.append(a if nxt is None else "%s=%s" % (a, nxt))
        else:
            out.append(a)
    return out


_VALUE_OPTIONS = ("--seeds", "--render-seeds", "--size", "--threads", "--texture-size", "--host")


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def make_parser():
    p = _Parser(prog="batch_run.py", description="banyan batch runner (docs/batch.md)")
    p.add_argument("--preset", help="a preset file (.json) or the name of a shipped preset")
    p.add_argument("--host", action="append", metavar="FILE.glb[@x,y,z]",
                   help="a glTF binary mesh as a host (roots, ivy; repeatable), moved by x,y,z metres: the CLI's --host")
    p.add_argument("--seeds", help="A:B, half-open: seeds A .. B-1")
    p.add_argument("--out", help="output folder (created)")
    p.add_argument("--render-seeds", help="C:D, half-open: the seeds (within --seeds) also rendered (Blender only)")
    p.add_argument("--size", type=int, default=64, help="render size in pixels, square (16 .. 4096, default 64)")
    p.add_argument("--engine", default="WORKBENCH", help="WORKBENCH (default) or EEVEE")
    p.add_argument("--threads", type=int, default=1, help="generator threads (0: all cores; default 1)")
    p.add_argument("--texture-size", type=int, default=1024, help="glTF texture size (as the CLI's; default 1024)")
    p.add_argument("--no-textures", action="store_true", help="glTF without textures (as the CLI's --textures off)")
    p.add_argument("--shared-textures", action="store_true",
                   help="textures once per preset hash in DIR/<preset>-<hash12>-textures/, referenced by the .glb files")
    p.add_argument("--check", action="store_true",
                   help="load the preset, hosts and options, then exit 0 (ready) or 2 (the reason); writes nothing")
    p.add_argument("--merge-manifest", metavar="DIR", help="merge DIR/manifest/*.json into DIR/manifest.json")
    p.add_argument("--verify", action="store_true", help="with --merge-manifest: re-hash every file")
    p.add_argument("--quiet", action="store_true")
    return p


# ------------------------------------------------------------------ records
def _write_atomic(path, data):
    _sub("core.atomic_file").write_atomic(path, data)


def _remove_stale_temps(folder, name):
    """Temporary files a killed task left for `name` (".<name>.XXXXXX.tmp",
    the library's and atomic_file's pattern; ".<name>.<pid>.tmp.png", a
    render's). Only the task that owns a seed writes its files, so any
    such file is a leftover."""
    base = os.path.join(glob.escape(folder), "." + glob.escape(name))
    for t in glob.glob(base + ".*.tmp") + glob.glob(base + ".*.tmp.png"):
        try:
            os.unlink(t)
        except OSError:
            pass


def _file_entry(path):
    return {"name": os.path.basename(path), "sha256": _file_sha256(path), "bytes": os.path.getsize(path)}


def _file_ok(folder, entry):
    path = os.path.join(folder, entry["name"])
    try:
        return os.path.getsize(path) == entry["bytes"] and _file_sha256(path) == entry["sha256"]
    except (OSError, KeyError, TypeError):
        return False


def read_record(path):
    try:
        with open(path, "rb") as f:
            rec = json.loads(f.read())
        return rec if isinstance(rec, dict) and rec.get("schema") == RECORD_SCHEMA else None
    except (OSError, ValueError):
        return None


def _blender_version():
    try:
        import bpy
        return bpy.app.version_string
    except ImportError:
        return None


def _render_settings(args):
    """What a render depends on besides the plant; Blender's version too, so
    a render made by another Blender is made again (docs/batch.md)."""
    return {"size": args.size, "engine": args.engine, "blender": _blender_version()}


def run_seed(job, args, seed, render, log):
    """Makes what is missing of one seed; returns 'skipped' or 'made'."""
    name = job.name(seed)
    out = args.out
    mdir = os.path.join(out, MANIFEST_DIR)
    rec_path = os.path.join(mdir, name + ".json")
    params = job.seed_params(seed)
    params_hash = _sha256(_canonical({"generator": job.generator, "params": params.as_dict(), "gltf": job.gltf}))
    old = read_record(rec_path)
    glb_name, png_name = name + ".glb", name + ".png"
    if old is not None and old.get("params_hash") != params_hash:
        old = None
    files = {f.get("name"): f for f in (old or {}).get("files", []) if isinstance(f, dict)}
    glb_ok = glb_name in files and _file_ok(out, files[glb_name])
    png_ok = (not render) or (png_name in files and _file_ok(out, files[png_name])
                              and old.get("render") == _render_settings(args))
    if glb_ok and png_ok:
        log("seed %d: %s up to date, skipped" % (seed, name))
        return "skipped"
    t0 = time.perf_counter()
    for n in (glb_name, png_name, name + ".json"):
        _remove_stale_temps(out if n != name + ".json" else mdir, n)
    glb_path = os.path.join(out, glb_name)
    made = []
    M = job.M
    with M.capture():
        d = job.grow(params)
        if not glb_ok:
            job.write_glb(d, glb_path)
            made.append("glb")
        if render and not png_ok:
            from_blender = _sub("batch_render")
            tmp = os.path.join(out, ".%s.%d.tmp.png" % (png_name, os.getpid()))
            try:
                from_blender.render(d, tmp, size=args.size, engine=args.engine)
                os.replace(tmp, os.path.join(out, png_name))
            finally:
                if os.path.exists(tmp):
                    os.unlink(tmp)
            made.append("png")
    seconds = time.perf_counter() - t0
    entries = [_file_entry(glb_path)]
    if render:
        entries.append(_file_entry(os.path.join(out, png_name)))
    elif png_name in files and _file_ok(out, files[png_name]):
        entries.append(files[png_name])  # a render from an earlier run stays listed
    rec = {
        "schema": RECORD_SCHEMA, "name": name, "seed": seed, "preset": job.preset_name,
        "preset_file": job.preset_path, "generator": job.generator, "preset_hash": job.preset_hash,
        "params_hash": params_hash, "gltf": job.gltf, "files": entries, "seconds": round(seconds, 4),
        "made": made, "banyan_version": job.version, "blender_version": _blender_version(),
        "host": platform.node(),
    }
    if render or (old and png_name in files and any(e["name"] == png_name for e in entries)):
        rec["render"] = _render_settings(args) if render else old.get("render")
    _write_atomic(rec_path, json.dumps(rec, indent=1, sort_keys=True) + "\n")
    log("seed %d: %s made %s in %.2f s" % (seed, name, "+".join(made) or "record", seconds))
    return "made"


def run(args, log):
    if not args.preset or not args.seeds or not args.out:
        raise UsageError("--preset, --seeds and --out are required (or --merge-manifest DIR)")
    a, b = parse_range(args.seeds, "--seeds")
    renders = range(0)
    if args.render_seeds:
        c, d = parse_range(args.render_seeds, "--render-seeds")
        renders = range(max(a, c), min(b, d))  # the seeds of this run to render (may be none)
        if renders and not _in_blender():
            raise UsageError("--render-seeds %s: seeds %d:%d need Blender: run the runner with blender -b "
                             "--python (plain python3 writes glTF only)" % (args.render_seeds, renders.start,
                                                                          renders.stop))
    args.engine = args.engine.upper()
    if args.engine not in ("WORKBENCH", "EEVEE"):
        raise UsageError("--engine '%s' must be WORKBENCH or EEVEE" % args.engine)
    if not (16 <= args.size <= 4096):
        raise UsageError("--size %d must be within [16, 4096] pixels" % args.size)
    job = Job(args)
    os.makedirs(os.path.join(args.out, MANIFEST_DIR), exist_ok=True)
    counts = {"made": 0, "skipped": 0, "failed": 0}
    t0 = time.perf_counter()
    for seed in range(a, b):
        try:
            counts[run_seed(job, args, seed, seed in renders, log)] += 1
        except (job.errors.BanyanError, OSError) as e:
            counts["failed"] += 1
            log("seed %d: FAILED: %s" % (seed, getattr(e, "message", None) or e))
    log("batch %s seeds %d:%d: %d made, %d skipped, %d failed in %.2f s"
        % (job.preset_name, a, b, counts["made"], counts["skipped"], counts["failed"], time.perf_counter() - t0))
    return 1 if counts["failed"] else 0


# ------------------------------------------------------------------- merging
def merge(args, log):
    """DIR/manifest/*.json -> DIR/manifest.json (records sorted by preset
    hash and seed). With --seeds A:B, every seed of the range must have a
    record (else exit 1, naming the missing ones); --verify re-hashes
    every listed file. Leftover temporary files are reported and removed."""
    out = args.merge_manifest
    mdir = os.path.join(out, MANIFEST_DIR)
    if not os.path.isdir(mdir):
        raise UsageError("--merge-manifest %s: no %s folder (nothing was run there)" % (out, MANIFEST_DIR))
    recs, bad = [], []
    for path in sorted(glob.glob(os.path.join(glob.escape(mdir), "*.json"))):
        rec = read_record(path)
        if rec is None:
            bad.append("%s: unreadable record" % os.path.basename(path))
            continue
        if args.verify:
            for f in rec.get("files", []):
                if not _file_ok(out, f):
                    bad.append("%s: %s is missing or differs from its record" % (rec["name"], f.get("name")))
        recs.append(rec)
    recs.sort(key=lambda r: (r.get("preset"), r.get("preset_hash"), r.get("seed")))
    missing = []
    if args.seeds:
        a, b = parse_range(args.seeds, "--seeds")
        have = {r.get("seed") for r in recs}
        missing = [s for s in range(a, b) if s not in have]
        if missing:
            bad.append("seeds without a record: %s" % _ranges(missing))
    for folder in (out, mdir):
        for t in glob.glob(os.path.join(glob.escape(folder), ".*.tmp")) + glob.glob(
                os.path.join(glob.escape(folder), ".*.tmp.png")):
            log("removing a leftover temporary file %s" % t)
            os.unlink(t)
    doc = {"schema": RECORD_SCHEMA, "count": len(recs),
           "files": sum(len(r.get("files", [])) for r in recs),
           "bytes": sum(f.get("bytes", 0) for r in recs for f in r.get("files", [])),
           "seconds": round(sum(r.get("seconds", 0) for r in recs), 4), "records": recs}
    _write_atomic(os.path.join(out, MANIFEST_FILE), json.dumps(doc, indent=1, sort_keys=True) + "\n")
    log("manifest %s: %d records, %d files" % (os.path.join(out, MANIFEST_FILE), doc["count"], doc["files"]))
    for b_ in bad:
        log("manifest: %s" % b_)
    return 1 if bad else 0


def _ranges(seeds):
    out, start, prev = [], None, None
    for s in seeds:
        if start is None:
            start = prev = s
        elif s == prev + 1:
            prev = s
        else:
            out.append("%d:%d" % (start, prev + 1))
            start = prev = s
    if start is not None:
        out.append("%d:%d" % (start, prev + 1))
    return ", ".join(out)


def main(argv=None):
    try:
        argv = _argv(argv)
        if "--check" in argv:
            argv = _job.strip_submit_options(argv)  # submit.sh passes its whole command line
        args = make_parser().parse_args(argv)

        def log(msg):
            if not args.quiet:
                print("batch_run: " + msg, flush=True)
        if args.merge_manifest:
            return merge(args, log)
        if args.check:
            return _job.check(args, log)
        return run(args, log)
    except UsageError as e:
        print("batch_run: error: %s" % e, file=sys.stderr, flush=True)
        return 2


if __name__ == "__main__":
    code = main()
    if _in_blender():
        # blender -b --python: a non-zero status needs an explicit exit
        # (--python-exit-code covers exceptions only).
        sys.stdout.flush()
        os._exit(code) if code else None
    else:
        sys.exit(code)

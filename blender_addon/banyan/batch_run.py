"""banyan's batch runner: one preset, a range of seeds, one output folder.

    blender -b --factory-startup --python <addon>/banyan/batch_run.py -- \\
        --preset NAME_OR_PATH --seeds A:B --out DIR [--host FILE.glb[@x,y,z] ...]
        [--render-seeds C:D] [--size 64] [--engine WORKBENCH|EEVEE] [--threads N]
        [--texture-size 1024] [--no-textures] [--shared-textures] [--format glb|usda] [--no-parent-watch]
    python3 <addon>/banyan/batch_run.py -- ...       (glTF only: no bpy; refuses a --render-seeds
                                                      range that meets --seeds)
    python3 <addon>/banyan/batch_run.py -- --merge-manifest DIR [--seeds A:B] [--verify]
        [--hash HASH12 | --preset P [--host ...] [--texture-size T] [--no-textures] [--shared-textures]]
    python3 <addon>/banyan/batch_run.py -- --check --preset NAME_OR_PATH [--host ...]

Seeds are half-open (A:B is A .. B-1). For each seed the preset (any
generator the CLI grows; hosts and the hash: batch_job.py), with its
`seed` replaced, is grown and written by libbanyan's glTF writer (the bytes
of `banyan <gen> --preset P --set seed=S [--host ...] -o X.glb`) as
DIR/<preset>-<hash12>-s<seed>.glb, <hash12> the preset hash (the resolved
parameters but the seed, the preset's host and segment lists, the host
files' bytes, the glTF options, libbanyan's version); with --format usda the
same nodes are written as a USD text layer by libbanyan's USD writer
(DIR/...-s<seed>.usda; docs/usd.md), its textures shared as with
--shared-textures; seeds in --render-seeds
are also rendered (DIR/...-s<seed>.png). A record of each seed goes to
DIR/manifest/<name>.json. A seed is made only under its lock
(DIR/manifest/.<name>.lock, an fcntl record lock), its files are written
into a private temporary folder and renamed into place (never through a
symlink), so a killed task leaves no cut file and overlapping runners
wait for each other; a seed whose files exist and match its record is
skipped (re-running is free), a missing or changed file is made again.
--merge-manifest gathers the records into DIR/manifest.json
(docs/batch.md; batch_files.py, batch_merge.py).

Exit status: 0 done, 2 bad arguments or preset, 1 a seed failed (or a
merge check), 3 the parent process died (the runner stops).
The package's __init__ is never run: only banyan.core (ctypes, no bpy) is
loaded, plus build_mesh for renders inside Blender.
"""
import argparse
import ctypes as C
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
def parse_range(text, what, cap=None):
    """'A:B' (half-open, 0 <= A < B <= 2^32, ASCII decimal digits; at most
    cap seeds when given) -> (A, B); UsageError naming `what`."""
    return _sub("batch_merge").parse_range(text, what, cap)


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


_VALUE_OPTIONS = ("--seeds", "--render-seeds", "--size", "--threads", "--texture-size", "--host", "--format")


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
    dec = _sub("batch_merge").decimal_int
    p.add_argument("--size", type=dec, default=64, help="render size in pixels, square (16 .. 4096, default 64)")
    p.add_argument("--engine", default="WORKBENCH", help="WORKBENCH (default) or EEVEE")
    p.add_argument("--threads", type=dec, default=1, help="generator threads (0: all cores; default 1)")
    p.add_argument("--texture-size", type=dec, default=1024, help="glTF texture size (as the CLI's; default 1024)")
    p.add_argument("--no-textures", action="store_true", help="glTF without textures (as the CLI's --textures off)")
    p.add_argument("--shared-textures", action="store_true",
                   help="textures once per preset hash in DIR/<preset>-<hash12>-textures/, referenced by the .glb files")
    p.add_argument("--format", default="glb", choices=("glb", "usda"),
                   help="glb (default: the CLI's -o X.glb) or usda (a USD text layer, docs/usd.md; its textures "
                        "shared as with --shared-textures)")
    p.add_argument("--check", action="store_true",
                   help="load the preset, hosts and options, then exit 0 (ready) or 2 (the reason); writes nothing")
    p.add_argument("--merge-manifest", metavar="DIR", help="merge DIR/manifest/*.json into DIR/manifest.json")
    p.add_argument("--verify", action="store_true", help="with --merge-manifest: re-hash every file")
    p.add_argument("--hash", help="with --merge-manifest: the preset hash (its first 12 or more hex digits) whose "
                                  "seeds --seeds must cover (--preset with the run's options gives it too)")
    p.add_argument("--no-parent-watch", action="store_true",
                   help="keep running when the parent process dies (default: stop with exit 3, an orphan)")
    p.add_argument("--quiet", action="store_true")
    return p


# ------------------------------------------------------------------ records
def _write_atomic(path, data):
    """Written beside path under a fresh name and renamed over it: a
    symlink at path is replaced, never written through."""
    _sub("batch_files").write_atomic(path, data)


def _remove_stale_temps(folder, name):
    """Leftover temporaries of seed `name` in folder (a dead runner's: call
    only while holding the seed's lock). Other files are never removed."""
    return _sub("batch_files").remove_stale_temps(folder, [name])


def _file_entry(path):
    st = os.lstat(path)
    return {"name": os.path.basename(path), "sha256": _sub("batch_merge").file_sha256(path), "bytes": st.st_size}


def _file_ok(folder, entry):
    return _sub("batch_merge").file_ok(folder, entry)


def read_record(path, log=None):
    """The record at path, or None when it is missing or malformed (then
    named through log)."""
    rec, why = _sub("batch_merge").load_record(path)
    if why and log and os.path.lexists(path):
        log("record %s is malformed (%s): the seed is made again" % (path, why))
    return rec


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
    """Makes what is missing of one seed under its lock; returns 'skipped'
    or 'made'. A seed locked by another live runner is waited for, then
    found up to date (or finished)."""
    name = job.name(seed)
    lock = _sub("batch_files").SeedLock(os.path.join(args.out, MANIFEST_DIR), name)
    lock.acquire(wait=True, on_wait=lambda why: log("seed %d: %s is locked (%s): waiting" % (seed, name, why)))
    try:
        return _run_seed_locked(job, args, seed, render, log, name)
    finally:
        lock.release()


def _place_textures(job, tmpdir, out, bf):
    """--shared-textures: the writer put the textures beside the .glb, in
    the private folder; each goes into DIR/<image_dir>/ unless a runner
    put it there already (the same bytes: a function of the preset hash).
    A symlink planted at that folder is refused."""
    if not job.image_dir:
        return
    src = os.path.join(tmpdir, job.image_dir)
    dst = os.path.join(out, job.image_dir)
    if os.path.islink(dst):
        raise OSError("%s is a symbolic link: the shared textures are not written through it" % dst)
    os.makedirs(dst, exist_ok=True)
    for f in sorted(os.listdir(src)) if os.path.isdir(src) else ():
        target = os.path.join(dst, f)
        if not os.path.lexists(target):
            bf.place(os.path.join(src, f), target)


def _run_seed_locked(job, args, seed, render, log, name):
    bf = _sub("batch_files")
    out = args.out
    mdir = os.path.join(out, MANIFEST_DIR)
    rec_path = os.path.join(mdir, name + ".json")
    params = job.seed_params(seed)
    params_hash = _sha256(_canonical({"generator": job.generator, "params": params.as_dict(), "gltf": job.gltf}))
    old = read_record(rec_path, log)
    glb_name, png_name = name + job.ext, name + ".png"
    if old is not None and old.get("params_hash") != params_hash:
        old = None
    files = {f["name"]: f for f in (old or {}).get("files", [])}
    glb_ok = glb_name in files and _file_ok(out, files[glb_name])
    png_ok = (not render) or (png_name in files and _file_ok(out, files[png_name])
                              and old.get("render") == _render_settings(args))
    if glb_ok and png_ok:
        log("seed %d: %s up to date, skipped" % (seed, name))
        return "skipped"
    t0 = time.perf_counter()
    for folder in (out, mdir):
        _remove_stale_temps(folder, name)  # a dead runner's: we hold the lock
    tmpdir = bf.private_folder(out, name)
    try:
        made = []
        glb_path = os.path.join(out, glb_name)
        glb_src = glb_path
        M = job.M
        with M.capture():
            d = job.grow(params)
            if not glb_ok:
                glb_src = os.path.join(tmpdir, glb_name)
                job.write(d, glb_src)
                _place_textures(job, tmpdir, out, bf)
                made.append(job.format)
            png_src = None
            if render and not png_ok:
                png_src = os.path.join(tmpdir, png_name)
                _sub("batch_render").render(d, png_src, size=args.size, engine=args.engine)
                made.append("png")
        seconds = time.perf_counter() - t0
        entries = [_file_entry(glb_src)]
        if render:
            entries.append(_file_entry(png_src or os.path.join(out, png_name)))
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
        rec_src = os.path.join(tmpdir, name + ".json")
        bf.write_new(rec_src, json.dumps(rec, indent=1, sort_keys=True) + "\n")
        # Into place, the record last: rename replaces a symlink at the
        # name, never its target.
        if glb_src != glb_path:
            bf.place(glb_src, glb_path)
        if png_src:
            bf.place(png_src, os.path.join(out, png_name))
        bf.place(rec_src, rec_path)
    finally:
        import shutil
        shutil.rmtree(tmpdir, ignore_errors=True)
    log("seed %d: %s made %s in %.2f s" % (seed, name, "+".join(made) or "record", seconds))
    return "made"


def run(args, log):
    if not args.preset or not args.seeds or not args.out:
        raise UsageError("--preset, --seeds and --out are required (or --merge-manifest DIR)")
    bm = _sub("batch_merge")
    a, b = parse_range(args.seeds, "--seeds", bm.SEEDS_MAX)
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
    bm.check_out_folder(args.out)
    bm.check_preset_file(find_preset(args.preset))  # size cap, JSON, "hosts" before Job reads it
    job = Job(args)
    try:
        os.makedirs(os.path.join(args.out, MANIFEST_DIR), exist_ok=True)
    except OSError as e:
        raise UsageError("--out %s: cannot make the folder: %s" % (args.out, e.strerror or e))
    bm.check_out_folder(args.out)
    if not args.no_parent_watch:
        _sub("batch_files").ParentWatch().start()  # an orphaned runner stops (exit 3)
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
    """DIR/manifest/*.json -> DIR/manifest.json (batch_merge.merge): with
    --seeds A:B every seed of the range must have a record of one preset
    hash (--hash, or --preset with the run's options, or the only one
    there); --verify re-hashes every listed file. Malformed records and
    failed checks are named and leave manifest.json as it was (exit 1)."""
    bm = _sub("batch_merge")
    preset_hash = None
    if args.preset:
        bm.check_preset_file(find_preset(args.preset))
        preset_hash = Job(args).preset_hash
    return bm.merge(args, log, preset_hash)


def _ranges(seeds):
    return _sub("batch_merge").ranges(seeds)


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
    except (UsageError, _sub("batch_merge").UsageError) as e:
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

"""The batch runner's argument checks, record checks and manifest merge
(docs/batch.md, "The manifest" and "Limits").

- Seeds and whole-number options are ASCII decimal digits only
  (`^[0-9]+$`): leading zeros are decimal (010 is ten), `1_0` and
  non-ASCII digits (which Python's int() accepts) are refused.
- A run or a merge covers at most SEEDS_MAX seeds; the range is checked
  before anything is allocated per seed.
- A preset file over PRESET_MAX_BYTES (the library's
  BANYAN_PRESET_MAX_BYTES, csrc/include/banyan.h) is refused before it is
  read; "hosts" must be a non-empty list when present.
- A record is trusted only when every field the runner and the merge use
  has its type and its name agrees with its contents; any other record is
  reported by file name and field.
- The merge checks completeness per preset hash and writes manifest.json
  only when every check passed.

Python 3.11 stdlib only; loaded by batch_run.py as a submodule of the
add-on package (its __init__ is not run).
"""
import json
import os
import re
import stat

from . import batch_files as bf

RECORD_SCHEMA = 1
MANIFEST_DIR = "manifest"
MANIFEST_FILE = "manifest.json"
SEED_END_MAX = 2 ** 32
SEEDS_MAX = 10 ** 7
PRESET_MAX_BYTES = 4 << 20
RECORD_MAX_BYTES = 1 << 20

_DECIMAL = re.compile(r"[0-9]+\Z")
_SIGNED = re.compile(r"-?[0-9]+\Z")
_HEX64 = re.compile(r"[0-9a-f]{64}\Z")
_HASH_ARG = re.compile(r"[0-9a-f]{12,64}\Z")


class UsageError(Exception):
    """Bad arguments or preset: exit status 2 with the message."""


# ---------------------------------------------------------------- arguments
def decimal_int(text):
    """argparse type: a whole number in ASCII decimal digits (an optional
    leading '-'); '010' is ten. '1_0', '+5', ' 5' and non-ASCII digits are
    refused."""
    import argparse
    s = str(text)
    if not _SIGNED.match(s):
        raise argparse.ArgumentTypeError("'%s' is not a whole number in decimal digits 0-9" % s)
    return int(s, 10)


def parse_range(text, what, cap=None):
    """'A:B' (half-open, 0 <= A < B <= 2^32, decimal digits 0-9 only) ->
    (A, B); with cap, at most cap seeds. UsageError naming `what`."""
    text = str(text)
    parts = text.split(":")
    if len(parts) != 2 or not all(_DECIMAL.match(p) for p in parts) or max(len(p) for p in parts) > 40:
        raise UsageError("%s '%s' must look like A:B (half-open: seeds A .. B-1, whole numbers in decimal "
                         "digits 0-9)" % (what, text))
    a, b = int(parts[0], 10), int(parts[1], 10)
    if not (0 <= a < b <= SEED_END_MAX):
        raise UsageError("%s '%s' must have 0 <= A < B <= %d (half-open: seeds A .. B-1)" % (what, text, SEED_END_MAX))
    if cap is not None and b - a > cap:
        raise UsageError("%s '%s' holds %d seeds, more than the %d a run or merge takes: split it into ranges of "
                         "at most %d seeds" % (what, text, b - a, cap, cap))
    return a, b


def check_out_folder(out, what="--out"):
    """An output folder that is a folder (or does not exist yet), with no
    symlink or file as its manifest/ folder."""
    try:
        st = os.stat(out)
    except FileNotFoundError:
        return
    except OSError as e:
        raise UsageError("%s %s: %s" % (what, out, e.strerror))
    if not stat.S_ISDIR(st.st_mode):
        raise UsageError("%s %s is a file, not a folder" % (what, out))
    m = os.path.join(out, MANIFEST_DIR)
    try:
        mst = os.lstat(m)
    except FileNotFoundError:
        return
    if not stat.S_ISDIR(mst.st_mode):
        raise UsageError("%s %s: %s is %s, not a folder: refused" % (
            what, out, m, "a symlink" if stat.S_ISLNK(mst.st_mode) else "a file"))


def check_preset_file(path):
    """Refuses a preset over PRESET_MAX_BYTES before reading it, one that
    is not JSON, and a "hosts" that is not a non-empty list."""
    try:
        with open(path, "rb") as f:
            size = os.fstat(f.fileno()).st_size
            if size > PRESET_MAX_BYTES:
                raise UsageError("--preset %s is %d bytes, more than the %d-byte limit for presets (as the CLI's "
                                 "BANYAN_PRESET_MAX_BYTES)" % (path, size, PRESET_MAX_BYTES))
            text = f.read(PRESET_MAX_BYTES + 1)
    except OSError as e:
        raise UsageError("--preset %s: %s" % (path, e.strerror or e))
    if len(text) > PRESET_MAX_BYTES:
        raise UsageError("--preset %s is more than the %d-byte limit for presets" % (path, PRESET_MAX_BYTES))
    try:
        doc = json.loads(text)
    except ValueError as e:
        raise UsageError("--preset %s: not JSON: %s" % (path, e))
    if isinstance(doc, dict) and "hosts" in doc:
        h = doc["hosts"]
        if not isinstance(h, list) or not h:
            raise UsageError("--preset %s: \"hosts\" must be a non-empty list of hosts (or left out), got %s"
                             % (path, json.dumps(h)[:60]))


# ------------------------------------------------------------------ records
def _is_int(v):
    return isinstance(v, int) and not isinstance(v, bool)


def record_problem(rec, stem):
    """None for a record the runner and merge can trust, else the first
    bad field as 'field X: why'. stem: the record's file name without .json."""
    if not isinstance(rec, dict):
        return "not a JSON object"
    if rec.get("schema") != RECORD_SCHEMA:
        return "field 'schema': %s, expected %d" % (json.dumps(rec.get("schema"))[:40], RECORD_SCHEMA)
    for key in ("name", "preset"):
        if not isinstance(rec.get(key), str) or not rec[key]:
            return "field '%s': %s is not a non-empty string" % (key, json.dumps(rec.get(key))[:40])
    seed = rec.get("seed")
    if not _is_int(seed) or not 0 <= seed < SEED_END_MAX:
        return "field 'seed': %s is not a whole number in [0, %d)" % (json.dumps(seed)[:40], SEED_END_MAX)
    for key in ("preset_hash", "params_hash"):
        if not isinstance(rec.get(key), str) or not _HEX64.match(rec[key]):
            return "field '%s': %s is not 64 hex digits" % (key, json.dumps(rec.get(key))[:40])
    expect = "%s-%s-s%d" % (rec["preset"], rec["preset_hash"][:12], seed)
    if rec["name"] != expect or stem != expect:
        return "field 'name': %s does not match its preset, hash and seed (%s) and file name" % (
            json.dumps(rec["name"])[:80], expect)
    files = rec.get("files")
    if not isinstance(files, list) or not files:
        return "field 'files': %s is not a list of {name, sha256, bytes}" % json.dumps(files)[:40]
    for i, f in enumerate(files):
        if not isinstance(f, dict):
            return "field 'files[%d]': %s is not an object" % (i, json.dumps(f)[:40])
        if f.get("name") not in (expect + ".glb", expect + ".usda", expect + ".png"):
            return "field 'files[%d].name': %s is not %s.glb, .usda or .png" % (i, json.dumps(f.get("name"))[:80],
                                                                                expect)
        if not isinstance(f.get("sha256"), str) or not _HEX64.match(f["sha256"]):
            return "field 'files[%d].sha256': not 64 hex digits" % i
        if not _is_int(f.get("bytes")) or f["bytes"] < 0:
            return "field 'files[%d].bytes': %s is not a whole number >= 0" % (i, json.dumps(f.get("bytes"))[:40])
    sec = rec.get("seconds", 0)
    if not isinstance(sec, (int, float)) or isinstance(sec, bool) or not sec >= 0:
        return "field 'seconds': %s is not a number >= 0" % json.dumps(sec)[:40]
    return None


def load_record(path):
    """(record, None) or (None, why) for DIR/manifest/<stem>.json; never
    follows a symlink, never reads more than RECORD_MAX_BYTES."""
    f = bf.open_regular(path)
    if f is None:
        return None, "missing, a symlink or not a regular file"
    with f:
        data = f.read(RECORD_MAX_BYTES + 1)
    if len(data) > RECORD_MAX_BYTES:
        return None, "more than %d bytes" % RECORD_MAX_BYTES
    try:
        rec = json.loads(data)
    except ValueError as e:
        return None, "not JSON (%s)" % e
    stem = os.path.basename(path)[:-len(".json")] if path.endswith(".json") else os.path.basename(path)
    why = record_problem(rec, stem)
    return (None, why) if why else (rec, None)


def file_sha256(path):
    import hashlib
    f = bf.open_regular(path)
    if f is None:
        raise FileNotFoundError(path)
    h = hashlib.sha256()
    with f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def file_ok(folder, entry):
    """The file of a record's entry is a regular file (not a symlink) with
    its size and SHA-256."""
    path = os.path.join(folder, entry["name"])
    try:
        st = os.lstat(path)
        return stat.S_ISREG(st.st_mode) and st.st_size == entry["bytes"] and file_sha256(path) == entry["sha256"]
    except (OSError, KeyError, TypeError):
        return False


def ranges(seeds):
    """Sorted whole numbers -> 'a:b, c:d' (half-open runs)."""
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


def missing_ranges(have, a, b):
    """The runs of [a, b) not in the set `have`, as 'a:b' strings, in
    O(len(have)) (never a list of every seed)."""
    out, at = [], a
    for s in sorted(x for x in have if a <= x < b):
        if s > at:
            out.append("%d:%d" % (at, s))
        at = s + 1
    if at < b:
        out.append("%d:%d" % (at, b))
    return out


_TEMP = re.compile(r"^\.(?P<name>.+-[0-9a-f]{12}-s[0-9]+)\.(?:(?:glb|usda|png|json)\.[A-Za-z0-9]{6}\.tmp"
                   r"|png\.[0-9]+\.tmp\.png|[A-Za-z0-9_-]+\.[0-9]+\.[a-z0-9_]+\.tmp)$")


def _leftovers(out, mdir, log):
    """Removes the runner's leftover temporaries of seeds whose lock is free
    (their writer is dead); reports those of seeds a live runner holds.
    Files of other names are never touched."""
    seeds = set()
    for folder in (out, mdir):
        try:
            for e in os.listdir(folder):
                m = _TEMP.match(e)
                if m:
                    seeds.add(m.group("name"))
        except OSError:
            pass
    for name in sorted(seeds):
        lock = bf.SeedLock(mdir, name)
        try:
            lock.acquire(wait=False)
        except bf.Busy as e:
            log("leftover temporary files of %s kept: the seed is being made (%s)" % (name, e))
            continue
        except OSError as e:
            log("leftover temporary files of %s kept: %s" % (name, e))
            continue
        try:
            for folder in (out, mdir):
                for t in bf.remove_stale_temps(folder, [name]):
                    log("removed a dead runner's temporary file %s" % os.path.join(folder, t))
        finally:
            lock.release()


# ------------------------------------------------------------------- merging
def merge(args, log, preset_hash=None):
    """DIR/manifest/*.json -> DIR/manifest.json. Exit status 0, or 1 with
    every problem named (manifest.json then left as it was)."""
    out = args.merge_manifest
    if not os.path.isdir(out):
        if os.path.exists(out):
            raise UsageError("--merge-manifest %s is a file, not a folder" % out)
        raise UsageError("--merge-manifest %s: no such folder (nothing was run there)" % out)
    check_out_folder(out, "--merge-manifest")
    mdir = os.path.join(out, MANIFEST_DIR)
    if not os.path.isdir(mdir):
        raise UsageError("--merge-manifest %s: no %s folder (nothing was run there)" % (out, MANIFEST_DIR))
    want = preset_hash
    if getattr(args, "hash", None):
        h = args.hash.lower()
        if not _HASH_ARG.match(h):
            raise UsageError("--hash '%s' must be 12 to 64 hex digits of a preset hash (the <hash12> of the "
                             "file names)" % args.hash)
        if want and not want.startswith(h):
            raise UsageError("--hash %s is not the hash of --preset (%s)" % (h, want[:12]))
        want = want or h
    rng = parse_range(args.seeds, "--seeds", SEEDS_MAX) if args.seeds else None

    recs, bad = [], []
    for fname in sorted(os.listdir(mdir)):
        if not fname.endswith(".json") or fname.startswith("."):
            continue
        rec, why = load_record(os.path.join(mdir, fname))
        if why:
            bad.append("%s: malformed record: %s" % (os.path.join(MANIFEST_DIR, fname), why))
            continue
        recs.append(rec)
    recs.sort(key=lambda r: (r["preset"], r["preset_hash"], r["seed"]))
    mine = [r for r in recs if want is None or r["preset_hash"].startswith(want)]

    if rng:
        a, b = rng
        inside = [r for r in mine if a <= r["seed"] < b]
        by_hash = {}
        for r in inside:
            by_hash.setdefault(r["preset_hash"], []).append(r)
        if want is None and len(by_hash) > 1:
            parts = []
            for h, rs in sorted(by_hash.items()):
                names = [r["name"] + ".json" for r in rs]
                parts.append("%s (%d records, seeds %s: %s%s)" % (
                    h[:12], len(rs), ranges(sorted({r["seed"] for r in rs})), ", ".join(names[:4]),
                    ", ..." if len(names) > 4 else ""))
            bad.append("seeds %d:%d hold records of %d preset hashes: %s; choose one with --hash HASH12 or "
                       "--preset" % (a, b, len(by_hash), "; ".join(parts)))
        else:
            miss = missing_ranges({r["seed"] for r in inside}, a, b)
            if miss:
                bad.append("seeds without a record%s: %s" % (
                    " of preset hash %s" % want[:12] if want else "", ", ".join(miss[:20])
                    + (", ... (%d runs)" % len(miss) if len(miss) > 20 else "")))
    if args.verify:
        for r in mine:
            for f in r["files"]:
                if not file_ok(out, f):
                    bad.append("%s: %s is missing, not a regular file or differs from its record"
                               % (r["name"] + ".json", f["name"]))
    _leftovers(out, mdir, log)
    target = os.path.join(out, MANIFEST_FILE)
    if bad:
        for b_ in bad:
            log("manifest: %s" % b_)
        log("manifest %s not written (%d problems; any previous one is left as it was)" % (target, len(bad)))
        return 1
    doc = {"schema": RECORD_SCHEMA, "count": len(recs),
           "files": sum(len(r["files"]) for r in recs),
           "bytes": sum(f["bytes"] for r in recs for f in r["files"]),
           "seconds": round(sum(r.get("seconds", 0) for r in recs), 4), "records": recs}
    try:
        bf.write_atomic(target, json.dumps(doc, indent=1, sort_keys=True) + "\n")
    except OSError as e:
        log("manifest %s: cannot write it: %s" % (target, e.strerror or e))
        return 1
    log("manifest %s: %d records, %d files" % (target, doc["count"], doc["files"]))
    return 0

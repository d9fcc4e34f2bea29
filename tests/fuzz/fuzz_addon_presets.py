#!/usr/bin/env python3
"""Fuzzes the add-on's preset reader (blender_addon/banyan/core/presets.py, which
imports without bpy) against the library for a bounded time.

Each round fills a fresh folder with a few files named like presets
(<generator>_<name>.json, some with odd names: non-UTF-8 bytes, control
characters, 200 characters): shipped presets mutated (bytes flipped,
cut, spliced, values swapped for NaN, huge numbers, deep nesting,
wrong types, another generator), random bytes, and files that are not
files (a FIFO, links to /dev/zero, /dev/null and a FIFO, a dangling
link, a link loop, a folder, a sparse file past presets.MAX_BYTES). Then
it lists the folder as the preset menu does (list_presets for every
generator, broken_presets), finds and reads every key, and checks:
  - no call blocks (each has a 5 s alarm) or raises anything but the
    documented refusal: BanyanError from read() / find() (PresetNotFound
    is one); list_presets / broken_presets never raise;
  - every file is listed once, under its name with control characters and
    bytes that are not UTF-8 escaped: good for its generator or broken with
    a message naming the file;
  - a listing takes under a second and the process stays under 1 GB.
A failing round's files are kept in --out (fuzz_addon_presets_fail_<seed>)
and the round's seed is printed: `--seed S --rounds 1` replays it.

    fuzz_addon_presets.py --lib build/libbanyan.so [--seconds 30] [--seed 1] [--rounds N] [--out DIR]
"""
import argparse
import json
import os
import random
import resource
import shutil
import signal
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "..", ".."))
ALARM_S = 5
LIST_S = 1.0
MAX_RSS_MB = 1024


class Hang(Exception):
    pass


def on_alarm(signum, frame):
    raise Hang("no answer within %d s" % ALARM_S)


def shipped():
    d = os.path.join(SRC, "presets")
    out = []
    for fn in sorted(os.listdir(d)):
        if fn.endswith(".json"):
            with open(os.path.join(d, fn), "rb") as f:
                out.append((fn[:-5], f.read()))
    return out


ODD_VALUES = ("NaN", "Infinity", "-1e999", "1e308", "-0", "null", "true", "\"\"", "[]", "{}", "\"\\u0000\"",
              "18446744073709551616", "1" * 5000, "[" * 3000 + "]" * 3000, "\"\\ud800\"", "0.5", "-2147483649")


def names(message, key):
    """Whether the message starts with the file's name: whole, or, in a
    message the library shortened by eliding its middle ("..."), the
    name's first part up to the elision (at least 40 characters)."""
    if message.startswith(key):
        return True
    cut = message.find("...")
    return cut >= 40 and key.startswith(message[:cut])


def printable(text):
    """As the add-on spells a file name in its messages: control characters escaped."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def loads(data):
    try:
        return json.loads(data)
    except (ValueError, RecursionError):
        return None


def mutate(rng, data, docs):
    """One of several mutations of preset bytes."""
    kind = rng.randrange(10)
    b = bytearray(data)
    if kind == 0 and b:  # flip bytes
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(len(b))] = rng.randrange(256)
    elif kind == 1 and b:  # cut
        b = b[:rng.randrange(len(b))]
    elif kind == 2:  # splice two presets
        other = rng.choice(docs)[1]
        b = b[:rng.randrange(len(b) + 1)] + other[rng.randrange(len(other) + 1):]
    elif kind == 3:  # a value swapped for an odd one
        doc = loads(data)
        if doc is None:
            return bytes(b)
        if isinstance(doc, dict) and isinstance(doc.get("params"), dict) and doc["params"]:
            k = rng.choice(sorted(doc["params"]))
            text = json.dumps(doc)
            needle = json.dumps(k) + ": " + json.dumps(doc["params"][k])
            return text.replace(needle, json.dumps(k) + ": " + rng.choice(ODD_VALUES), 1).encode()
        return bytes(b)
    elif kind == 4:  # another generator, an odd one, or none
        doc = loads(data)
        if doc is None:
            return bytes(b)
        if isinstance(doc, dict):
            doc["generator"] = rng.choice(["roots", "keyaki", "ivy", "avenue", "segments", "tube", "", 5, None,
                                           ["roots"], "roots\x00", "ROOTS"])
            if rng.random() < 0.3:
                doc.pop("generator")
        return json.dumps(doc).encode()
    elif kind == 5:  # top level not an object
        return rng.choice([b"[]", b"null", b"42", b"\"roots\"", b"", b"\xef\xbb\xbf{}", b"{", b"\xff\xfe{}"])
    elif kind == 6:  # deep nesting
        n = rng.choice([100, 1000, 100000])
        return b'{"generator": "roots", "params": ' + b"[" * n + b"]" * n + b"}"
    elif kind == 7:  # random bytes
        return bytes(rng.randrange(256) for _ in range(rng.randint(0, 300)))
    elif kind == 8:  # hosts entries of odd kinds
        doc = loads(data)
        if doc is None:
            return bytes(b)
        if isinstance(doc, dict):
            doc["hosts"] = rng.choice([[{"mesh": "/dev/zero"}], [{"mesh": "hosts/none.glb"}], "x", [1, 2],
                                       [{"center": [0, 0, 1e300], "half": [1, 1, 1]}], [{"mesh": "\x1b[31m.glb"}]])
        return json.dumps(doc).encode()
    else:  # a long description with control characters
        doc = loads(data)
        if doc is None:
            return bytes(b)
        if isinstance(doc, dict):
            doc["description"] = "\x1b[2J" + "d" * rng.choice([10, 10000]) + "\x07"
        return json.dumps(doc).encode()
    return bytes(b)


def odd_name(rng, gen, i):
    return rng.choice([
        "%s_f%d" % (gen, i), "%s_f%d\x1b[31m" % (gen, i), "%s_f%d_\udcff" % (gen, i),
        "%s_%s%d" % (gen, "n" * 190, i), "%s_f %d" % (gen, i), "x%d" % i, "%s_f%d.json" % (gen, i)])


def special(rng, d, name, big):
    """A file of an odd kind named `name`; its description."""
    p = os.path.join(d, name)
    kind = rng.randrange(9)
    if kind == 0:
        os.mkfifo(p)
        return "fifo"
    if kind == 1:
        os.symlink("/dev/zero", p)
        return "link to /dev/zero"
    if kind == 2:
        os.symlink("/dev/null", p)
        return "link to /dev/null"
    if kind == 3:
        fifo = os.path.join(d, ".fifo_%s" % name)
        os.mkfifo(fifo)
        os.symlink(fifo, p)
        return "link to a fifo"
    if kind == 4:
        os.symlink(os.path.join(d, "missing_target"), p)
        return "dangling link"
    if kind == 5:
        os.symlink(p, p)
        return "link loop"
    if kind == 6:
        os.mkdir(p)
        return "folder"
    if kind == 7:
        with open(p, "wb") as f:
            f.truncate(big + rng.choice([1, 4096]))
        return "sparse file past MAX_BYTES"
    os.symlink(os.path.join(SRC, "presets"), p)
    return "link to a folder"


def one_round(PR, BanyanError, seed, docs, d):
    """Problems found (a list of strings) in the round of this seed."""
    rng = random.Random(seed)
    problems = []
    made = {}
    for i in range(rng.randint(1, 6)):
        gen = rng.choice(["roots", "keyaki", "ivy", "avenue", "segments", "tube"])
        name = odd_name(rng, gen, i) + ".json"
        try:
            if rng.random() < 0.3:
                made[name[:-5]] = special(rng, d, name, getattr(PR, "MAX_BYTES", 4 << 20))
            else:
                key, data = rng.choice(docs)
                for _ in range(rng.randint(0, 2)):
                    data = mutate(rng, data, docs)
                with open(os.path.join(d, name), "wb") as f:
                    f.write(data)
                made[name[:-5]] = "mutated %s" % key
        except (OSError, UnicodeEncodeError):
            continue  # a name the file system refuses
    PR._parsed.clear()

    def call(what, fn, *args, refusal=False):
        signal.alarm(ALARM_S)
        try:
            return fn(*args), None
        except Hang as e:
            problems.append("%s: %s" % (what, e))
        except BanyanError as e:
            if not refusal:
                problems.append("%s raised BanyanError: %s" % (what, e.message))
            elif not isinstance(e.message, str) or not e.message:
                problems.append("%s: refusal without a message" % what)
            return None, e
        except Exception:
            problems.append("%s raised:\n%s" % (what, traceback.format_exc()))
        finally:
            signal.alarm(0)
        return None, None

    t0 = time.perf_counter()
    good = {}
    for gen in ("roots", "keyaki", "ivy", "avenue", "segments"):
        items, _ = call("list_presets(%r)" % gen, PR.list_presets, gen)
        for key, path, _desc in items or ():
            good.setdefault(key, []).append(gen)
    broken, _ = call("broken_presets()", PR.broken_presets)
    s = time.perf_counter() - t0
    if s > LIST_S:
        problems.append("listing took %.2f s" % s)
    broken = {k: e for k, _p, e in broken or ()}
    for name, what in made.items():
        path = os.path.join(d, name + ".json")
        if not os.path.lexists(path):
            continue
        key = printable(name)  # the menu's identifier of that file
        n = len(good.get(key, [])) + (key in broken)
        if n != 1:
            problems.append("%s (%s): listed %d times (good for %s, broken: %r)" % (
                ascii(key), what, n, good.get(key), broken.get(key)))
        if key in broken and not names(broken[key], key):
            problems.append("%s (%s): its error does not name it: %r" % (ascii(key), what, broken[key]))
        for gen in ("roots", "ivy"):
            call("find(%r, %s)" % (gen, ascii(key)), PR.find, gen, key, refusal=True)
        call("read(%s)" % ascii(key), PR.read, path, refusal=True)
        call("title(%s)" % ascii(key), PR.title, key)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    if rss > MAX_RSS_MB:
        problems.append("peak RSS %.0f MB" % rss)
    return problems, made


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lib", required=True, help="libbanyan.so to check presets with")
    ap.add_argument("--seconds", type=float, default=float(os.environ.get("FUZZ_SECONDS") or 30))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=0, help="stop after this many rounds (0: --seconds only)")
    ap.add_argument("--out", default=tempfile.gettempdir())
    a = ap.parse_args()
    os.environ["BANYAN_LIB"] = os.path.abspath(a.lib)
    sys.path.insert(0, os.path.join(SRC, "blender_addon"))
    from banyan.core import presets as PR
    from banyan.core import lib
    from banyan.core.errors import BanyanError
    lib.load()  # a library that does not load is a failure
    signal.signal(signal.SIGALRM, on_alarm)
    docs = shipped()
    root = tempfile.mkdtemp(prefix="fuzz_addon_presets_")
    PR.preset_dirs = lambda: [os.path.join(root, "p")]
    end = time.monotonic() + a.seconds
    rounds = failed = 0
    seed = a.seed
    try:
        while (a.rounds == 0 or rounds < a.rounds) and (a.rounds or time.monotonic() < end):
            d = os.path.join(root, "p")
            os.mkdir(d)
            problems, made = one_round(PR, BanyanError, seed, docs, d)
            rounds += 1
            if problems:
                failed += 1
                keep = os.path.join(a.out, "fuzz_addon_presets_fail_%d" % seed)
                shutil.rmtree(keep, ignore_errors=True)
                shutil.copytree(d, keep, symlinks=True, ignore=lambda _d, names: [
                    n for n in names if not os.path.isfile(os.path.join(_d, n)) or os.path.islink(os.path.join(_d, n))])
                print("FAIL seed %d (files %s; regular files kept in %s):" % (
                    seed, {ascii(k): v for k, v in made.items()}, keep))
                for p in problems[:10]:
                    print("  " + p)
            shutil.rmtree(d)
            seed += 1
            if failed >= 5:
                break
    finally:
        shutil.rmtree(root, ignore_errors=True)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print("fuzz_addon_presets: %d rounds (seeds %d..%d), %d failed, peak RSS %.0f MB" % (
        rounds, a.seed, seed - 1, failed, rss))
    return 1 if failed or rounds == 0 else 0


if __name__ == "__main__":
    sys.exit(main())

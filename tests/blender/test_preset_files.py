"""Preset files that are not presets, in the user preset folder:
  - a FIFO named roots_*.json, a link to /dev/zero, a folder named *.json
    and a file over presets.MAX_BYTES: the preset menu (operators.base
    preset_items, presets.list_presets / broken_presets) is listed in under
    a second, shows the good user preset and lists each of these as broken
    with what it is; presets.read refuses each with a BanyanError naming
    it, without blocking or reading it;
  - a good preset beside them still applies (the operator runs with it).
Each listing runs in a thread with a deadline, so a listing that blocks
fails the test instead of hanging it.
"""
import os
import shutil
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402
import gens  # noqa: E402

from banyan.core import presets as PR  # noqa: E402
from banyan.core.errors import BanyanError  # noqa: E402

DEADLINE = 1.0  # s: the menu must be listed within this
GIVE_UP = 8.0  # s: a listing still running then has hung (the test ends)
MADE = []  # the files this test made, removed at its end (also when a listing hangs)
GOOD = '{"generator": "roots", "schema": 1, "description": "zz good", "params": {"sides": 6}}\n'


def timed(fn, *args):
    """(fn(*args), seconds), run in a daemon thread; a call still running
    after GIVE_UP seconds fails the test and ends it (it would hang)."""
    box = {}

    def run():
        t0 = time.perf_counter()
        try:
            box["value"] = fn(*args)
        except BaseException as e:  # noqa: B902 - reported below
            box["error"] = e
        box["seconds"] = time.perf_counter() - t0

    th = threading.Thread(target=run, daemon=True)
    th.start()
    th.join(GIVE_UP)
    if th.is_alive():
        bt.check(False, "%s(%s) still running after %.0f s: it blocks" % (fn.__name__, ", ".join(map(repr, args)),
                                                                         GIVE_UP))
        remove_made()
        bt.done()  # ends the process: the blocked thread cannot be stopped
    if "error" in box:
        raise box["error"]
    return box["value"], box["seconds"]


def listing(what):
    """The roots preset menu, checked: in time, the good preset offered."""
    from banyan.ops.base import preset_items
    PR._parsed.clear()  # as on a fresh start: nothing cached
    (items, broken), s = timed(lambda: (preset_items("roots"), PR.broken_presets("roots")))
    bt.check(s < DEADLINE, "%s: the preset menu listed in %.3f s (< %.1f s)" % (what, s, DEADLINE))
    keys = [i[0] for i in items]
    bt.check("roots_zz_files_good" in keys and "roots_mature_fig" in keys,
             "%s: the good user preset and the shipped ones are offered: %s" % (what, keys))
    print("%s: listed in %.3f s, %d items, %d broken" % (what, s, len(items), len(broken)), flush=True)
    return {k: e for k, _, e in broken}


def remove_made():
    for p in MADE:
        if os.path.isdir(p) and not os.path.islink(p):
            shutil.rmtree(p)
        elif os.path.lexists(p):
            os.remove(p)
    del MADE[:]
    PR._parsed.clear()


def test_files():
    d = PR.user_dir(create=True)

    def path(name):
        p = os.path.join(d, name)
        MADE.append(p)
        return p

    try:
        with open(path("roots_zz_files_good.json"), "w") as f:
            f.write(GOOD)
        os.symlink("/dev/zero", path("roots_zz_files_zero.json"))
        broken = listing("a link to /dev/zero")
        err = broken.get("roots_zz_files_zero", "")
        bt.check("link to a character device" in err and "/dev/zero" in err,
                 "the /dev/zero link is listed as broken, saying what it is: %r" % err)

        os.mkfifo(path("roots_zz_files_fifo.json"))
        os.mkdir(path("roots_zz_files_dir.json"))
        with open(path("roots_zz_files_big.json"), "wb") as f:
            f.truncate(PR.MAX_BYTES + 1)  # sparse: nothing written
        # A file name that is not UTF-8 and one with an ESC byte.
        with open(path(os.fsdecode(b"roots_zz_files_\xff.json")), "w") as f:
            f.write(GOOD)
        with open(path("roots_zz_files_\x1b[31m.json"), "w") as f:
            f.write("{")
        broken = listing("a FIFO, a folder and a large file too")
        bt.check("roots_zz_files_\\udcff" in [k for k, _, _ in PR.list_presets("roots")],
                 "a good preset whose file name is not UTF-8 is offered, its key escaped")
        bt.check(broken.get("roots_zz_files_\\x1b[31m", "").startswith("roots_zz_files_\\x1b[31m.json:1:"),
                 "a broken preset with an ESC in its name: listed, escaped: %r"
                 % broken.get("roots_zz_files_\\x1b[31m"))
        for key, want in (("roots_zz_files_fifo", "FIFO"), ("roots_zz_files_dir", "folder"),
                          ("roots_zz_files_big", "at most %d" % PR.MAX_BYTES),
                          ("roots_zz_files_zero", "character device")):
            bt.check(want in broken.get(key, ""), "%s listed as broken with %r: %r" % (key, want, broken.get(key)))
        # Listed a second time: from the cache, and still in time.
        _, s = timed(PR.list_presets, "roots")
        bt.check(s < DEADLINE, "listed again in %.3f s" % s)

        for key in ("roots_zz_files_fifo", "roots_zz_files_zero", "roots_zz_files_dir", "roots_zz_files_big"):
            p = os.path.join(d, key + ".json")
            bt.check(PR.find("roots", key) == p, "find() gives %s's path (choosing it reports why)" % key)
            try:
                timed(PR.read, p)
                bt.check(False, "read(%s): accepted" % key)
            except BanyanError as e:
                bt.check(e.message.startswith(key + ".json: ") and e.name in ("BANYAN_E_IO", "BANYAN_E_LIMIT"),
                         "read(%s) refused naming it: %s %s" % (key, e.name, e.message))
        # The good one beside them applies.
        bt.reset_scene()
        res = gens.op("roots")(banyan_preset="roots_zz_files_good")
        bt.check(res == {'FINISHED'}, "the good user preset runs: %s" % res)
        bt.reset_scene()
        res = gens.op("roots")(banyan_preset="roots_zz_files_\\udcff")
        bt.check(res == {'FINISHED'}, "the good user preset of a file name that is not UTF-8 runs: %s" % res)
    finally:
        remove_made()


if bt.generator("roots"):
    bt.run(test_files)
bt.done()

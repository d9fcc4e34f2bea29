"""The hostile CLI cases, run for real by tools/reliability_table.py.

Each case is a `banyan` command line (with its files made in a scratch
folder), what was wanted, and a judge that reads the run - exit status,
wall time, peak resident memory of the child (os.wait4), its last stderr
line, the files it left - and says whether the wish held. Peak memory is
/usr/bin/time's %M, which sees only the command (a child forked from
this script would inherit its high-water mark). A run is cut at
CUT seconds (its process group killed), which is recorded as "ran past".
Budget cases ask for `--set max_seconds=2` when the command's table has
max_seconds; a build without it runs them unbounded, cut at CUT.
Plain python3, no dependencies.
"""
import hashlib
import json
import os
import shutil
import signal
import struct
import subprocess
import tempfile
import threading
import time

CUT = 20.0        # s: a run still going is killed and recorded as ran past
BUDGET = 2.0      # s: max_seconds asked of budget cases
BUDGET_SLACK = 2.5  # s: a budget run "stops within 2.5 s"


class Run:
    """One finished child: rc (negative: killed by that signal), wall s, rss MB."""

    def __init__(self, rc, wall, rss_mb, out, err, cut):
        self.rc, self.wall, self.rss_mb, self.out, self.err, self.cut = rc, wall, rss_mb, out, err, cut

    def last_err(self):
        lines = [l for l in self.err.replace("\r", "\n").splitlines() if l.strip()]
        return lines[-1].strip() if lines else ""


def run(argv, env=None, cwd=None, cut=CUT, kill_when=None, shell_prefix=None):
    """Runs argv (through bash when shell_prefix, e.g. 'ulimit -f 100;'), cut
    at `cut` s; kill_when: a test polled every millisecond, SIGKILL once true."""
    if shell_prefix:
        argv = ["bash", "-c", shell_prefix + ' exec "$@"', "bash"] + list(argv)
    e = dict(os.environ)
    e.update(env or {})
    with tempfile.TemporaryFile() as fo, tempfile.TemporaryFile() as fe, \
            tempfile.NamedTemporaryFile(suffix=".rss") as fr:
        argv = ["/usr/bin/time", "-f", "%M", "-o", fr.name] + list(argv)
        t0 = time.monotonic()
        p = subprocess.Popen(argv, stdout=fo, stderr=fe, env=e, cwd=cwd, start_new_session=True)
        state = {"cut": False, "done": False}

        def stop(why):
            state[why] = True
            # The command, not /usr/bin/time (which then still reports its
            # peak memory); the whole group if time has no child yet.
            try:
                with open("/proc/%d/task/%d/children" % (p.pid, p.pid)) as f:
                    kids = [int(k) for k in f.read().split()]
            except (OSError, ValueError):
                kids = []
            try:
                for k in kids:
                    os.kill(k, signal.SIGKILL)
                if not kids:
                    os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

        def watch():
            while not state["done"]:
                if kill_when():
                    stop("killed")
                    return
                time.sleep(0.001)

        timer = threading.Timer(cut, stop, ("cut",))
        timer.start()
        watcher = threading.Thread(target=watch) if kill_when else None
        if watcher:
            watcher.start()
        p.wait()
        wall = time.monotonic() - t0
        try:  # anything the command left running
            os.killpg(p.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        state["done"] = True
        timer.cancel()
        if watcher:
            watcher.join()
        fo.seek(0)
        fe.seek(0)
        err = fe.read().decode("utf-8", "replace")
        # time's own lines: "Command exited with non-zero status N" and the
        # signal note; the exit status is the command's (time passes it on).
        err = "\n".join(l for l in err.splitlines() if not l.startswith(("Command exited", "Command terminated")))
        rc = p.returncode
        try:
            with open(fr.name, encoding="utf-8") as f:
                lines = [l for l in f.read().splitlines() if l.strip()]
            rss = int(lines[-1]) / 1024.0
            if lines and lines[0].startswith("Command terminated by signal"):
                rc = -int(lines[0].split()[-1])
        except (OSError, ValueError, IndexError):
            rss = None  # /usr/bin/time itself killed: not measured
        if state["cut"] or state.get("killed"):
            rc = -signal.SIGKILL
        return Run(rc, wall, rss, fo.read().decode("utf-8", "replace"), err, state["cut"])


def has_param(banyan, command, key):
    p = subprocess.run([banyan, command, "--list"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    return any(line.split()[:1] == [key] for line in p.stdout.splitlines())


def sha(path):
    try:
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return None


def glb_ok(path):
    """A whole .glb: its header's length is the file's and its JSON parses."""
    try:
        with open(path, "rb") as f:
            b = f.read()
        magic, _, length = struct.unpack_from("<III", b, 0)
        jlen, jtype = struct.unpack_from("<II", b, 12)
        return magic == 0x46546C67 and length == len(b) and jtype == 0x4E4F534A and json.loads(b[20:20 + jlen])
    except (OSError, struct.error, ValueError):
        return False


def glb_positions(path):
    """World positions of every POSITION accessor (node translations added)."""
    with open(path, "rb") as f:
        b = f.read()
    jlen = struct.unpack_from("<I", b, 12)[0]
    g = json.loads(b[20:20 + jlen])
    bin0 = 20 + jlen + 8
    out = []
    for node in g.get("nodes", []):
        if "mesh" not in node:
            continue
        t = node.get("translation", [0.0, 0.0, 0.0])
        for prim in g["meshes"][node["mesh"]]["primitives"]:
            acc = g["accessors"][prim["attributes"]["POSITION"]]
            view = g["bufferViews"][acc["bufferView"]]
            off = bin0 + view.get("byteOffset", 0) + acc.get("byteOffset", 0)
            stride = view.get("byteStride", 12)
            for i in range(acc["count"]):
                x, y, z = struct.unpack_from("<fff", b, off + i * stride)
                out.append((x + t[0], y + t[1], z + t[2]))
    return out


def describe(r):
    if r.cut:
        return "ran past %.0f s (killed)" % CUT
    if r.rc < 0:
        return "killed by signal %d" % -r.rc
    return "exit %d" % r.rc


class Case:
    def __init__(self, item, what, wanted, build, judge):
        self.item, self.what, self.wanted, self.build, self.judge = item, what, wanted, build, judge


def budget_judge(limit_mb=None):
    """Held: ended within BUDGET_SLACK s, made a mesh or refused with
    BANYAN_E_LIMIT (a clear budget or size error), within limit_mb."""
    def judge(r, ctx):
        ok = not r.cut and r.wall <= BUDGET_SLACK and (r.rc == 0 or "E_LIMIT" in r.err)
        if limit_mb and (r.rss_mb is None or r.rss_mb > limit_mb):
            ok = False
        return ok, "no max_seconds in this build: run without a budget" if ctx.get("no_budget") else ""
    return judge


def refused_judge(*words):
    """Held: a non-zero exit whose message has one of `words`, in 2.5 s."""
    def judge(r, ctx):
        ok = not r.cut and r.rc > 0 and r.wall <= BUDGET_SLACK and any(w.lower() in r.err.lower() for w in words)
        return ok, ""
    return judge


def accepted_judge(r, ctx):
    return (r.rc == 0 and not r.cut), ""


def cases(banyan, presets, tmp):
    """The cases, in a fixed order. Each build(ctx) returns (argv, run
    options); ctx holds the scratch folder and what the judge needs."""
    P = lambda name: os.path.join(presets, name)
    out = lambda name: os.path.join(tmp, name)
    quick = ["--textures", "off"]

    def write_json(name, obj):
        with open(out(name), "w", encoding="utf-8") as f:
            json.dump(obj, f)
        return out(name)

    def budget(cmd, ctx):
        if has_param(banyan, cmd, "max_seconds"):
            return ["--set", "max_seconds=%g" % BUDGET]
        ctx["no_budget"] = True
        return []

    def good_glb(ctx, name):
        """A good old .glb (keyaki_young), its hash kept for the judge."""
        path = out(name)
        subprocess.run([banyan, "keyaki", "--preset", P("keyaki_young.json"), "-o", path] + quick,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        ctx["old"] = sha(path)
        return path

    def old_intact(path_key):
        def judge(r, ctx):
            now = sha(ctx[path_key])
            ok = ctx["old"] is not None and (now == ctx["old"] or (ctx.get("new_ok") and glb_ok(ctx[path_key])))
            note = "old file intact" if now == ctx["old"] else (
                "a complete new file" if glb_ok(ctx[path_key]) else "old file gone or cut short")
            if ctx.get("link") and not os.path.islink(ctx["link"]):
                ok, note = False, note + "; the symlink was replaced"
            return ok, note
        return judge

    L = []
    shared = {}  # what one case's judge leaves for a later one's
    # 1. Writing never destroys the user's file.
    def c_bad_o(ctx):
        return [banyan, "avenue", "--preset", P("avenue_street.json"), "-o", "/nonexistent-dir/x.glb"] + quick, {}
    L.append(Case(1, "`banyan avenue --preset avenue_street.json -o /nonexistent-dir/x.glb`",
                  "refused before any work (under 0.5 s)",
                  c_bad_o, lambda r, c: (r.rc > 0 and not r.cut and r.wall < 0.5, "")))

    def c_ulimit(ctx):
        ctx["target"] = good_glb(ctx, "old.glb")
        return [banyan, "keyaki", "--preset", P("keyaki_mature.json"), "-o", ctx["target"]] + quick, {
            "shell_prefix": "ulimit -f 200;"}
    L.append(Case(1, "`ulimit -f 200; banyan keyaki --preset keyaki_mature.json -o old.glb` over a good old.glb",
                  "fails; old.glb byte-identical", c_ulimit, old_intact("target")))

    def c_symlink(ctx):
        target = good_glb(ctx, "target.glb")
        link = out("link.glb")
        os.symlink(target, link)
        ctx["target"], ctx["link"] = target, link
        return [banyan, "keyaki", "--preset", P("keyaki_mature.json"), "-o", link] + quick, {
            "shell_prefix": "ulimit -f 200;"}
    L.append(Case(1, "the same through a symlink link.glb -> target.glb",
                  "fails; the link stays a link, target.glb byte-identical", c_symlink, old_intact("target")))

    def c_killed(ctx):
        ctx["target"] = good_glb(ctx, "killed.glb")
        ctx["new_ok"] = True
        before = (os.stat(ctx["target"]).st_mtime_ns, set(os.listdir(tmp)))
        t0 = time.monotonic()

        def writing():  # the target touched, or a new file next to it: the write began
            try:
                changed = os.stat(ctx["target"]).st_mtime_ns != before[0] or set(os.listdir(tmp)) != before[1]
            except OSError:
                changed = True
            if changed and "kill_at" not in ctx:
                ctx["kill_at"] = time.monotonic() - t0
            return changed
        return [banyan, "avenue", "--preset", P("avenue_young.json"), "-o", ctx["target"]] + quick, {
            "kill_when": writing}
    def j_killed(r, ctx):
        ok, note = old_intact("target")(r, ctx)
        if "kill_at" not in ctx:
            return False, note + "; finished before the write was seen, not killed"
        return ok, note + "; SIGKILL as the write began, %.2f s in" % ctx["kill_at"]
    L.append(Case(1, "`banyan avenue --preset avenue_young.json -o killed.glb` killed (SIGKILL) during its write",
                  "killed.glb is the old file or a whole new one, never a partial one", c_killed, j_killed))

    # 2. Ivy bounded while it grows.
    L.append(Case(2, "`banyan ivy --set t0=1000000 --set max_seconds=2`",
                  "stops within 2.5 s (a mesh, or BANYAN_E_LIMIT)",
                  lambda ctx: ([banyan, "ivy", "--set", "t0=1000000", "-o", out("ivy.glb")] + budget("ivy", ctx) +
                               quick, {}), budget_judge()))

    def c_km_wall(ctx):
        pre = write_json("wall_1km.json", {"generator": "ivy", "schema": 1, "params": {"start": [0, 0, 0.05]},
                                           "hosts": [{"center": [0, 0.1, 500], "half": [500, 0.1, 500]}]})
        return [banyan, "ivy", "--preset", pre, "-o", out("wall.glb")] + budget("ivy", ctx) + quick, {}
    L.append(Case(2, "ivy on a 1 km x 1 km wall, max_seconds 2",
                  "ends within 2.5 s under 500 MB", c_km_wall, budget_judge(500)))

    # 3. Avenue memory does not multiply with threads.
    for t in (1, 4, 8):
        def c_avenue(ctx, t=t):
            return [banyan, "avenue", "--preset", P("avenue_street.json"), "--threads", str(t), "-o",
                    out("avenue%d.glb" % t)] + quick, {}

        def j_avenue(r, ctx, t=t):
            shared.setdefault("avenue_rss", {})[t] = r.rss_mb
            one = shared["avenue_rss"].get(1)
            if t == 1:
                return (r.rc == 0 and not r.cut), "the reference"
            return (one is not None and r.rc == 0 and r.rss_mb <= 1.2 * one), "%.2fx the 1-thread peak" % (
                r.rss_mb / one if one else float("nan"))
        L.append(Case(3, "`banyan avenue --preset avenue_street.json --threads %d`" % t,
                      "peak memory within 1.2x of 1 thread" if t > 1 else "builds (the 1-thread reference)",
                      c_avenue, j_avenue))
    L.append(Case(3, "`banyan keyaki --set model=simple --set levels=23 --set max_nodes=16777216 --set "
                     "max_seconds=2` (a huge tree: 16.7 M branches)",
                  "ends within 2.5 s under 500 MB",
                  lambda ctx: ([banyan, "keyaki", "--set", "model=simple", "--set", "levels=23", "--set",
                                "max_nodes=16777216", "-o", out("huge.glb")] + budget("keyaki", ctx) + quick, {}),
                  budget_judge(500)))

    # 4. Roots bounded.
    def c_roots(ctx):
        hosts = [{"center": [(i % 16) * 3.0, (i // 16) * 3.0, 1], "half": [1, 1, 1]} for i in range(256)]
        pre = write_json("roots_256.json", {"generator": "roots", "schema": 1,
                                            "params": {"main_roots": 64, "growth_points": 10000, "moves": 100},
                                            "hosts": hosts})
        return [banyan, "roots", "--preset", pre, "-o", out("roots.glb")] + budget("roots", ctx) + quick, {}
    L.append(Case(4, "roots: 256 hosts, 64 roots, 10,000 growth points, 100 moves, max_seconds 2",
                  "stops within 2.5 s with a clear error", c_roots, budget_judge()))

    def c_roots_big(ctx):
        argv, opts = c_roots(ctx)
        return argv + ["--set", "max_vertices=1073741824"], opts
    L.append(Case(4, "the same with max_vertices at its largest (1,073,741,824), so no estimate refuses it",
                  "stops within 2.5 s with a clear error", c_roots_big, budget_judge()))

    # 5. Precision far from the origin.
    def c_far(ctx):
        near = json.load(open(P("roots_trunk.json"), encoding="utf-8"))
        far = json.loads(json.dumps(near))
        for h in far["hosts"]:
            h["center"][0] += 999999.0
        ctx["near"] = out("near.glb")
        subprocess.run([banyan, "roots", "--preset", P("roots_trunk.json"), "-o", ctx["near"]] + quick,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        ctx["far"] = out("far.glb")
        return [banyan, "roots", "--preset", write_json("roots_far.json", far), "-o", ctx["far"]] + quick, {}

    def j_far(r, ctx):
        if r.rc != 0:
            return r.rc > 0 and "1e6" in r.err, "refused"
        try:
            a, b = glb_positions(ctx["near"]), glb_positions(ctx["far"])
        except (OSError, ValueError, KeyError, struct.error):
            return False, "cannot read the meshes"
        if len(a) != len(b):
            return False, "%d vertices near the origin, %d far" % (len(a), len(b))
        err = max((max(abs(q[0] - 999999.0 - p[0]), abs(q[1] - p[1]), abs(q[2] - p[2])) for p, q in zip(a, b)),
                  default=0.0)
        return err <= 1e-3, "largest difference from the shifted origin run %.4g m" % err
    L.append(Case(5, "roots_trunk with its host moved to x = 999,999 m",
                  "the roots at the origin shifted, to 1 mm (or refused)", c_far, j_far))

    # 6. Explicit empty lists.
    def c_empty_hosts(ctx):
        pre = write_json("no_hosts.json", {"generator": "roots", "schema": 1, "params": {}, "hosts": []})
        return [banyan, "roots", "--preset", pre, "-o", out("empty.glb")] + quick, {}
    L.append(Case(6, 'roots preset with `"hosts": []`', "refused (an empty list is an error)", c_empty_hosts,
                  refused_judge("host")))

    def c_empty_segs(ctx):
        pre = write_json("no_segments.json", {"generator": "segments", "schema": 1, "params": {}, "segments": []})
        return [banyan, "segments", "--preset", pre, "-o", out("empty_seg.glb")] + quick, {}
    L.append(Case(6, 'segments preset with `"segments": []`', "refused (an empty list is an error)", c_empty_segs,
                  refused_judge("segment")))

    # 7. Smaller.
    L.append(Case(7, "`LC_NUMERIC=de_DE.UTF-8 banyan roots --set maturity=0.5`", "0.5 accepted",
                  lambda ctx: ([banyan, "roots", "--set", "maturity=0.5", "--set", "growth_points=10", "-o",
                                out("locale.glb")] + quick, {"env": {"LC_ALL": "", "LANG": "",
                                                                     "LC_NUMERIC": "de_DE.UTF-8"}}),
                  accepted_judge))
    L.append(Case(7, "`banyan keyaki --threads abc`", "refused, naming --threads",
                  lambda ctx: ([banyan, "keyaki", "--threads", "abc", "-o", out("t.glb")] + quick, {}),
                  refused_judge("--threads")))
    L.append(Case(7, "`banyan keyaki --seed \" -1\"`", "refused, naming the seed",
                  lambda ctx: ([banyan, "keyaki", "--seed", " -1", "-o", out("s.glb")] + quick, {}),
                  refused_judge("seed")))

    def c_big_preset(ctx):
        path = out("big.json")
        with open(path, "wb") as f:
            f.write(b'{"generator": "keyaki", "schema": 1, "description": "')
            f.write(b"x" * (200 * 1024 * 1024))
            f.write(b'"}')
        return [banyan, "keyaki", "--preset", path, "-o", out("big.glb")] + quick, {}
    def j_big(r, ctx):
        ok = r.rc > 0 and not r.cut and "success" not in r.err.lower() and r.wall <= BUDGET_SLACK
        return ok, ""
    L.append(Case(7, "a 200 MB preset", "refused with a message that says why (not \"Success\")", c_big_preset,
                  j_big))
    L.append(Case(7, "`banyan avenue --set tree.trunk_length=0.01` (its documented minimum)", "accepted",
                  lambda ctx: ([banyan, "avenue", "--set", "tree.trunk_length=0.01", "--set", "count=1", "--set",
                                "placement=count", "-o", out("tl.glb")] + quick, {}), accepted_judge))

    # The stages after generation keep the command's budget, and a bad -o
    # is a bad command line, refused before any work.
    def stage_judge(budget_s, limit_mb=None):
        """Held: a mesh or BANYAN_E_LIMIT within budget_s + 0.5 s (and limit_mb)."""
        def judge(r, ctx):
            ok = not r.cut and r.wall <= budget_s + 0.5 and (r.rc == 0 or "E_LIMIT" in r.err)
            if limit_mb and (r.rss_mb is None or r.rss_mb > limit_mb):
                ok = False
            return ok, ""
        return judge
    L.append(Case(2, "`banyan keyaki --preset keyaki_mature.json --texture-size 8192 --set max_seconds=1 --set "
                     "max_memory_mb=200`", "textures refused from their size within 1.5 s under 400 MB",
                  lambda ctx: ([banyan, "keyaki", "--preset", P("keyaki_mature.json"), "--texture-size", "8192",
                                "--set", "max_seconds=1", "--set", "max_memory_mb=200", "-o", out("k8192.glb")], {}),
                  stage_judge(1.0, 400)))
    L.append(Case(2, "`banyan avenue --preset avenue_mixed_age.json --lod 0.5,0.15,billboard --set max_seconds=1`",
                  "stops within 1.5 s", lambda ctx: ([banyan, "avenue", "--preset", P("avenue_mixed_age.json"),
                                                      "--lod", "0.5,0.15,billboard", "--set", "max_seconds=1",
                                                      "-o", out("lod.glb")] + quick, {}),
                  stage_judge(1.0)))
    L.append(Case(2, "`banyan roots --preset roots_trunk.json --set voxel_size=0.1 --set max_seconds=4` (the budget "
                     "passes while OpenVDB meshes)", "stops within 4.5 s",
                  lambda ctx: ([banyan, "roots", "--preset", P("roots_trunk.json"), "--set", "voxel_size=0.1",
                                "--set", "max_seconds=4", "-o", out("vdb.glb")] + quick, {}),
                  stage_judge(4.0)))
    L.append(Case(1, "`banyan keyaki --preset keyaki_mature.json -o <a 256-byte name>.glb`",
                  "refused before any work (exit 2, under 0.5 s), naming the file name's length",
                  lambda ctx: ([banyan, "keyaki", "--preset", P("keyaki_mature.json"), "-o",
                                out("a" * 252 + ".glb")] + quick, {}),
                  lambda r, c: (r.rc == 2 and not r.cut and r.wall < 0.5 and "file name is 256 bytes" in r.err, "")))

    # 8. Hostile host files and presets: refused from their sizes, inside the budget, messages escaped.
    def glb(name, doc, bin_len, bin_bytes=b"", size=None):
        """A .glb of the JSON doc and a BIN chunk of bin_len bytes (bin_bytes, then zeros left as a sparse
        hole); size: a larger file (sparse) whose header says so."""
        js = json.dumps(doc).encode()
        js += b" " * (-len(js) % 4)
        bl = bin_len + (-bin_len % 4)
        total = 20 + len(js) + (8 + bl if bin_len else 0)
        with open(out(name), "wb") as f:
            f.write(struct.pack("<4sIIII", b"glTF", 2, size or total, len(js), 0x4E4F534A) + js)
            if bin_len:
                f.write(struct.pack("<II", bl, 0x004E4942) + bin_bytes)
            f.truncate(size or total)
        return out(name)

    def mesh_doc(nodes=1, prims=None, accessors=None, views=None, buffer_len=96):
        return {"asset": {"version": "2.0"}, "scenes": [{"nodes": list(range(nodes))}],
                "nodes": [{"mesh": 0, "translation": [i, 0, 0]} for i in range(nodes)],
                "meshes": [{"primitives": prims or [{"attributes": {"POSITION": 0}, "indices": 1}]}],
                "buffers": [{"byteLength": buffer_len}],
                "bufferViews": views or [{"buffer": 0, "byteLength": 48},
                                         {"buffer": 0, "byteOffset": 48, "byteLength": 48}],
                "accessors": accessors or [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                                           {"bufferView": 1, "componentType": 5125, "count": 12, "type": "SCALAR"}]}
    tet = struct.pack("<12f12I", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3)

    def roots_host(path, extra=()):
        return [banyan, "roots", "--host", path, "-o", out("h.glb")] + list(extra) + budget("roots", {}) + quick

    def refused_2(*words):
        """refused_judge, with exit code 2: host files are refused as a bad command line."""
        def judge(r, ctx):
            ok, note = refused_judge(*words)(r, ctx)
            return ok and r.rc == 2, note if r.rc == 2 else "exit %d, not 2" % r.rc
        return judge

    def refused_small(limit_mb, *words):
        def judge(r, ctx):
            ok, note = refused_2(*words)(r, ctx)
            return ok and r.rss_mb is not None and r.rss_mb <= limit_mb, note
        return judge

    def c_wrap(ctx):
        d = mesh_doc()
        d["accessors"][0].update(byteOffset=2 ** 64 - 64 * 2 ** 20, count=5592406)
        return roots_host(glb("wrap.glb", d, 96, tet)), {}
    L.append(Case(8, "`banyan roots --host wrap.glb`: an accessor at byteOffset 2^64 - 64 MiB whose end wraps to "
                  "byte 8", "refused (no crash, exit 2), naming the accessor", c_wrap, refused_2("reaches past")))

    def c_mode(ctx):
        d = mesh_doc()
        d["meshes"][0]["primitives"][0]["mode"] = -5
        return roots_host(glb("mode.glb", d, 96, tet)), {}
    L.append(Case(8, "`banyan roots --host mode.glb`: primitive mode -5", "refused (exit 2), naming the mode",
                  c_mode, refused_2("mode = -5")))

    def c_not_gltf(ctx):
        with open(out("zip.glb"), "wb") as f:
            f.write(b"PK\x03\x04 not glTF")
            f.truncate(2 * 10 ** 9)
        return roots_host(out("zip.glb")), {}
    L.append(Case(8, "`banyan roots --host zip.glb`: a 2 GB file that is not glTF",
                  "refused from its 12-byte header (exit 2), under 100 MB", c_not_gltf,
                  refused_small(100, "does not start with")))

    def c_big_header(ctx):
        d = mesh_doc(buffer_len=2 * 10 ** 9 - 2048,
                     views=[{"buffer": 0, "byteLength": 12000000},
                            {"buffer": 0, "byteOffset": 12000000, "byteLength": 150000000}],
                     accessors=[{"bufferView": 0, "componentType": 5126, "count": 1000000, "type": "VEC3"},
                                {"bufferView": 1, "componentType": 5121, "count": 150000000, "type": "SCALAR"}])
        return roots_host(glb("big.glb", d, 2 * 10 ** 9 - 2048, size=None)), {}
    L.append(Case(8, "`banyan roots --host big.glb`: a valid header and JSON on 2 GB (50 M triangles)",
                  "refused from its JSON before the 2 GB are read, under 100 MB", c_big_header,
                  refused_small(100, "33554432")))

    def instanced(name, nodes):
        d = mesh_doc(nodes=nodes, prims=[{"attributes": {"POSITION": 0}}], buffer_len=1199988,
                     views=[{"buffer": 0, "byteLength": 1199988}],
                     accessors=[{"bufferView": 0, "componentType": 5126, "count": 99999, "type": "VEC3"}])
        return glb(name, d, 1199988)
    L.append(Case(8, "`banyan roots --host inst.glb --set max_memory_mb=64 --set max_seconds=2`: 100 nodes "
                  "instancing one 100k-vertex mesh (1.2 MB)", "stops within 2.5 s under 100 MB",
                  lambda ctx: (roots_host(instanced("inst.glb", 100), ["--set", "max_memory_mb=64"]), {}),
                  budget_judge(100)))
    L.append(Case(8, "`banyan roots --host inst2000.glb`: 2,000 nodes instancing one 100k-vertex mesh",
                  "refused from its JSON, counting the instances", lambda ctx: (
                      roots_host(instanced("inst2000.glb", 2000)), {}), refused_small(100, "instance")))

    def c_shared(ctx):
        d = mesh_doc(prims=[{"attributes": {"POSITION": 0}, "indices": 1}] * 5000, buffer_len=2400012,
                     views=[{"buffer": 0, "byteLength": 2400000},
                            {"buffer": 0, "byteOffset": 2400000, "byteLength": 12}],
                     accessors=[{"bufferView": 0, "componentType": 5126, "count": 200000, "type": "VEC3"},
                                {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}])
        return roots_host(glb("shared.glb", d, 2400012)), {}
    L.append(Case(8, "`banyan roots --host shared.glb`: 5,000 primitives sharing one 200k-vertex accessor",
                  "refused from its JSON, counting the vertex reads", c_shared,
                  refused_small(100, "vertices to read")))

    def c_many(ctx):
        d = mesh_doc(buffer_len=3000036, views=[{"buffer": 0, "byteLength": 36},
                                                {"buffer": 0, "byteOffset": 36, "byteLength": 3000000}],
                     accessors=[{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                                {"bufferView": 1, "componentType": 5121, "count": 3000000, "type": "SCALAR"}])
        glb("one_m.glb", d, 3000036)
        pre = write_json("many.json", {"generator": "roots", "schema": 1, "hosts": [{"mesh": "one_m.glb"}] * 150})
        return [banyan, "roots", "--preset", pre, "-o", out("m.glb")] + budget("roots", ctx) + quick, {}
    L.append(Case(8, "a roots preset naming one 1M-triangle file 150 times", "refused by the set-wide limit "
                  "before the files are read, under 100 MB", c_many, refused_small(100, "33554432")))

    def c_many_cli(ctx):
        c_many(ctx)
        hosts = sum((["--host", out("one_m.glb") + "@%d,0,0" % i] for i in range(150)), [])
        return [banyan, "roots"] + hosts + ["-o", out("m.glb")] + budget("roots", ctx) + quick, {}
    L.append(Case(8, "`banyan roots --host one_m.glb@i,0,0` 150 times (a 1M-triangle file)", "refused by the "
                  "set-wide limit, the file read once, under 100 MB", c_many_cli, refused_small(100, "33554432")))

    def c_esc(ctx):
        pre = write_json("esc.json", {"generator": "roots", "schema": 1,
                                      "hosts": [{"mesh": "a\u001b[2J\u001b]0;pwned\u0007.glb"}]})
        return [banyan, "roots", "--preset", pre, "-o", out("e.glb")] + quick, {}
    def j_esc(r, ctx):
        ok = r.rc == 2 and not r.cut and "\x1b" not in r.err and "\\x1b[2J" in r.err
        return ok, "" if ok else "control characters reached the terminal"
    L.append(Case(8, "a preset whose mesh path holds ESC sequences", "refused with the path's control characters "
                  "escaped (\\x1b)", c_esc, j_esc))
    return L


def run_all(banyan, presets):
    """Runs every case; returns rows of dicts for the table."""
    rows = []
    tmp = tempfile.mkdtemp(prefix="banyan_hostile_")
    try:
        for c in cases(banyan, presets, tmp):
            ctx = {}
            try:
                argv, opts = c.build(ctx)
                r = run(argv, **opts)
                held, note = c.judge(r, ctx)
                rows.append({"item": c.item, "what": c.what, "wanted": c.wanted, "held": bool(held),
                             "outcome": describe(r), "wall": r.wall, "rss_mb": r.rss_mb,
                             "message": r.last_err(), "note": note})
            except OSError as e:
                rows.append({"item": c.item, "what": c.what, "wanted": c.wanted, "held": False,
                             "outcome": "could not run: %s" % e, "wall": 0.0, "rss_mb": 0.0, "message": "",
                             "note": ""})
            for name in os.listdir(tmp):  # each case starts from an empty folder
                p = os.path.join(tmp, name)
                if os.path.isdir(p) and not os.path.islink(p):
                    shutil.rmtree(p)
                else:
                    os.unlink(p)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return rows

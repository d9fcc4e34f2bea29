"""The binding (banyan.core) without bpy: it imports in plain Python,
parameter tables drive set/get/check, the library's messages come back as
BanyanError, and meshes copy out intact."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

from banyan.core import BanyanError, lib, mesh, params, structs as S  # noqa: E402
from banyan.core import generators as G  # noqa: E402


def test_plain_python():
    addon_parent = os.path.join(bt.SOURCE_DIR, "blender_addon")
    code = ("import sys; sys.path.insert(0, %r)\n"
            "import banyan.core.lib as L, banyan.core.params, banyan.core.mesh, banyan.core.generators\n"
            "L.load(); d = banyan.core.mesh.tube([(0,0,0),(0,0,1)], [0.1,0.1], 6)\n"
            "assert 'bpy' not in sys.modules, 'bpy imported'\n"
            "print('plain', d.vertex_count)\n" % addon_parent)
    r = subprocess.run([sys.executable.replace("blender", "python3") if not os.path.exists("/usr/bin/python3")
                        else "/usr/bin/python3", "-c", code], capture_output=True, text=True)
    bt.check(r.returncode == 0 and "plain" in r.stdout, "core works in plain python without bpy: %s" % r.stderr[-300:])


def test_loader():
    L = lib.load()
    bt.check(L.banyan_abi_version() == S.ABI_VERSION, "ABI version")
    for k, cls in S.SIZED.items():
        import ctypes
        bt.check(getattr(L, "banyan_sizeof_" + k)() == ctypes.sizeof(cls), "sizeof %s" % k)
    old = os.environ.get("BANYAN_LIB")
    os.environ["BANYAN_LIB"] = "/x/y.so"
    bt.check(lib.candidate_paths() == ["/x/y.so"], "BANYAN_LIB overrides all")
    del os.environ["BANYAN_LIB"]
    c = lib.candidate_paths()
    bt.check(c[0].endswith(os.path.join("banyan", "lib", "libbanyan.so")) and
             c[1].endswith(os.path.join("build", "libbanyan.so")), "lib/ then the repo's build/: %s" % c)
    if old is not None:
        os.environ["BANYAN_LIB"] = old


def test_tube_copy():
    pts = [(0, 0, 0), (0, 0, 1), (0.5, 0, 2)]
    d = mesh.tube(pts, [0.1, 0.1, 0.05], 8)
    bt.check(len(d.positions) == 3 * d.vertex_count and len(d.indices) == d.index_count, "array lengths")
    bt.check(max(d.indices) < d.vertex_count and min(d.indices) >= 0, "indices in range")
    bt.check(abs(d.positions[2] - 0.0) < 0.2, "first ring near the start")
    bt.check(d.parts and d.parts[0]["vertex_count"] == d.vertex_count, "one part covers all")
    try:
        mesh.tube([(0, 0, 0), (0, 0, 0)], [1, 1])
        bt.check(False, "repeated points accepted")
    except BanyanError as e:
        bt.check(e.status == 2 and e.name == "BANYAN_E_RANGE" and "repeats" in e.message, "tube error: %s" % e)


def test_params(gen):
    p = params.Params(gen)
    bt.check(len(p.specs) == lib.load().banyan_param_count(params.generator_id(gen)), "%s: every row" % gen)
    p.check()
    for s in p.specs:
        v = p.get(s.name)
        if s.type == S.PT_DOUBLE:
            try:
                p.set(s.name, s.max * 2 + 1 if s.max > 0 else s.max + 1)
                bt.check(s.max >= 1e300, "%s.%s above max accepted" % (gen, s.name))
            except BanyanError as e:
                bt.check(e.status == 2 and s.name in e.message, "%s.%s range: %s" % (gen, s.name, e.message))
            bt.check(p.get(s.name) == v, "%s.%s unchanged after a refused set" % (gen, s.name))
            try:
                p.set(s.name, float("inf"))
                bt.check(False, "%s.%s inf accepted" % (gen, s.name))
            except BanyanError:
                bt.check(p.get(s.name) == v, "%s.%s unchanged after inf" % (gen, s.name))
        elif s.type == S.PT_ENUM:
            for c in s.choices:
                p.set(s.name, c)
                bt.check(p.get(s.name) == c, "%s.%s = %s" % (gen, s.name, c))
            p.set(s.name, v)
    try:
        p.set("no_such_parameter", 1)
        bt.check(False, "unknown key accepted")
    except BanyanError as e:
        bt.check(e.status == 11, "%s: unknown key -> BANYAN_E_UNKNOWN_KEY" % gen)


def test_atomic_file():
    """write_atomic (user presets): a failed write (a full disk: a child
    with a 64 KiB file size limit) keeps the old file byte for byte and
    leaves no temporary file; a symlink stays a link; the mode is kept."""
    import shutil
    import stat
    import tempfile
    from banyan.core.atomic_file import write_atomic
    d = tempfile.mkdtemp(prefix="atomic_", dir=bt.OUT_DIR if os.path.isdir(bt.OUT_DIR) else None)
    try:
        path, link = os.path.join(d, "p.json"), os.path.join(d, "link.json")
        write_atomic(path, "old")
        os.chmod(path, 0o640)
        os.symlink("p.json", link)
        write_atomic(link, b"new")
        bt.check(os.path.islink(link) and os.readlink(link) == "p.json", "a symlink stays a link")
        bt.check(open(path, "rb").read() == b"new", "its target replaced")
        bt.check(stat.S_IMODE(os.stat(path).st_mode) == 0o640, "the mode kept")
        addon_parent = os.path.join(bt.SOURCE_DIR, "blender_addon")
        code = ("import resource, signal, sys; sys.path.insert(0, %r)\n"
                "from banyan.core.atomic_file import write_atomic\n"
                "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
                "resource.setrlimit(resource.RLIMIT_FSIZE, (65536, 65536))\n"
                "try:\n    write_atomic(%r, b'x' * (1 << 20))\n"
                "except OSError as e:\n    print('refused', e.errno)\n" % (addon_parent, link))
        r = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True)
        import errno
        bt.check("refused %d" % errno.EFBIG in r.stdout, "a full disk is an OSError EFBIG: %r %r" % (r.stdout, r.stderr[-300:]))
        bt.check(open(path, "rb").read() == b"new", "the old file kept after a full disk")
        bt.check(os.path.islink(link), "the link kept after a full disk")
        left = [n for n in os.listdir(d) if n.endswith(".tmp")]
        bt.check(not left, "no temporary file left: %s" % left)
    finally:
        shutil.rmtree(d, ignore_errors=True)


bt.run(test_plain_python)
bt.run(test_loader)
bt.run(test_tube_copy)
bt.run(test_atomic_file)
for g in S.GENERATORS:
    if bt.generator(g):
        bt.run(lambda: test_params(g))
bt.done()

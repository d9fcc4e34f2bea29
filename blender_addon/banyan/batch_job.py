"""The batch runner's job (batch_run.py): one preset of any generator the
CLI grows (roots, ivy, segments, avenue, keyaki), its hosts, its preset
hash and the glTF writer's options, shared by every seed of a run.

Hosts are chosen as the CLI's `banyan <gen> --preset P [--host F.glb@x,y,z]`
chooses them (csrc/cli/main.c): a preset with boxes only and no --host
grows on its boxes (banyan_preset_hosts); a preset with a mesh host
("mesh": "hosts/x.glb", read beside the preset) or any --host grows on the
library's host set of the preset (banyan_preset_host_set, through
core.hostset.HostSet.from_preset) plus the --host meshes; a roots or ivy
preset without hosts grows on the CLI's default box. Segments take the
preset's "segments" list, else the demo tree of the seed. So every .glb is
the CLI's bytes for the same preset, seed and options.

Loaded as a submodule of the add-on package (batch_run._sub): no bpy.
"""
import ctypes as C
import hashlib
import importlib
import json
import os
import re

GENERATORS = ("roots", "ivy", "segments", "avenue", "keyaki")  # every generator the CLI grows from a preset
HOSTED = ("roots", "ivy")  # the generators that take hosts (and --host)
# The CLI's default hosts (cmd_roots.c, cmd_ivy.c) when a preset names none: (centre, half extents).
DEFAULT_BOX = {"roots": ((0.0, 0.0, 4.0), (0.4, 0.4, 4.0)),    # a trunk 0.8 m wide, 8 m tall
               "ivy": ((0.0, 0.1, 1.5), (1.5, 0.1, 1.5))}      # a 3 m x 3 m wall, its face y = 0
# The node names the CLI gives its one mesh (None: the library's "banyan_0").
NODE_NAME = {"roots": None, "segments": None, "ivy": "ivy", "avenue": "avenue", "keyaki": "keyaki"}
# submit.sh's own options (each with a value): accepted and ignored by --check.
SUBMIT_OPTIONS = ("--per-task", "--workers", "--logs")


class UsageError(Exception):
    """Bad arguments or preset: exit status 2 with the message."""


def _sub(name):
    return importlib.import_module(__package__ + "." + name)


def _here():
    return os.path.dirname(os.path.abspath(__file__))


def _sha256(data):
    return hashlib.sha256(data).hexdigest()


def _file_sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _canonical(obj):
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def find_preset(name):
    """A path for NAME_OR_PATH: an existing file, else a shipped preset
    (banyan/presets/ in the zip, <repo>/presets/ beside the add-on)."""
    if os.path.isfile(name):
        return os.path.abspath(name)
    if os.sep in name or name.endswith(".json"):
        raise UsageError("--preset '%s': no such file" % name)
    here = _here()
    dirs = [os.path.join(here, "presets"),
            os.path.normpath(os.path.join(os.path.dirname(os.path.realpath(os.path.join(here, "__init__.py"))),
                                          "..", "..", "presets"))]
    for d in dirs:
        f = os.path.join(d, name + ".json")
        if os.path.isfile(f):
            return f
    raise UsageError("--preset '%s': not a file, nor a shipped preset (looked in %s)" % (name, ", ".join(dirs)))


_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def host_spec(spec):
    """'FILE.glb' or 'FILE.glb@x,y,z' (the CLI's --host) -> (path, (x, y, z)).
    As the CLI: the part after the last '@' is a placement when it starts
    like a number, and must then be three numbers within [-1e6, 1e6]."""
    at = spec.rfind("@")
    t = (0.0, 0.0, 0.0)
    path = spec
    if at >= 0 and at + 1 < len(spec) and spec[at + 1] in "+-.0123456789":
        parts = spec[at + 1:].split(",")
        if len(parts) != 3 or not all(_NUMBER.match(p) for p in parts):
            raise UsageError("--host %s: expected FILE.glb or FILE.glb@x,y,z (metres, each within [-1e6, 1e6])"
                             % spec)
        t = tuple(float(p) for p in parts)
        if not all(-1e6 <= v <= 1e6 for v in t):
            raise UsageError("--host %s: expected FILE.glb or FILE.glb@x,y,z (metres, each within [-1e6, 1e6])"
                             % spec)
        path = spec[:at]
    if not path:
        raise UsageError("--host %s: expected FILE.glb or FILE.glb@x,y,z (metres, each within [-1e6, 1e6])" % spec)
    return path, t


def strip_submit_options(argv):
    """argv without submit.sh's own options and their values (for --check)."""
    out, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a in SUBMIT_OPTIONS:
            skip = True
        elif not any(a.startswith(o + "=") for o in SUBMIT_OPTIONS):
            out.append(a)
    return out


class Job:
    """The resolved preset, hosts and options, shared by every seed of a run."""

    GENERATORS = GENERATORS

    def __init__(self, args):
        self.core = _sub("core")
        self.P = _sub("core.params")
        self.G = _sub("core.generators")
        self.M = _sub("core.mesh")
        self.S = _sub("core.structs")
        self.L = _sub("core.lib")
        self.H = _sub("core.hostset")
        self.errors = _sub("core.errors")
        try:
            self.L.load()
        except self.errors.BanyanError as e:
            raise UsageError("libbanyan: %s" % e.message)
        self.preset_path = find_preset(args.preset)
        with open(self.preset_path, "rb") as f:
            self.preset_text = f.read()
        try:
            doc = json.loads(self.preset_text)
        except ValueError as e:
            raise UsageError("--preset %s: not JSON: %s" % (self.preset_path, e))
        gen = doc.get("generator") if isinstance(doc, dict) else None
        if gen not in GENERATORS:
            raise UsageError("--preset %s: generator %r: the runner grows %s (as the CLI)"
                             % (self.preset_path, gen, ", ".join(GENERATORS)))
        self.generator = gen
        self.preset_name = os.path.splitext(os.path.basename(self.preset_path))[0]
        try:
            self.params = self.P.Params(gen)
            self.params.apply_preset(self.preset_text, os.path.basename(self.preset_path))
            self.params.check()
        except self.errors.BanyanError as e:
            raise UsageError("--preset %s: %s" % (self.preset_path, e.message))
        if not (0 <= args.threads <= 1024):
            raise UsageError("--threads %d must be within [0, 1024] (0: all cores)" % args.threads)
        ts = args.texture_size
        if ts < 64 or ts > 8192 or ts & (ts - 1):
            raise UsageError("--texture-size %d must be a power of two within [64, 8192]" % ts)
        self.threads = args.threads
        self.hostset, self.boxes, self.segments_input = None, None, None
        host_args = self._hosts(doc, list(getattr(args, "host", None) or []))
        if gen == "segments":
            try:
                inputs = self.G.segments_read(self.preset_text, self.preset_path)
            except self.errors.BanyanError as e:
                raise UsageError("--preset %s: %s" % (self.preset_path, e.message))
            self.segments_input = inputs if inputs[1] else None  # none: the demo tree of each seed
        self.format = getattr(args, "format", None) or "glb"
        if self.format not in ("glb", "usda"):
            raise UsageError("--format %s must be glb or usda" % self.format)
        self.ext = "." + self.format
        # USD's images are always files: shared, as --shared-textures shares the glTF's.
        shared = bool(getattr(args, "shared_textures", False)) or self.format == "usda"
        self.gltf = {"textures": 0 if args.no_textures else 1, "texture_size": ts, "texture_seed": 1,
                     "engine_uvs": 0, "shared_textures": 1 if shared and not args.no_textures else 0}
        if self.format != "glb":
            self.gltf["format"] = self.format  # in the hash (a .glb's hash stays as it was)
        self.version = self.L.version()
        resolved = self.params.as_dict()
        resolved.pop("seed", None)
        # What else decides the bytes: the preset's host and segment lists, the
        # bytes of every mesh host file and --host file, libbanyan's version.
        scene = {k: doc[k] for k in ("hosts", "segments", "trunk") if k in doc}
        self.preset_hash = _sha256(_canonical({"generator": gen, "params": resolved, "gltf": self.gltf,
                                               "scene": scene, "host_files": self.host_files,
                                               "host_args": host_args, "banyan": self.version}))
        self.image_dir = "%s-%s-textures" % (self.preset_name, self.preset_hash[:12]) if self.gltf[
            "shared_textures"] else None
        self._bind_writer()

    # ------------------------------------------------------------ hosts
    def _hosts(self, doc, specs):
        """The CLI's choice of hosts (csrc/cli/main.c); returns what the
        --host arguments add to the hash. Sets self.hostset or self.boxes
        (roots, ivy) and self.host_files (sha256 of each preset mesh file,
        in the preset's order; None for a file that cannot be read)."""
        gen, path = self.generator, self.preset_path
        base = os.path.dirname(path)
        self.host_files = []
        for h in doc.get("hosts") or []:
            if isinstance(h, dict) and isinstance(h.get("mesh"), str):
                f = h["mesh"] if os.path.isabs(h["mesh"]) else os.path.join(base, h["mesh"])
                try:
                    self.host_files.append(_file_sha256(f))
                except OSError:
                    self.host_files.append(None)  # the library refuses it below, naming hosts[i]
        if specs and gen not in HOSTED:
            raise UsageError("--host: the %s generator takes no hosts (%s do)" % (gen, " and ".join(HOSTED)))
        parsed = [host_spec(s) for s in specs]
        host_args = []
        for (f, t), s in zip(parsed, specs):
            try:
                host_args.append({"sha256": _file_sha256(f), "at": list(t)})
            except OSError as e:
                raise UsageError("--host %s: %s" % (s, e.strerror or e))
        use_set = bool(specs)
        boxes = []
        if not use_set:
            try:
                boxes = self.P.preset_hosts(self.preset_text, path)
            except self.errors.BanyanError as e:
                if e.name != "BANYAN_E_UNSUPPORTED" or gen not in HOSTED:
                    raise UsageError("--preset %s: %s" % (path, e.message))
                use_set = True  # a mesh host: the host set, as the CLI
        if gen not in HOSTED:
            return host_args  # avenue, keyaki and segments grow without hosts (the CLI ignores box hosts)
        if use_set:
            extra, first = [], {}
            for (f, t), s in zip(parsed, specs):
                try:
                    if f in first:  # a file named again: the first one's triangles, moved (the CLI's rule)
                        m, t0 = first[f]
                        rows = list(m.transform)
                        for r in range(3):
                            rows[4 * r + 3] += t[r] - t0[r]
                        extra.append(self.H.MeshInput(m.positions, m.indices, transform=rows, closed=m.closed,
                                                      name=m.name))
                        continue
                    m = self.H.read_glb(f, transform=(1, 0, 0, t[0], 0, 1, 0, t[1], 0, 0, 1, t[2]))
                except self.errors.BanyanError as e:
                    raise UsageError("--host %s: %s: %s" % (s, e.name, e.message))
                first[f] = (m, t)
                extra.append(m)
            try:
                self.hostset = self.H.HostSet.from_preset(self.preset_text, path, base_dir=base, extra=extra)
            except self.errors.BanyanError as e:
                raise UsageError("--preset %s: %s" % (path, e.message))
        else:
            if not boxes:
                c, h = DEFAULT_BOX[gen]
                boxes = [self.S.Box.make(c, h)]
            self.boxes = boxes
        return host_args

    # ------------------------------------------------------------ writer
    def _bind_writer(self):
        lib = self.L.load()

        class GltfOptions(C.Structure):
            _fields_ = [("textures", C.c_int32), ("texture_size", C.c_int32), ("texture_seed", C.c_uint64),
                        ("engine_uvs", C.c_int32), ("sync", C.c_int32),  # sync 0: no fsync, as the CLI
                        ("image_dir", C.c_char_p),  # NULL: textures embedded, as the CLI
                        ("compact", C.c_int32),  # 0: plain meshes, as the CLI
                        ("texture_cache", C.c_int32), ("texture_cache_dir", C.c_char_p),
                        ("pivot_painter", C.c_int32)]  # 0: no Pivot Painter UV set, as the CLI

        class Node(C.Structure):  # banyan_gltf_node
            _fields_ = [("mesh", C.POINTER(self.S.Mesh)), ("name", C.c_char_p), ("lod_count", C.c_uint32),
                        ("lods", C.c_void_p), ("lod_coverage", C.c_void_p)]

        for name, cls in (("gltf_options", GltfOptions), ("gltf_node", Node)):
            size = getattr(lib, "banyan_sizeof_" + name)
            size.restype, size.argtypes = C.c_size_t, []
            if size() != C.sizeof(cls):
                raise UsageError("libbanyan's banyan_%s is %d bytes, the runner's %d: rebuild both from "
                                 "the same source" % (name, size(), C.sizeof(cls)))
        opt = {k: v for k, v in self.gltf.items() if k not in ("shared_textures", "format")}
        self._image_dir = self.image_dir.encode() if self.image_dir else None
        opt.setdefault("texture_cache", 1)  # the library's default: BANYAN_TEXTURE_CACHE=off still turns it off
        self._opt = GltfOptions(image_dir=self._image_dir, **opt)
        # One plain node: for glTF the bytes of banyan_gltf_write_ex, the CLI's call.
        w = lib.banyan_usd_write_nodes if self.format == "usda" else lib.banyan_gltf_write_nodes
        w.restype = C.c_int
        w.argtypes = [C.c_char_p, C.POINTER(Node), C.c_uint32, C.POINTER(GltfOptions), C.POINTER(self.S.Error)]
        self._Node, self._write = Node, w

    def seed_params(self, seed):
        p = self.params.copy()
        p.set("seed", seed)
        return p

    def name(self, seed):
        return "%s-%s-s%d" % (self.preset_name, self.preset_hash[:12], seed)

    def grow(self, params):
        """MeshData with its C mesh (call within core.mesh.capture())."""
        gen, G = self.generator, self.G
        if gen in ("avenue", "keyaki"):
            params = params.copy()
            params.set("threads", self.threads)  # the avenue's trees, or one tree's meshing; the bytes do not depend on them
            return G.avenue(params) if gen == "avenue" else G.keyaki(params)
        hosts = self.hostset if self.hostset is not None else self.boxes
        if gen == "roots":
            return G.roots(params, hosts)
        if gen == "ivy":
            params = params.copy()
            params.set("threads", self.threads)  # the meshing's threads; the bytes do not depend on them
            plant = G.IvyPlant(params, hosts)  # create, step, mesh: the CLI's calls
            try:
                plant.step(G.ivy_steps(params))  # `steps`, or the years in steps (banyan_ivy_steps)
                return plant.mesh()
            finally:
                plant.close()
        if self.segments_input is not None:
            return G.segments(params, *self.segments_input)[0]
        return G.segments(params)[0]  # the demo tree of this seed

    def write(self, d, path):
        """The CLI's bytes: one mesh named as the CLI names it, the same
        options; as .glb, or as USD text (--format usda; the CLI's with its
        image folder)."""
        node = NODE_NAME[self.generator]
        err = self.S.Error()
        n = self._Node(d.c_mesh, node.encode() if node else None, 0, None, None)
        st = self._write(os.fsencode(path), C.byref(n), 1, C.byref(self._opt), C.byref(err))
        self.L.raise_for(st, err)

    def close(self):
        if self.hostset is not None:
            self.hostset.close()
            self.hostset = None


def check(args, log):
    """--check: the preset, --host files and options as a run would take
    them; 0 when a run could start, UsageError (exit 2) otherwise."""
    if not args.preset:
        raise UsageError("--check needs --preset")
    job = Job(args)
    try:
        log("check: %s (%s) is ready: preset hash %s, names %s-s<seed>" % (
            job.preset_path, job.generator, job.preset_hash[:12], job.name(0)[:-3]))
    finally:
        job.close()
    return 0

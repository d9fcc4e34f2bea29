"""Per-generator calls: the one place that knows each generate()
signature (csrc/include/banyan/<gen>.h). Symbols are looked up on first
use; lib.load() has checked the ABI version, so a missing one is a
LoadError.
"""
import ctypes as C

from . import args as A
from . import lib as L
from . import structs as S
from .errors import BanyanError, Cancelled, LoadError
from .hostset import HostSet
from .mesh import MeshData, call_generate
from .params import Params

P = C.POINTER
_err = P(S.Error)
_mesh_out = P(P(S.Mesh))


class SegmentInput(C.Structure):
    _fields_ = [("S", C.c_double * 3), ("A", C.c_double * 3), ("l", C.c_double),
                ("n", C.c_int32), ("s", C.c_int32)]


class SegmentsStats(C.Structure):
    _fields_ = [("segments", C.c_uint32), ("lines", C.c_uint32), ("budget_hits", C.c_uint32),
                ("unattached", C.c_uint32), ("max_level", C.c_uint32), ("lines_per_level", C.c_uint32 * 8)]


def _fn(name, restype, argtypes, gen):
    f = L.symbol(name)
    if f is None:
        raise LoadError("%s() is not in the library (%s)" % (name, gen))
    f.restype = restype
    f.argtypes = argtypes
    return f


def _check_size(name, cls, gen):
    f = _fn("banyan_sizeof_" + name, C.c_size_t, [], gen)
    if f() != C.sizeof(cls):
        raise BanyanError(14, "banyan_%s: library %d bytes, add-on %d; rebuild both from the same source"
                          % (name, f(), C.sizeof(cls)), "LOAD")


class _Progress:
    """A Python progress(done: float) -> bool (True cancels) as a
    banyan_progress for one call. The ctypes callback object lives as long
    as this wrapper, i.e. the whole call. An exception raised by the
    callback cancels the generation and is raised again once the library
    has returned (never swallowed, never left to ctypes, which would only
    print it)."""

    def __init__(self, progress):
        if progress is not None and not callable(progress):
            raise TypeError("progress must be callable as progress(done) -> bool, not %s"
                            % type(progress).__name__)
        self.user = progress
        self.error = None
        self.cfn = S.PROGRESS_FN(self._call) if progress is not None else None
        self.struct = S.Progress(self.cfn, None) if progress is not None else None

    def _call(self, _user, done):
        if self.error is not None:
            return 1
        try:
            return 1 if self.user(done) else 0
        except BaseException as e:  # KeyboardInterrupt too: the C call must unwind first
            self.error = e
            return 1

    @property
    def arg(self):
        return C.byref(self.struct) if self.struct is not None else None

    def run(self, call):
        """call(progress_arg); the callback's own exception wins over the
        library's Cancelled."""
        try:
            result = call(self.arg)
        except Cancelled:
            if self.error is not None:
                raise self.error
            raise
        if self.error is not None:  # not expected: a raising callback always cancels
            raise self.error
        return result


_progress_arg = P(S.Progress)


def _boxes(hosts):
    hosts = list(hosts or [])
    arr = (S.Box * max(1, len(hosts)))()
    for i, h in enumerate(hosts):
        arr[i] = h
    return arr, len(hosts)


def _as_params(gen, params):
    if params is None:
        return Params(gen)
    if params.name != gen:
        raise BanyanError(1, "params are for '%s', not '%s'" % (params.name, gen))
    return params


def roots(params=None, hosts=(), progress=None):
    """Strangler-fig roots around hosts (banyan_roots_generate): a list
    of structs.Box (grown on a host set of them) or a hostset.HostSet (the
    real surface of its meshes). progress: None or progress(done) -> bool,
    done 0..1, True cancels (raises errors.Cancelled)."""
    params = _as_params("roots", params)
    if not isinstance(hosts, HostSet):
        with HostSet(boxes=list(hosts or [])) as hs:
            return roots(params, hs, progress)
    pr = _Progress(progress)
    f = _fn("banyan_roots_generate", C.c_int,
            [C.c_void_p, C.c_void_p, _mesh_out, C.c_void_p, _progress_arg, _err], "roots")
    return hosts.named(lambda: pr.run(lambda arg: call_generate(
        lambda out, err: f(params.ptr, hosts._live(), out, None, arg, err))))


def keyaki_stats_dict(st):
    """banyan_keyaki_stats as a dict; the per-order lists hold the orders
    1 .. max_order (stream counts) and 1 .. max_order - 1 (ratios)."""
    d = {k: getattr(st, k) for k, _ in S.KeyakiStats._fields_ if k not in ("stream_count", "bifurcation_ratio")}
    d["stream_count"] = list(st.stream_count[:st.max_order])
    d["bifurcation_ratio"] = list(st.bifurcation_ratio[:max(st.max_order - 1, 0)])
    return d


def keyaki(params=None, progress=None):
    """One keyaki tree. Returns MeshData with .stats, the measures of the
    skeleton it was built from (keyaki_stats_dict). progress: None or
    progress(done) -> bool, done 0..1, True cancels (raises
    errors.Cancelled); called on the calling thread."""
    params = _as_params("keyaki", params)
    pr = _Progress(progress)
    _check_size("keyaki_stats", S.KeyakiStats, "keyaki")
    f = _fn("banyan_keyaki_generate", C.c_int, [C.c_void_p, _mesh_out, P(S.KeyakiStats), _progress_arg, _err],
            "keyaki")
    st = S.KeyakiStats()
    d = pr.run(lambda arg: call_generate(lambda out, err: f(params.ptr, out, C.byref(st), arg, err)))
    d.stats = keyaki_stats_dict(st)
    return d


def keyaki_skeleton_stats(params=None):
    """banyan_keyaki_skeleton_stats: the skeleton grown and measured, no
    mesh (keyaki_stats_dict)."""
    params = _as_params("keyaki", params)
    _check_size("keyaki_stats", S.KeyakiStats, "keyaki")
    f = _fn("banyan_keyaki_skeleton_stats", C.c_int, [C.c_void_p, P(S.KeyakiStats), _err], "keyaki")
    st = S.KeyakiStats()
    err = S.Error()
    L.raise_for(f(params.ptr, C.byref(st), C.byref(err)), err)
    return keyaki_stats_dict(st)


def avenue(params=None, path=None, progress=None):
    """path: None (the params' start-end line) or a list of (x, y, z)
    (the library wants 2 or more, finite, consecutive ones distinct).
    The params' `threads` spreads the trees. progress: None or
    progress(done) -> bool, done 0..1, True cancels (raises
    errors.Cancelled); called on the calling thread."""
    params = _as_params("avenue", params)
    pr = _Progress(progress)
    f = _fn("banyan_avenue_generate", C.c_int,
            [C.c_void_p, P(C.c_double), C.c_uint32, _mesh_out, _progress_arg, _err], "avenue")
    pts, n = A.points("path", path) if path is not None else (None, 0)
    return pr.run(lambda arg: call_generate(lambda out, err: f(params.ptr, pts, n, out, arg, err)))


def avenue_tree_count(params, path=None):
    f = _fn("banyan_avenue_layout", C.c_int, [C.c_void_p, P(C.c_double), C.c_uint32, C.c_void_p, C.c_uint32,
                                              P(C.c_uint32), _err], "avenue")
    n = C.c_uint32(0)
    err = S.Error()
    pts, npts = A.points("path", path) if path is not None else (None, 0)
    L.raise_for(f(params.ptr, pts, npts, None, 0, C.byref(n), C.byref(err)), err)
    return n.value


def ivy_steps(params):
    """The steps the ivy grows (banyan_ivy_steps: `steps`, or the years
    turned into steps); -1 for params the check refuses."""
    return _fn("banyan_ivy_steps", C.c_int32, [C.c_void_p], "ivy")(params.ptr)


def ivy_stats_dict(st):
    """banyan_ivy_stats as a dict; "warning" is the library's sentence
    when the plant could not grow (cannot_grow != 0), else ""."""
    d = {k: getattr(st, k) for k, _ in S.IvyStats._fields_ if k != "by_state"}
    d["by_state"] = dict(zip(("A0", "A1", "A2", "D", "Z"), st.by_state))
    d["warning"] = ""
    if st.cannot_grow:
        text = _fn("banyan_ivy_growth_text", C.c_char_p, [C.c_int32], "ivy")(st.cannot_grow).decode()
        d["warning"] = "%s (%d buds after %d steps)" % (text, st.buds, st.steps)
    return d


def ivy(params=None, hosts=(), progress=None):
    """Ivy over hosts (banyan_ivy_generate): a list of structs.Box (grown
    on a host set of them) or a hostset.HostSet. Returns
    MeshData with .stats, the plant's measures (ivy_stats_dict): when
    stats["cannot_grow"] is not 0 the plant could not grow and
    stats["warning"] says why. progress: None or progress(done) -> bool,
    done 0..1, True cancels (raises errors.Cancelled)."""
    params = _as_params("ivy", params)
    pr = _Progress(progress)
    if not isinstance(hosts, HostSet):
        with HostSet(boxes=list(hosts or [])) as hs:
            return ivy(params, hs, progress)
    _check_size("ivy_stats", S.IvyStats, "ivy")
    f = _fn("banyan_ivy_generate", C.c_int,
            [C.c_void_p, C.c_void_p, _mesh_out, P(S.IvyStats), _progress_arg, _err], "ivy")
    st = S.IvyStats()
    d = hosts.named(lambda: pr.run(lambda arg: call_generate(
        lambda out, err: f(params.ptr, hosts._live(), out, C.byref(st), arg, err))))
    d.stats = ivy_stats_dict(st)
    return d


class IvyPlant(L.Handle):
    """The stepping API: create, step(n) as often as wanted, mesh(). hosts:
    a list of structs.Box (the plant grows on a host set of them that it
    frees on close) or a hostset.HostSet, which the plant keeps using:
    close the plant before the set."""

    def __init__(self, params, hosts):
        self._free = _fn("banyan_ivy_free", None, [C.c_void_p], "ivy")
        self._step = _fn("banyan_ivy_step", C.c_int, [C.c_void_p, C.c_int32, _err], "ivy")
        self._mesh = _fn("banyan_ivy_mesh", C.c_int, [C.c_void_p, _mesh_out, _err], "ivy")
        self.handle = C.c_void_p()
        self.hosts = None
        self._own = None
        if not isinstance(hosts, HostSet):
            hosts = self._own = HostSet(boxes=list(hosts or []))
        create = _fn("banyan_ivy_create", C.c_int, [C.c_void_p, C.c_void_p, P(C.c_void_p), _err], "ivy")
        self.hosts = hosts  # kept alive at least as long as the plant
        err = S.Error()
        st = create(params.ptr, hosts._live(), C.byref(self.handle), C.byref(err))
        if st:
            self.close()
            hosts.named(lambda: L.raise_for(st, err))

    def step(self, n):
        err = S.Error()
        L.raise_for(self._step(self.handle, A.int32("steps", n), C.byref(err)), err)

    def mesh(self):
        return call_generate(self._mesh, self.handle)

    def close(self):
        if self.handle:
            self._free(self.handle)
            self.handle = C.c_void_p()
        self.hosts = None
        if self._own is not None:
            self._own.close()
            self._own = None


def segments_read(text, source="<preset>"):
    """(inputs array, count, trunk or None) from a segments preset text."""
    _check_size("segment_input", SegmentInput, "segments")
    f = _fn("banyan_segments_preset_read", C.c_int,
            [C.c_char_p, C.c_size_t, C.c_char_p, P(SegmentInput), C.c_uint32, P(C.c_uint32), P(C.c_double),
             P(C.c_int32), _err], "segments")
    data = text.encode() if isinstance(text, str) else bytes(text)
    count = C.c_uint32(0)
    err = S.Error()
    L.raise_for(f(data, len(data), L.source_name(source), None, 0, C.byref(count), None, None, C.byref(err)), err)
    arr = (SegmentInput * max(1, count.value))()
    trunk = (C.c_double * 6)()
    has = C.c_int32(0)
    L.raise_for(f(data, len(data), L.source_name(source), arr, count.value, C.byref(count), trunk, C.byref(has),
                  C.byref(err)), err)
    return arr, count.value, (trunk if has.value else None)


def segments_demo(params):
    f = _fn("banyan_segments_demo", C.c_int, [C.c_void_p, P(SegmentInput), C.c_uint32, P(C.c_uint32),
                                              P(C.c_double), _err], "segments")
    cap = max(1, int(params.get("demo_segments")))
    arr = (SegmentInput * cap)()
    trunk = (C.c_double * 6)()
    count = C.c_uint32(0)
    err = S.Error()
    L.raise_for(f(params.ptr, arr, cap, C.byref(count), trunk, C.byref(err)), err)
    return arr, count.value, trunk


def segments(params=None, inputs=None, count=0, trunk=None, progress=None):
    """A segment tree (banyan_segments_generate). inputs/count/trunk from
    segments_read or segments_demo; None -> the demo tree of params.
    progress: None or progress(done) -> bool, done 0..1, True cancels
    (raises errors.Cancelled). Returns (MeshData, stats dict)."""
    params = _as_params("segments", params)
    pr = _Progress(progress)
    _check_size("segments_stats", SegmentsStats, "segments")
    if inputs is None:
        inputs, count, trunk = segments_demo(params)
    f = _fn("banyan_segments_generate", C.c_int,
            [C.c_void_p, P(SegmentInput), C.c_uint32, P(C.c_double), _mesh_out, P(SegmentsStats),
             _progress_arg, _err], "segments")
    stats = SegmentsStats()
    d = pr.run(lambda arg: call_generate(
        lambda out, err: f(params.ptr, inputs, count, trunk, out, C.byref(stats), arg, err)))
    info = {k: getattr(stats, k) for k, _ in SegmentsStats._fields_ if k != "lines_per_level"}
    info["lines_per_level"] = list(stats.lines_per_level)
    return d, info

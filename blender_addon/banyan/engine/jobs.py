"""A generator run as a Job: made on the main thread (the scene read, host
sets built), compute(progress) on any thread (the library only), build()
on the main thread (the objects, rolled back on failure, recorded as a
plant); and the helpers every run shares (progress, rollback, units)."""
import contextlib
import inspect
import math

import bpy
from mathutils import Matrix

from ..core.errors import BanyanError, Cancelled
from ..core.hostset import HostSet
from ..core.mesh import triangle_edges
from . import build_mesh as BM
from . import hosts as H
from . import plant as PL


def target_collection(collection):
    if collection is None:
        return bpy.context.scene.collection
    if not isinstance(collection, bpy.types.Collection):
        raise TypeError("collection must be a bpy.types.Collection, not %s" % type(collection).__name__)
    return collection


def check_name(name):
    if not isinstance(name, str):
        raise TypeError("name must be a string, not %s" % type(name).__name__)


def frame_number(what, value, default):
    """A frame number: finite, or the scene's when None."""
    if value is None:
        return default
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise BanyanError(12, "%s = %r must be a number" % (what, value), "BANYAN_E_TYPE")
    if not math.isfinite(f):
        raise BanyanError(2, "%s = %r must be finite" % (what, value), "BANYAN_E_RANGE")
    return f


def guard(build):
    """Runs build(created); on failure removes what it made and re-raises."""
    created = BM.Created()
    try:
        return build(created)
    except BaseException:
        created.rollback()
        raise


def single_object(name, d, collection, uv, created, origin=None):
    return [BM.object_from_mesh_data(name, d, target_collection(collection), created, uv=uv, origin=origin)]


CANCELLED = 15  # BANYAN_E_CANCELLED


def is_cancelled(e):
    return isinstance(e, BanyanError) and e.status == CANCELLED


def check_progress(progress):
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable as progress(done) -> cancel, not %s" % type(progress).__name__)


def _takes_progress(fn):
    try:
        return "progress" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def call_with_progress(fn, *args, progress=None):
    """fn(*args, progress=progress) when the binding takes one (the
    library reports ~100 steps and cancels on a True return); else fn
    runs whole, framed by progress(0.0) and progress(1.0), each of which
    may still cancel (the result is then dropped)."""
    if progress is None:
        return fn(*args)
    if _takes_progress(fn):
        return fn(*args, progress=progress)
    if progress(0.0):
        raise Cancelled()
    d = fn(*args)
    if progress(1.0):
        raise Cancelled()
    return d


class Job:
    """One generator run in three steps, so that an operator can put the
    middle one on a worker thread: made here (main thread: the scene is
    read, a host set built), compute(progress) (any thread: the library
    only, no bpy), build() (main thread: the objects, rolled back on
    failure). close() frees what the job holds (host sets); run() does
    it all. `info` holds what compute learnt (ivy: "grew")."""

    def __init__(self, compute, build, cleanup=None, whole=True, unit_scale=None):
        self._compute, self._make = compute, build
        # Metres per Blender unit of the scene the objects go to (read here, on the main thread).
        self.unit_scale = scene_unit_scale() if unit_scale is None else unit_scale
        # whole: build makes one object of the whole mesh, so its edge list
        # (triangle_edges, C) is computed in compute, off the main thread.
        self.whole = whole
        self.stack = contextlib.ExitStack()
        if cleanup is not None:
            self.stack.push(cleanup)
        self.data = None
        self.info = {}
        self.finishers = []  # fn(objs, created) after build, in its rollback (wind, growth setups)
        self.plant = None  # (generator, host objects, options): what build records on the plant (recorded)

    def adopt(self, stack_or_cm):
        """Ties a context manager (or ExitStack) to the job's lifetime."""
        self.stack.enter_context(stack_or_cm)
        return self

    def compute(self, progress=None):
        check_progress(progress)
        d = self._compute(progress)
        if self.whole and d is not None and getattr(d, "indices", None) is not None \
                and not getattr(d, "instances", None):
            d.topology = triangle_edges(d.indices, len(d.positions) // 3)
        self.data = d
        return self

    def _build(self, d, created):
        """The objects of d (build's), in the scene's units (from_metres)."""
        objs = self._make(d, created)
        from_metres(objs, self.unit_scale)
        return objs

    def build(self):
        if self.data is None:
            raise BanyanError(1, "the job has not computed yet", "BANYAN_E_INVALID_ARG")
        return guard(lambda c: self._finish(self._build(self.data, c), c))

    def _finish(self, objs, created):
        for fn in self.finishers:
            fn(objs, created)
        if self.plant is not None:
            # Kept on the plant as an operator keeps it: Regenerate, Make LODs and the Plant panel work on it.
            gen, hosts, options = self.plant
            PL.record(objs, gen, self.params, hosts, options)
        return objs

    def close(self):
        self.stack.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def run(self, progress=None):
        with self:
            self.compute(progress)
            return self.build()


def scene_unit_scale():
    """Metres per Blender unit of the current scene (hosts.unit_scale)."""
    return H.unit_scale(bpy.context.scene)


def from_metres(objs, scale):
    """The library's objects (world metres) in Blender units of `scale`
    metres: scaled about the world origin, so their meshes, wind and
    growth data stay the library's, in metres of object space."""
    if scale == 1.0:
        return
    m = Matrix.Scale(1.0 / scale, 4)
    # Objects an instancer among objs shows (an instanced avenue's
    # variants) are scaled through it.
    shown = {c.name for o in objs if o.instance_type == 'COLLECTION' and o.instance_collection
             for c in o.instance_collection.all_objects}
    for o in objs:
        if o.parent is None and o.name not in shown:
            o.matrix_basis = m @ o.matrix_basis  # matrix_world may not be evaluated yet


def recorded(job, gen, options, hosts=()):
    """job, set to record what it builds (plant.record: the generator, its
    params, the host objects among `hosts`, options as regenerate.build_job
    reads them) so that the plant can be regenerated and edited."""
    if isinstance(hosts, HostSet):
        hosts = getattr(hosts, "objects", ())  # a set made by hosts.surface_host_set
    objs = [h for h in hosts or () if isinstance(h, bpy.types.Object)]
    job.plant = (gen, objs, dict(options))
    return job


def prepared(prepare):
    """Calls prepare(stack) -> Job with an ExitStack that the job adopts;
    on failure the stack is closed (host sets freed)."""
    stack = contextlib.ExitStack()
    try:
        job = prepare(stack)
    except BaseException:
        stack.close()
        raise
    return job.adopt(stack)

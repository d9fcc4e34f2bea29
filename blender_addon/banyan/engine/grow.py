"""One Job per generator (see jobs.py): the parameters (add-on defaults,
preset, values), the hosts or path, and how its mesh becomes objects.
api.py runs them; the operators and Regenerate prepare them."""
from collections.abc import Mapping
import inspect
import json

import bpy

from ..core import generators as G
from ..core import presets as PR
from ..core.errors import BanyanError
from ..core.params import Params
from . import build_mesh as BM
from . import growth_anim as GA
from . import hosts as H
from . import props as PP
from . import wind as W
from .instances import build_instanced
from .jobs import Job, call_with_progress, check_name, frame_number, prepared, recorded, scene_unit_scale, single_object, target_collection
from .placement import (curve_points, ground_wanted, host_arg, hosted_options, hosts_list, origin_point,
                        set_ground_at_hosts, set_roots_germination, translation)
from .setups import setups


def make_params(gen, preset=None, params=None, values=None, **kw):
    """Params of gen: the add-on's defaults (props.addon_params: the
    library's, wind data off), then the preset, then values and kw."""
    if params is not None and not isinstance(params, Params):
        raise TypeError("params must be a banyan.core.params.Params, not %s" % type(params).__name__)
    if values is not None and not isinstance(values, Mapping):
        raise TypeError("values must be a mapping of parameter names to values, not %s" % type(values).__name__)
    p = params.copy() if params is not None else PP.addon_params(gen)
    if preset:
        path = PR.find(gen, preset)
        p.apply_preset(PR.read(path), path)
    for k, v in dict(values or {}, **{k.replace("__", "."): v for k, v in kw.items()}).items():
        if not isinstance(k, str):
            raise TypeError("parameter names are strings, not %r" % (k,))
        p.set(k, v)
    return p


def strangler_roots_job(hosts=(), *, preset=None, params=None, germination=None, collection=None,
                        name="Banyan Roots", uv=True, host_shape=H.SURFACE, origin='BASE', values=None, wind=None,
                        animate=False, frame_start=None, frame_end=None, ground_at_hosts=None, **kw):
    """strangler_roots as a Job (see Job). wind, animate, frame_start,
    frame_end: the wind and growth setups (setups); ground_at_hosts: see
    the module docstring (The ground)."""
    target_collection(collection)
    check_name(name)
    p = make_params("roots", preset, params, values, **kw)
    if germination is not None:
        set_roots_germination(p, germination)
    hosts = hosts_list(hosts)
    ground = ground_wanted(ground_at_hosts, "roots", hosts, preset, params, values, kw)
    scale = scene_unit_scale()

    def prepare(stack):
        arg, named, base = host_arg("roots", hosts, host_shape, preset, stack, scale)
        if ground:
            set_ground_at_hosts("roots", p, arg, preset)
        o = origin_point(origin, base if base is not None else p.get("germination"))
        return Job(lambda prog: named(lambda: call_with_progress(G.roots, p, arg, progress=prog)),
                   lambda d, c: single_object(name, d, collection, uv, c, o), unit_scale=scale)
    job = prepared(prepare)
    job.params = p
    recorded(job, "roots", hosted_options("strangler_roots", hosts, host_shape, preset, uv), hosts)
    return setups(job, "roots", wind, animate, frame_start, frame_end)


def keyaki_tree_job(*, preset=None, params=None, position=None, collection=None, name="Keyaki", uv=True,
                    origin='BASE', values=None, wind=None, animate=False, frame_start=None, frame_end=None, **kw):
    target_collection(collection)
    check_name(name)
    p = make_params("keyaki", preset, params, values, **kw)
    if position is not None:
        p.set("position", position)
    foot = p.get("position")
    o = origin_point(origin, foot)
    local = p
    if o is not None:
        # Grown at the world origin and placed: the library's tree moves
        # with its position (checked to float precision), so the mesh is
        # local to the foot without losing digits far from the origin.
        local = p.copy()
        local.set("position", (0.0, 0.0, 0.0))

    def build(d, c):
        objs = single_object(name, d, collection, uv, c)
        if o is not None:
            if o != foot:  # an explicit origin: the mesh moves so that the foot stays at `position`
                W.transform_mesh(objs[0].data, translation(tuple(foot[k] - o[k] for k in range(3))))
            objs[0].location = o
        return objs
    job = Job(lambda prog: call_with_progress(G.keyaki, local, progress=prog), build)
    job.params = p
    recorded(job, "keyaki", {"api": "keyaki_tree", "uv_map": bool(uv),
                              "origin": origin if origin is not None else 'WORLD'})
    if wind is not None:
        local.set("wind", bool(wind))
    return setups(job, "keyaki", wind, animate, frame_start, frame_end)


def avenue_progress(progress):
    """(generation progress, object-building progress): progress(done) ->
    cancel for the whole run, or the earlier progress(done, total) called
    as objects are built."""
    if progress is None:
        return None, None
    try:
        inspect.signature(progress).bind(0.5)
        return progress, None
    except TypeError:
        return None, progress
    except ValueError:  # no signature (a builtin): the one-argument form
        return progress, None


def keyaki_avenue_job(*, path=None, preset=None, params=None, merged=False, collection=None,
                      name="Keyaki Avenue", uv=True, origin='BASE', build_progress=None, values=None,
                      wind=None, animate=False, frame_start=None, frame_end=None, **kw):
    target_collection(collection)
    check_name(name)
    if build_progress is not None and not callable(build_progress):
        raise TypeError("progress must be callable as progress(done, total), not %s" % type(build_progress).__name__)
    p = make_params("avenue", preset, params, values, **kw)
    curve = path if isinstance(path, bpy.types.bpy_struct) else None
    scale = scene_unit_scale()
    if curve is not None:
        path = [tuple(c * scale for c in q) for q in curve_points(curve)]  # in metres, as the library's
    elif path is not None and (isinstance(path, (str, bytes)) or not hasattr(path, "__iter__")):
        raise TypeError("path must be a curve object or a list of (x, y, z), not %s" % type(path).__name__)
    path = list(path) if path is not None else None
    start = tuple(path[0]) if path else p.get("start")

    def compute(prog):
        try:
            return call_with_progress(G.avenue, p, path, progress=prog)
        except BanyanError as e:
            if curve is not None and e.message.startswith("path"):
                raise BanyanError(e.status, "curve '%s': %s" % (curve.name, e.message), e.name) from None
            raise

    def build(d, created):
        parent = target_collection(collection)
        if getattr(d, "instances", None):
            return build_instanced(name, d, parent, created, uv=uv, progress=build_progress)
        if merged:
            return single_object(name, d, parent, uv, created, origin_point(origin, start))
        coll = created.add(bpy.data.collections.new(name))
        objs = BM.objects_per_group(name, d, coll, created, uv=uv, progress=build_progress)
        # Joins the scene once its trees are in: Blender syncs the view
        # layers once, not once per tree.
        parent.children.link(coll)
        return objs
    job = Job(compute, build, whole=merged, unit_scale=scale)
    job.params = p
    opts = {"api": "keyaki_avenue", "uv_map": bool(uv), "merged": bool(merged)}
    if curve is not None:
        opts.update(path_from='CURVE', path=curve)
    elif path is not None:
        opts.update(path_from='POINTS', path=path)
    else:
        opts["path_from"] = 'PARAMS'
    recorded(job, "avenue", opts)
    return setups(job, "avenue", wind, animate, frame_start, frame_end)


def ivy_job(hosts=(), *, preset=None, params=None, start=None, steps=None, collection=None, name="Ivy", uv=True,
            animate=False, frame_start=None, frame_end=None, host_shape=H.SURFACE, origin='BASE', values=None,
            wind=None, ground_at_hosts=None, **kw):
    target_collection(collection)
    check_name(name)
    sc = bpy.context.scene
    f0, f1 = frame_number("frame_start", frame_start, sc.frame_start), frame_number("frame_end", frame_end, sc.frame_end)
    p = make_params("ivy", preset, params, values, **kw)
    if start is not None:
        p.set("start", start)
    if steps is not None:
        p.set("steps", steps)
    hosts = hosts_list(hosts)
    ground = ground_wanted(ground_at_hosts, "ivy", hosts, preset, params, values, kw)
    scale = scene_unit_scale()

    def prepare(stack):
        arg, named, base = host_arg("ivy", hosts, host_shape, preset, stack, scale)
        if ground:
            set_ground_at_hosts("ivy", p, arg, preset)
        o = origin_point(origin, base if base is not None else p.get("start"))

        def compute(prog):
            d = named(lambda: call_with_progress(G.ivy, p, arg, progress=prog))
            job.info["grew"] = ivy_grew(d)
            return d

        def build(d, created):
            objs = single_object(name, d, collection, uv, created, o)
            if animate:
                GA.add_growth_modifier(objs[0], created, max(1, G.ivy_steps(p)), f0, f1)
            return objs
        job = Job(compute, build, unit_scale=scale)
        return job
    if wind is not None:
        p.set("wind", bool(wind))
    job = prepared(prepare)
    job.params = p
    recorded(job, "ivy", hosted_options("ivy", hosts, host_shape, preset, uv), hosts)
    return setups(job, "ivy", wind)


def ivy_grew(d):
    """False when the ivy could not grow: the library's verdict
    (banyan_ivy_stats' cannot_grow, in the MeshData's stats)."""
    stats = getattr(d, "stats", None) or {}
    return not stats.get("cannot_grow", 0)


def _has_key(text, key):
    try:
        doc = json.loads(text)
    except ValueError:
        return True  # let the library report the syntax error with its line
    return isinstance(doc, dict) and key in doc


def segment_twigs_job(*, preset=None, params=None, collection=None, name="Segment Twigs", uv=True, values=None,
                      wind=None, **kw):
    target_collection(collection)
    check_name(name)
    p = make_params("segments", preset, params, values, **kw)
    inputs = None
    count, trunk = 0, None
    if preset:
        path = PR.find("segments", preset)
        text = PR.read(path)
        if _has_key(text, "segments"):
            inputs, count, trunk = G.segments_read(text, path)
    job = Job(lambda prog: G.segments(p, inputs, count, trunk, progress=prog)[0],
              lambda d, c: single_object(name, d, collection, uv, c))
    job.params = p
    recorded(job, "segments", {"api": "segment_twigs", "uv_map": bool(uv), "banyan_preset": preset})
    return setups(job, "segments", wind)

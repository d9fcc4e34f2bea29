"""Regenerate: a plant rebuilt in place from what it keeps (plant.py:
params, hosts, options), through the same Jobs as a first run
(grow.py)."""
import contextlib

import bpy

from ..core import generators as G
from ..core.errors import BanyanError
from . import grow
from . import hosts as H
from . import materials as MAT
from . import plant as PL
from . import wind as W
from .placement import host_arg


def _hosts(obj):
    hosts = []
    for name, h in PL.host_status(obj):
        if h is None:
            raise BanyanError(3, "host '%s' of '%s' was deleted; select new hosts and add the plant again"
                              % (name, obj.name), "BANYAN_E_NO_HOSTS")
        hosts.append(h)
    return hosts


def build_job(obj, params, coll):
    """The api Job that builds obj's plant anew into coll (linked to no
    scene): what Regenerate runs, and what make_lods computes to get the
    library's mesh (core.mesh.capture)."""
    pl = obj.banyan_plant
    gen = pl.generator
    opt = PL.options(obj)
    uv = bool(opt.get("uv_map", True))
    shape = opt.get("host_shape", H.SURFACE)
    if gen in PL.HOSTED:
        make = grow.strangler_roots_job if gen == "roots" else grow.ivy_job
        with contextlib.ExitStack() as stack:
            hosts = _hosts(obj)
            if not hosts and opt.get("preset_hosts"):
                # Grown by banyan.api on a preset's own hosts (its boxes and meshes).
                hosts = host_arg(gen, (), shape, opt["preset_hosts"], stack)[0]
            job = make(hosts=hosts, params=params, collection=coll, uv=uv, host_shape=shape)
            return job.adopt(stack.pop_all())
    if gen == "keyaki":
        return grow.keyaki_tree_job(params=params, collection=coll, uv=uv, origin=opt.get("origin", 'BASE'))
    if gen == "avenue":
        path = None
        if opt.get("path_from") == 'CURVE':
            path = pl.path
            if path is None or not path.users_scene:
                raise BanyanError(1, "the avenue's curve was deleted; add the avenue again", "BANYAN_E_INVALID_ARG")
        elif opt.get("path_points"):
            path = [tuple(q) for q in opt["path_points"]]
        return grow.keyaki_avenue_job(path=path, params=params, merged=bool(opt.get("merged", False)),
                                     collection=coll, uv=uv)
    if gen == "segments":
        key = opt.get("banyan_preset")
        return grow.segment_twigs_job(preset=key if key and key != "NONE" else None, params=params,
                                     collection=coll, uv=uv)
    raise BanyanError(13, "'%s': generator '%s' cannot be regenerated" % (obj.name, gen), "BANYAN_E_UNSUPPORTED")


def _build(obj, params, coll):
    """The plant's objects built anew into coll (linked to no scene)."""
    if obj.banyan_plant.generator == "avenue" and "variants" in params.by_name and params.get("variants"):
        raise BanyanError(13, "'%s': an instanced avenue (variants %d) cannot be regenerated in place yet; add it "
                          "again" % (obj.name, params.get("variants")), "BANYAN_E_UNSUPPORTED")
    job = build_job(obj, params, coll)
    job.plant = None  # regenerate() records the plant's own objects, not these temporary ones
    return job.run()


def _remove_tree(coll):
    """Removes a temporary collection and its children (emptied before)."""
    for c in list(coll.children):
        _remove_tree(c)
    bpy.data.collections.remove(coll)


def _is_identity(m, eps=1e-12):
    return all(abs(m[i][j] - (1.0 if i == j else 0.0)) <= eps for i in range(4) for j in range(4))


def _keep_slots(new_me, old_me):
    """new_me gets old_me's material slots as they are (the artist's
    materials); slots the library has beyond them follow. A slot still
    holding a shared library material (materials.py) takes the new one,
    so a changed season swaps it; a material the artist put there stays."""
    lib_mats = list(new_me.materials)
    new_me.materials.clear()
    for i, m in enumerate(old_me.materials):
        if MAT.is_shared(m) and i < len(lib_mats) and MAT.is_shared(lib_mats[i]):
            m = lib_mats[i]
        new_me.materials.append(m)
    for m in lib_mats[len(old_me.materials):]:
        new_me.materials.append(m)


def _swap_mesh(obj, new_me, to_local=None):
    """Gives obj the mesh new_me (material slots kept, coordinates moved
    by to_local); the old mesh is removed when nothing else uses it, and
    its name passes to new_me."""
    old = obj.data
    _keep_slots(new_me, old)
    if to_local is not None and not _is_identity(to_local):
        W.transform_mesh(new_me, to_local)
    obj.data = new_me
    if old.users == 0:
        name = old.name
        bpy.data.meshes.remove(old)
        new_me.name = name


def _update_growth(obj, params):
    """The ivy growth modifier's last step follows a changed `steps` or
    `years`."""
    if "steps" not in params.by_name:
        return
    last = float(max(1, G.ivy_steps(params)))
    for mod in obj.modifiers:
        ng = getattr(mod, "node_group", None)
        if mod.type == 'NODES' and ng is not None and ng.name.startswith("Banyan Ivy Growth"):
            for n in ng.nodes:
                if n.bl_idname == 'ShaderNodeMapRange':
                    n.inputs["To Max"].default_value = last


def regenerate(obj, params=None):
    """Rebuilds obj's plant in place (every tree of its avenue) from its
    stored params with the sidebar's edits (or `params`) and its current
    hosts. Returns the plant's objects. On any error raises with nothing
    changed."""
    if not PL.is_plant(obj):
        raise BanyanError(1, "'%s' is not a Banyan plant" % getattr(obj, "name", obj), "BANYAN_E_INVALID_ARG")
    pl = obj.banyan_plant
    gen = pl.generator
    p = params if params is not None else PL.current_params(obj)
    old = PL.members(obj)
    opts = PL.options(obj)
    if pl.path is not None:
        opts["path"] = pl.path
    hosts = [h for _n, h in PL.host_status(obj)]
    first = old[min(old)]
    home = next(iter(first.users_collection), None)
    coll = bpy.data.collections.new("banyan_regenerate")
    made_mats = set()
    had_mats = set(bpy.data.materials)  # shared materials are reused: only new ones may be left unused
    keep, frames = [], {}
    try:
        new = _build(obj, p, coll)
        for o in new:
            made_mats.update(m for m in o.data.materials if m is not None and m not in had_mats)
        for i, o in enumerate(new):
            built = o.matrix_basis.copy()
            target = old.get(i)
            if target is None:
                # The avenue grew a tree more: it joins the others, with their materials.
                _keep_slots(o.data, first.data)
                for c in list(o.users_collection):
                    c.objects.unlink(o)
                (home or bpy.context.scene.collection).objects.link(o)
                keep.append(o)
                continue
            if gen in PL.HOSTED:
                # Grown where the hosts are now, seen from where the object is now.
                _swap_mesh(target, o.data, target.matrix_world.inverted_safe() @ built)
                if gen == "ivy":
                    _update_growth(target, p)
            elif gen in PL.FOLLOWS:
                # Where the generator puts it now (a tree of a changed avenue), moved as the artist moved it.
                was = PL._matrix(target.banyan_plant.frame)
                _swap_mesh(target, o.data)
                mw = target.matrix_world @ was.inverted_safe() @ built
                if not _is_identity(mw.inverted_safe() @ target.matrix_world):
                    target.matrix_world = mw
                frames[target.name] = PL._matrix_json(built)
            else:
                # A tree or twigs: the object's transform is where it stands; the mesh is the generator's, local.
                _swap_mesh(target, o.data)
            keep.append(target)
        for i, o in old.items():
            if i >= len(new):  # the avenue has fewer trees now
                me = o.data
                bpy.data.objects.remove(o)
                if me is not None and me.users == 0:
                    bpy.data.meshes.remove(me)
    finally:
        # The temporary objects (their meshes live on in the plant), or all of a failed build.
        for o in list(coll.all_objects):
            me = o.data
            bpy.data.objects.remove(o)
            if me is not None and me.users == 0:
                bpy.data.meshes.remove(me)
        _remove_tree(coll)
        for m in made_mats:
            if m.users == 0:
                bpy.data.materials.remove(m)
    PL.record(keep, gen, p, hosts, opts)
    for o in keep:
        if o.name in frames:
            o.banyan_plant.frame = frames[o.name]
    return keep

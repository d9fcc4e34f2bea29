"""Levels of detail in Blender: make_lods(obj) grows obj's plant again
from what it keeps (plant.py: params, hosts, options), hands the
library's mesh to banyan_mesh_lod (banyan/lod.h) for each ratio and, for
trees, for the crossed billboard cards, and puts the levels in a
collection "<name> LODs": <name>_LOD0 (obj's own mesh, shared), _LOD1 ..
in ratio order, then the billboard (its picture packed as an image). The
levels stand where obj stands (its world matrix; a plant on hosts seen
from where obj is now, as Regenerate does). obj's wind and growth
modifiers are copied onto the levels that carry the attributes."""
import bpy

from . import nodes as N
from . import plant as PL
from . import wind as W
from ..core import mesh as M
from ..core.errors import BanyanError
from .jobs import guard
from .regenerate import build_job

TREES = ("keyaki", "avenue")  # plants that get billboard cards by default


def _copy_modifiers(src, dst):
    for m in src.modifiers:
        if m.type != 'NODES' or m.node_group is None:
            continue
        needs_wind = m.node_group.get(W.GROUP_KEY) is not None
        if needs_wind and not W.has_wind(dst.data):
            continue
        if not needs_wind and "birth" not in dst.data.attributes and m.node_group.get("banyan_growth") is not None:
            continue
        n = dst.modifiers.new(m.name, 'NODES')
        n.node_group = m.node_group
        N.copy_inputs(m, n)


def _level_object(name, d, coll, created, job, obj, index):
    """An object of LOD MeshData d where obj stands: built by the plant's
    own job (placed as the first build was), then moved into obj's frame."""
    built = job._build(d, created)
    src = built[index if index < len(built) else 0]
    me = src.data
    pl = obj.banyan_plant
    where = obj.matrix_world.copy()
    built_at = src.matrix_basis.copy()  # a new object's matrix_world waits for the depsgraph; it has no parent
    if pl.generator in PL.HOSTED:
        W.transform_mesh(me, obj.matrix_world.inverted_safe() @ built_at)
    elif pl.generator in PL.FOLLOWS:  # as Regenerate: where the generator put it, moved as the artist moved it
        where = obj.matrix_world @ PL._matrix(pl.frame).inverted_safe() @ built_at
    for o in built:
        for c in list(o.users_collection):
            c.objects.unlink(o)
    for o in built:
        if o is not src:
            bpy.data.objects.remove(o)
    me.name = name
    src.name = name
    src.matrix_world = where
    coll.objects.link(src)
    return src


def make_lods(obj, ratios=(0.5, 0.15), billboard=None, billboard_size=256, collection=None):
    """The LOD collection of obj (a Banyan plant): returns the objects,
    LOD0 first. ratios: shares of the triangles kept, falling, each within
    [0.001, 1) (each level is made from the one before, as the CLI's --lod);
    billboard: crossed cards as the last level (default: for trees).
    Raises BanyanError (nothing left behind) for a non-plant, bad ratios
    or a library error."""
    if not PL.is_plant(obj):
        raise BanyanError(1, "'%s' is not a Banyan plant (make_lods grows it again from its parameters)"
                          % getattr(obj, "name", obj), "BANYAN_E_INVALID_ARG")
    try:
        ratios = [float(r) for r in ratios]
    except (TypeError, ValueError):
        raise BanyanError(12, "ratios must be falling numbers within [0.001, 1), not %r" % (ratios,), "BANYAN_E_TYPE")
    # Checked before the plant is grown again; banyan_mesh_lods checks the same.
    for i, r in enumerate(ratios):
        if not 0.001 <= r < (ratios[i - 1] if i else 1.0):
            raise BanyanError(2, "ratios[%d] = %r must be within [0.001, 1) and below the ratio before it" % (i, r),
                              "BANYAN_E_RANGE")
    pl = obj.banyan_plant
    if billboard is None:
        billboard = pl.generator in TREES
    parent = collection or (obj.users_collection[0] if obj.users_collection else bpy.context.scene.collection)
    params = PL.stored_params(obj)
    base = obj.name
    if obj.name in bpy.context.view_layer.objects:
        bpy.context.view_layer.update()  # obj.matrix_world after a move made by a script

    def build(created):
        coll = created.add(bpy.data.collections.new("%s LODs" % base))
        lod0 = created.add(obj.copy())  # shares obj's mesh: LOD0 is the plant as it is
        lod0.name = "%s_LOD0" % base
        if PL.is_plant(lod0):
            lod0.banyan_plant.schema = 0  # a copy of the plant's mesh, not a second plant to regenerate
        coll.objects.link(lod0)
        out = [lod0]
        with M.capture():
            tmp = created.add(bpy.data.collections.new("banyan_lod_build"))
            with build_job(obj, params, tmp) as job:
                job.compute()
                full = job.data
                levels = M.lods(full, ratios, billboard=billboard, size=billboard_size)
                index = pl.index if pl.group else 0
                for k, d in enumerate(levels, start=1):
                    o = _level_object("%s_LOD%d" % (base, k), d, coll, created, job, obj, index)
                    created.add(o)
                    created.add(o.data)
                    _copy_modifiers(obj, o)
                    o["banyan_lod"] = k
                    out.append(o)
            bpy.data.collections.remove(tmp)
        parent.children.link(coll)
        lod0["banyan_lod"] = 0
        return out

    return guard(build)

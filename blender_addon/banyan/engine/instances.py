"""An instanced avenue in Blender: the library's variants (banyan_mesh
parts of group g = variant g, standing at the frame's origin) become one
object each, in a collection per variant under "<name> variants"
(excluded from the view layers: seen only through the instances), and
each banyan_instance one empty instancing its variant's collection,
turned by rotation_z, scaled and moved to the mesh origin + translation.

Bulk: the empties go into the avenue's collection before that collection
joins the scene, so Blender syncs its view layers once, not once per
empty, and each gets a unique name of its own (no name search)."""
import bpy

from . import build_mesh as BM


def _exclude(coll):
    """Excludes coll from every view layer that shows it."""
    def find(lc):
        if lc.collection == coll:
            return lc
        for c in lc.children:
            r = find(c)
            if r is not None:
                return r
        return None
    for sc in bpy.data.scenes:
        for vl in sc.view_layers:
            lc = find(vl.layer_collection)
            if lc is not None:
                lc.exclude = True


def build_instanced(name, d, parent, created, *, uv=True, progress=None):
    """Variant objects and instance empties of MeshData d (with
    instances) under a new collection `name` linked to parent. Returns
    the variant objects, then the empties in instance order."""
    coll = created.add(bpy.data.collections.new(name))
    vroot = created.add(bpy.data.collections.new("%s variants" % name))
    coll.children.link(vroot)
    groups = list(d.groups())
    vcolls = {}
    for g in groups:
        c = created.add(bpy.data.collections.new("%s variant %d" % (name, g)))
        vroot.children.link(c)
        vcolls[g] = c
    variants = BM.objects_per_group("%s_variant" % name, d, vroot, created, uv=uv, frame_local=True,
                                    collections=vcolls)
    mo = getattr(d, "origin", (0.0, 0.0, 0.0))
    empties = []
    n = len(d.instances)
    objs_new = bpy.data.objects.new
    link = coll.objects.link
    for i, (v, t, rz, s) in enumerate(d.instances):
        e = created.add(objs_new("%s_%05d" % (name, i), None))
        e.instance_type = 'COLLECTION'
        e.instance_collection = vcolls[v]
        e.location = BM.as_location((mo[0] + t[0], mo[1] + t[1], mo[2] + t[2]))
        if rz:
            e.rotation_euler[2] = rz
        if s != 1.0:
            e.scale = (s, s, s)
        link(e)
        empties.append(e)
        if progress and (i + 1) % 1000 == 0:
            progress(i + 1, n)
    parent.children.link(coll)
    _exclude(vroot)
    if progress:
        progress(n, n)
    return variants + empties


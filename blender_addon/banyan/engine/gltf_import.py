"""A user extension of Blender's stock glTF importer (io_scene_gltf2) for
the files banyan writes (asset.generator "banyan", docs/gltf.md).

The importer looks for a class `glTF2ImportUserExtension` on the module of
every enabled add-on (a legacy add-on's `banyan`, the extension's
`bl_ext.<repo>.banyan`) and calls its hooks. On a banyan file this one:
  - turns the custom attributes into the add-on's own: the pivot's three
    scalars _WIND_PIVOT_X/_Y/_Z (glTF's axes, like POSITION) into
    `wind_pivot`, a FLOAT_VECTOR in Blender's frame converted as the
    importer converts positions, and every other `_NAME` into `name`
    (wind_level, ..., birth: what Add Wind and the growth animation read).
    Importers that keep no custom attributes (Blender 3.4's) get them from
    the file's accessors, in the importer's vertex order;
  - removes the coarser MSFT_lod levels: glTF-Blender-IO does not read
    MSFT_lod and makes an object of every node, those outside the scene
    too, so the levels would stand on top of each other.
Other files are left as the importer made them. Nothing here runs
without the importer, which brings numpy.
"""

GENERATOR = "banyan"
PIVOT = ("_WIND_PIVOT_X", "_WIND_PIVOT_Y", "_WIND_PIVOT_Z")
VECTOR = "wind_pivot"  # wind.PIVOT


def is_banyan(gltf):
    asset = getattr(gltf.data, "asset", None)
    gen = getattr(asset, "generator", None) or ""
    return gen == GENERATOR or gen.startswith(GENERATOR + " ")


def _custom_names(pymesh):
    names = []
    for prim in pymesh.primitives:
        for k in prim.attributes or {}:
            if k.startswith("_") and k not in names:
                names.append(k)
    return names


def _used_vertices(gltf, pymesh):
    """[(primitive, the file's vertices its triangles use, sorted)] for the
    primitives with POSITION: the vertices the importer keeps, primitive
    after primitive, when it does not merge vertices."""
    import numpy as np
    from io_scene_gltf2.io.imp.gltf2_io_binary import BinaryData
    out = []
    for prim in pymesh.primitives:
        if "POSITION" not in (prim.attributes or {}):
            continue
        if prim.indices is not None:
            idx = BinaryData.decode_accessor(gltf, prim.indices).reshape(-1)
        else:
            idx = np.arange(gltf.data.accessors[prim.attributes["POSITION"]].count)
        out.append((prim, np.unique(idx)))
    return out


def _from_accessors(gltf, used, name, n):
    """Attribute `name` per vertex of the imported mesh, from the file's
    accessors; None when that is not n vertices."""
    import numpy as np
    from io_scene_gltf2.io.imp.gltf2_io_binary import BinaryData
    out = []
    for prim, u in used:
        if name in prim.attributes:
            data = BinaryData.decode_accessor(gltf, prim.attributes[name]).reshape(-1)
            out.append(data[u].astype(np.float32))
        else:
            out.append(np.zeros(len(u), np.float32))
    if not out:
        return None
    a = np.concatenate(out)
    return a if len(a) == n else None


def _values(gltf, used, mesh, name):
    """The values of custom attribute `name` per vertex: the importer's
    attribute (removed), or, when it kept none, the file's."""
    import numpy as np
    n = len(mesh.vertices)
    a = mesh.attributes.get(name)
    if a is not None and a.domain == 'POINT' and a.data_type == 'FLOAT':
        out = np.empty(n, np.float32)
        a.data.foreach_get("value", out)
        mesh.attributes.remove(mesh.attributes[name])
        return out
    try:
        if not used:
            used.extend(_used_vertices(gltf, used.pymesh))
        return _from_accessors(gltf, used, name, n)
    except Exception:  # an importer whose modules moved: leave the mesh as it is
        return None


class _Used(list):
    def __init__(self, pymesh):
        super().__init__()
        self.pymesh = pymesh


def convert_mesh(gltf, pymesh, mesh):
    """The banyan attributes of one imported mesh under the add-on's names
    (once, when two copies of the add-on are enabled)."""
    import numpy as np
    done = gltf.__dict__.setdefault("banyan_converted", set())
    names = _custom_names(pymesh)
    if not names or mesh.as_pointer() in done:
        return
    done.add(mesh.as_pointer())
    used = _Used(pymesh)  # filled on first need
    vals = {k: _values(gltf, used, mesh, k) for k in names}
    vals = {k: v for k, v in vals.items() if v is not None}
    if all(k in vals for k in PIVOT):
        piv = np.stack([vals.pop(k) for k in PIVOT], axis=1).astype(np.float32)
        gltf.locs_batch_gltf_to_blender(piv)
        if VECTOR in mesh.attributes:
            mesh.attributes.remove(mesh.attributes[VECTOR])
        mesh.attributes.new(VECTOR, 'FLOAT_VECTOR', 'POINT').data.foreach_set("vector", piv.reshape(-1))
    for k, v in vals.items():
        name = k[1:].lower()
        if name in mesh.attributes:
            name = "banyan_" + name
        mesh.attributes.new(name, 'FLOAT', 'POINT').data.foreach_set("value", v)


def coarser_levels(gltf):
    """Node indices that MSFT_lod lists as coarser levels of another node."""
    out = set()
    for node in gltf.data.nodes or []:
        ext = (getattr(node, "extensions", None) or {}).get("MSFT_lod")
        if isinstance(ext, dict):
            out.update(i for i in ext.get("ids", []) if isinstance(i, int))
    return out


def remove_coarser_levels(gltf):
    """Removes the objects of the coarser levels and their nodes from the
    importer's node tree (it selects every node's object afterwards)."""
    import bpy
    if gltf.__dict__.setdefault("banyan_levels_removed", False):
        return
    gltf.banyan_levels_removed = True
    vnodes = getattr(gltf, "vnodes", None) or {}
    ids, stack = [], [i for i in sorted(coarser_levels(gltf)) if i in vnodes]  # the levels and their subtrees
    while stack:
        i = stack.pop()
        if i in vnodes and i not in ids:
            ids.append(i)
            stack.extend(getattr(vnodes[i], "children", None) or [])
    objs = {}
    for i in ids:
        ob = getattr(vnodes[i], "blender_object", None)
        if ob is not None:
            objs[ob.name] = ob
    meshes = {ob.data.name: ob.data for ob in objs.values() if ob.type == 'MESH'}
    # glTF-Blender-IO 4.5+ puts the nodes outside the scene in a collection
    # of their own ("Orphan Nodes", excluded from the view layer when the
    # scene is imported as a collection), removed here once empty.
    colls = {c.name: c for ob in objs.values() for c in ob.users_collection if c.name.startswith("Orphan Nodes")}
    for ob in objs.values():
        bpy.data.objects.remove(ob)
    for me in meshes.values():
        if me.users == 0:
            bpy.data.meshes.remove(me)
    known = getattr(gltf, "blender_collections", None) or {}
    for c in colls.values():
        if not c.all_objects and not c.children:
            for k in [k for k, v in known.items() if v == c]:
                del known[k]
            bpy.data.collections.remove(c)
    for i in ids:
        parent = vnodes.get(getattr(vnodes[i], "parent", None))
        if parent is not None and i in (parent.children or []):
            parent.children.remove(i)
    for i in ids:
        del vnodes[i]


class glTF2ImportUserExtension:
    def gather_import_mesh_after_hook(self, pymesh, mesh, gltf):
        if is_banyan(gltf):
            convert_mesh(gltf, pymesh, mesh)

    def gather_import_scene_after_nodes_hook(self, gltf_scene, blender_scene, gltf):
        if is_banyan(gltf):
            remove_coarser_levels(gltf)

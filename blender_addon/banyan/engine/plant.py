"""Edit later: a built plant keeps on its object what it was grown from
(generator, the full params, seed, host objects, the options of the
operator or banyan.api call that built it), and regenerate() rebuilds it
in place from that.

Storage is Object.banyan_plant, a PropertyGroup: saved in the .blend and
copied with the object. The params JSON text (Params.to_preset) is the
source of truth; a PropertyGroup per generator made from the library's
table (props.annotations) is its editable view in the sidebar. Values the
float32 view cannot hold exactly (and seeds above 2^31) are listed in
`lossy` with the view's value at record time, so an untouched property maps
back to the exact JSON value and an edited one wins. The view's lengths
in metres (the table's "m" rows) are in Blender units of the scene's
Unit Scale when recorded (`unit_scale`), so the Plant panel shows them in
the scene's units as the operators' redo panel does. Hosts are Object
pointers, so a renamed host is still found.

An avenue split into one object per tree is recorded on every tree (same
`group`, its tree number in `index`); regenerating any tree rebuilds the
whole avenue.

Regenerate builds through banyan.api (which reads hosts and curves in the
scene's units and makes the objects in them, api.from_metres) into a
collection linked to no scene, then swaps each object's mesh data: the
object itself (name, transform, parent, collections, modifiers,
selection, material slots) stays. Plants on hosts (roots, ivy) grow where their hosts are now, seen
from the object's current transform; a tree or twigs keep their object's
transform as their place (the mesh is the generator's, as built); an
avenue's trees go where the changed avenue puts them, moved by as much as
the artist moved them.
"""
import json
import random
import traceback
import uuid

import bpy
from bpy.props import CollectionProperty, FloatProperty, IntProperty, PointerProperty, StringProperty
from mathutils import Matrix

from . import hosts as H
from . import props as PP
from ..core import structs as S
from ..core.errors import BanyanError
from ..core.params import Params

SCHEMA = 1
HOSTED = ("roots", "ivy")  # generators whose plant grows on host objects
FOLLOWS = ("avenue",)  # objects placed by the generator (along the path), not by the operator
INT_MAX = 2 ** 31 - 1


class BanyanPlantHost(bpy.types.PropertyGroup):
    object: PointerProperty(type=bpy.types.Object, name="Host")
    # name (PropertyGroup's own): the host's name when recorded, to name it once it is gone


def _view_class(gen):
    return type("BanyanPlantParams_" + gen, (bpy.types.PropertyGroup,), {"__annotations__": PP.annotations(gen)})


def _plant_class(gens):
    ann = {
        "schema": IntProperty(name="Schema", default=0, description="0: not a Banyan plant"),
        "generator": StringProperty(name="Generator"),
        "params": StringProperty(name="Parameters", description="Params.to_preset JSON: what was built"),
        "seed": StringProperty(name="Seed", description="The params' seed when built"),
        "lossy": StringProperty(description="JSON {key: view value} of values the view rounds"),
        "unit_scale": FloatProperty(default=0.0, min=0.0, description="Metres per Blender unit of the view's "
                                                                       "lengths (0: metres, 1)"),
        "hosts": CollectionProperty(type=BanyanPlantHost),
        "path": PointerProperty(type=bpy.types.Object, name="Path",
                                description="The avenue's curve, when it was grown along one"),
        "options": StringProperty(name="Options", description="JSON of the operator's options"),
        "frame": StringProperty(description="JSON 4x4 world matrix of the object when built"),
        "group": StringProperty(description="Shared by the objects of one build (an avenue's trees)"),
        "index": IntProperty(description="This object's number in its group"),
    }
    for g in gens:
        ann[g] = PointerProperty(type=_VIEWS[g])
    return type("BanyanPlant", (bpy.types.PropertyGroup,), {"__annotations__": ann})


_VIEWS = {}
_classes = []


# ------------------------------------------------------------------ data

def is_plant(obj):
    # is_property_set first: reading obj.banyan_plant would add an empty record to any object.
    try:
        if obj is None or not obj.is_property_set("banyan_plant"):
            return False
    except (TypeError, AttributeError, ReferenceError):  # not an Object, or the add-on unregistered
        return False
    pl = obj.banyan_plant
    return pl.schema > 0 and bool(pl.generator)


def _matrix_json(m):
    return json.dumps([list(r) for r in m])


def _matrix(text):
    try:
        return Matrix(json.loads(text))
    except (ValueError, TypeError):
        return Matrix.Identity(4)


def _seed(params):
    for s in params.specs:
        if s.type == S.PT_SEED:
            return str(params.get(s.name))
    return ""


def _same(a, b):
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


def view_scale(pl):
    """Metres per Blender unit of a plant view's lengths (1 for a record
    made before the view had a unit scale)."""
    s = float("%.7g" % pl.unit_scale)  # a float32 property: 0.01, not 0.0099999998
    return s if 0 < s < float("inf") else 1.0


def _write_view(pl, params, lossy=None):
    """Copies params into the editable view, its lengths in Blender units
    of the current scene, and notes what it rounds (`lossy`, the JSON text,
    when already known: an avenue's trees share it)."""
    view = getattr(pl, params.name, None)
    if view is None:
        pl.lossy = ""
        return ""
    scale = H.unit_scale(bpy.context.scene)
    pl.unit_scale = scale
    PP.write_props(view, params, scale=scale)
    if lossy is None:
        seen = PP.to_params(params.name, view, scale=scale)
        out = {}
        for s in params.specs:
            a, b = seen.get(s.name), params.get(s.name)
            if not _same(a, b):
                out[s.name] = list(a) if isinstance(a, tuple) else a
        lossy = json.dumps(out)
    pl.lossy = lossy
    return lossy


def _plain(v):
    """v as JSON (numbers, text, lists of them), or None."""
    if isinstance(v, (bool, int, float, str)):
        return v
    if hasattr(v, "__len__") and hasattr(v, "__getitem__"):
        out = [_plain(c) for c in v]
        return None if any(c is None for c in out) else out
    return None


def record(objs, generator, params, hosts=(), options=None):
    """Stores on each object of `objs` (an Object or a list) what it was
    built from: generator name, params (a core.params.Params), host
    objects (Object pointers; core.structs.Box hosts are not kept),
    options (a JSON-able dict; an Object under "path" is kept as a
    pointer). Several objects are one group, rebuilt together.
    options["frame"] (4x4 rows): the object's world matrix as the
    generator placed it, by default its matrix now; an avenue's regenerated
    trees move by how their place changed from it. Does nothing when the
    add-on is not registered (its modules imported by a script)."""
    if not hasattr(bpy.types.Object, "banyan_plant"):
        return  # the modules used without the add-on enabled (e.g. a script on sys.path): nothing to record on
    objs = [objs] if isinstance(objs, bpy.types.Object) else list(objs)
    # An instanced avenue's empties are placements, not plants (and may be 10,000).
    objs = [o for o in objs if o.type != 'EMPTY']
    if not isinstance(params, Params):
        raise TypeError("params must be a banyan.core.params.Params, not %s" % type(params).__name__)
    options = dict(options or {})
    frame = options.pop("frame", None)
    path = options.pop("path", None)
    if path is not None and not isinstance(path, bpy.types.Object):
        options["path_points"] = [list(map(float, q)) for q in path]
        path = None
    text = params.to_preset()
    opt_text = json.dumps({k: _plain(v) for k, v in options.items() if _plain(v) is not None}, sort_keys=True)
    group = uuid.uuid4().hex if len(objs) > 1 else ""
    host_objs = [h for h in (hosts or ()) if isinstance(h, bpy.types.Object)]
    lossy = None
    for i, o in enumerate(objs):
        pl = o.banyan_plant
        pl.generator = generator if isinstance(generator, str) else params.name
        pl.params = text
        pl.seed = _seed(params)
        pl.hosts.clear()
        for h in host_objs:
            item = pl.hosts.add()
            item.object = h
            item.name = h.name
        pl.path = path
        pl.options = opt_text
        pl.frame = _matrix_json(Matrix(frame) if frame is not None else
                                o.matrix_basis if o.parent is None else o.matrix_world)
        pl.group = group
        pl.index = i
        lossy = _write_view(pl, params, lossy)
        pl.schema = SCHEMA


def record_operator(op, context, objs, params):
    """What a Banyan operator calls after a successful build: its hosts
    (the selected ones), its own options and the params it grew. Never
    raises: the plant is built, only its record would be missing."""
    try:
        hosts = op.selected_hosts(context) if hasattr(op, "selected_hosts") else []
        options = {"operator": getattr(op, "banyan_idname", op.bl_idname)}
        for name in tuple(getattr(op, "placement_props", ())) + tuple(getattr(op, "extra_props", ())) + (
                "banyan_preset",):
            options[name] = getattr(op, name, None)
        if options.get("path_from") == 'CURVE':
            options["path"] = context.active_object
        elif getattr(op, "built_path", None) is not None:
            options["path"] = op.built_path
        record(objs, op.generator, params, hosts, options)
    except Exception as e:  # noqa: BLE001 - the build succeeded; say why it cannot be edited later
        traceback.print_exc()
        op.report({'WARNING'}, "Banyan: built, but its parameters were not kept: %s" % e)


def options(obj):
    try:
        return json.loads(obj.banyan_plant.options or "{}")
    except ValueError:
        return {}


def host_status(obj):
    """[(name, object or None)]: None for a host that was deleted."""
    out = []
    for item in obj.banyan_plant.hosts:
        h = item.object
        gone = h is None or not h.users_scene
        out.append((item.name if gone else h.name, None if gone else h))
    return out


def stored_params(obj):
    """The params as built (the JSON text), exact."""
    pl = obj.banyan_plant
    p = Params(pl.generator)
    p.apply_preset(pl.params, "object '%s'" % obj.name)
    return p


def current_params(obj):
    """The params to build now: the stored ones with the sidebar's edits
    on top. BanyanError (naming the key) for an edit the library refuses."""
    pl = obj.banyan_plant
    exact = stored_params(obj)
    view = getattr(pl, pl.generator, None)
    if view is None:
        return exact
    p = PP.to_params(pl.generator, view, scale=view_scale(pl))
    try:
        lossy = json.loads(pl.lossy or "{}")
    except ValueError:
        lossy = {}
    for k, seen in lossy.items():
        if k in p.by_name and _same(p.get(k), tuple(seen) if isinstance(seen, list) else seen):
            p.set(k, exact.get(k))
    return p


def set_params(obj, params):
    """Replaces the stored params (and the view) of obj's plant, e.g. from a
    script; Regenerate then builds them."""
    pl = obj.banyan_plant
    if params.name != pl.generator:
        raise BanyanError(1, "'%s' is a %s plant, not %s" % (obj.name, pl.generator, params.name))
    pl.params = params.to_preset()
    pl.seed = _seed(params)
    _write_view(pl, params)


def edited(obj):
    """Keys whose sidebar value differs from what was built."""
    try:
        a, b = current_params(obj), stored_params(obj)
    except BanyanError:
        return ["?"]
    return [s.name for s in a.specs if not _same(a.get(s.name), b.get(s.name))]


def randomize_seed(obj, rng=None):
    """A new seed in the view (an edit; Regenerate builds it). Returns
    {property: old value} to put back."""
    pl = obj.banyan_plant
    view = getattr(pl, pl.generator)
    r = rng or random.SystemRandom()
    before = {}
    for s in stored_params(obj).specs:
        if s.type == S.PT_SEED:
            name = PP.prop_name(s.name)
            before[name] = old = getattr(view, name)
            new = old
            while new == old:
                new = r.randint(1, INT_MAX)
            setattr(view, name, new)
    return before


# ------------------------------------------------------------ regenerate

def members(obj):
    """The objects rebuilt with obj: [obj], or every tree of its avenue in
    the scene by tree number (the first one per number)."""
    pl = obj.banyan_plant
    if not pl.group:
        return {pl.index: obj}
    out = {}
    for o in bpy.data.objects:
        if is_plant(o) and o.banyan_plant.group == pl.group and o.users_scene and o.banyan_plant.index not in out:
            out[o.banyan_plant.index] = o
    out[pl.index] = obj
    return out


# -------------------------------------------------------------- register

def active_plant(context):
    """The context's active object when it is a Banyan plant, else None."""
    obj = getattr(context, "active_object", None)
    return obj if is_plant(obj) else None


def register():
    """Registers the record's types on Object, one view per generator."""
    gens = list(S.GENERATORS)
    _VIEWS.clear()
    del _classes[:]
    _classes.append(BanyanPlantHost)
    for g in gens:
        _VIEWS[g] = _view_class(g)
        _classes.append(_VIEWS[g])
    _classes.append(_plant_class(gens))
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Object.banyan_plant = PointerProperty(type=_classes[-1], name="Banyan plant")


def unregister():
    if hasattr(bpy.types.Object, "banyan_plant"):
        del bpy.types.Object.banyan_plant
    while _classes:
        bpy.utils.unregister_class(_classes.pop())
    _VIEWS.clear()

"""The machinery every Banyan operator shares: properties generated from
the generator's parameter table, the JSON preset menu, and execute()
that turns a library error into an error report with the scene left as
it was (api calls roll back what they made)."""
import contextlib
import math
import traceback

import bpy
from bpy.props import BoolProperty, EnumProperty, StringProperty

from .. import hosts as H
from .. import live
from .. import panels
from .. import plant
from .. import presets as PR
from .. import props as PP
from ..core import lib as LIB
from ..core.errors import BanyanError
from ..core.params import Params

NO_PRESET = "NONE"
LAST_PARAMS = {}  # bl_idname -> Params of its last successful run (for "save preset")


_items_cache = {}  # Blender needs the enum strings kept alive


def preset_items(gen):
    """The preset menu: (current values), the presets of gen, then the
    broken ones, greyed by their icon and named with the library's error;
    choosing one reports that error."""
    items = [(NO_PRESET, "(current values)", "Keep the values below", 'NONE', 0)]
    for key, _path, desc in PR.list_presets(gen):
        items.append((key, key, desc or key, 'NONE', len(items)))
    for key, _path, err in PR.broken_presets(gen):
        items.append((key, "%s (broken: %s)" % (key, err), "Cannot be used: %s" % err, 'ERROR', len(items)))
    _items_cache[gen] = items
    return items


def why_not(cls, message):
    """poll() failed: say why in the greyed menu entry's tooltip (Blender 3.0+)."""
    if hasattr(cls, "poll_message_set"):
        cls.poll_message_set(message)
    return False


def library_ready(cls):
    if LIB._lib is None:
        return why_not(cls, "The Banyan library is not loaded (see the Banyan tab in the sidebar)")
    return True


def _dynamic_items(gen):
    return lambda self, context: preset_items(gen)


class BanyanOperatorMixin:
    """Subclasses set `generator` and implement build(context, params) ->
    objects (through banyan.api). Properties come from make_operator()."""
    bl_options = {'REGISTER', 'UNDO', 'PRESET'}
    generator = ""
    extra_props = ()  # names of non-table properties, drawn first

    @classmethod
    def poll(cls, context):
        if not library_ready(cls):
            return False
        if getattr(context, "scene", None) is None:
            return why_not(cls, "No scene to add to")
        return True

    def load_preset_if_changed(self):
        """A newly chosen JSON preset overwrites the table properties once;
        later edits in the redo panel then apply on top of it."""
        key = self.banyan_preset or NO_PRESET
        if key == self.banyan_preset_loaded:
            return
        if key != NO_PRESET:
            p = Params(self.generator)
            path = PR.find(self.generator, key)
            p.apply_preset(PR.read(path), path)
            PP.write_props(self.properties, p)
        self.banyan_preset_loaded = key

    def params(self):
        # Through self.properties: each attribute of the operator itself
        # costs a property lookup in Python (bpy_types.Operator), ~30 us.
        return PP.to_params(self.generator, self.properties)

    def execute(self, context):
        try:
            self.load_preset_if_changed()
            params = self.params()
            objs = self.build(context, params)
            LAST_PARAMS[self.banyan_idname] = params
            plant.record_operator(self, context, objs, params)  # edit later (never raises)
        except (BanyanError, FileNotFoundError, ValueError) as e:
            self.report({'ERROR'}, "Banyan: %s" % (e.message if isinstance(e, BanyanError) else e))
            return {'CANCELLED'}
        except Exception as e:  # never leave a half-built scene or crash
            traceback.print_exc()
            self.report({'ERROR'}, "Banyan: unexpected %s: %s" % (type(e).__name__, e))
            return {'CANCELLED'}
        select_only(context, objs)
        nv = sum(len(o.data.vertices) for o in objs if o.type == 'MESH')
        self.report({'INFO'}, "Banyan: %d object(s), %d vertices" % (len(objs), nv))
        return {'FINISHED'}

    def draw(self, context):
        panels.draw_operator(self, context)


def cursor_location(context):
    """The 3D cursor's location; BanyanError when it is not finite (a
    script can put it at NaN, and the library would name a parameter the
    user never set)."""
    loc = tuple(context.scene.cursor.location)
    if not all(math.isfinite(c) for c in loc):
        raise BanyanError(2, "the 3D cursor is at (%s); move it to a finite location" % ", ".join(
            "%g" % c for c in loc), "BANYAN_E_RANGE")
    return loc


def cursor_axis(context, k=0):
    """Unit world direction of the 3D cursor's local axis k."""
    d = context.scene.cursor.matrix.to_3x3().col[k]
    if not all(math.isfinite(c) for c in d) or d.length < 1e-9:
        raise BanyanError(2, "the 3D cursor's rotation is not finite; reset it (Shift+C)", "BANYAN_E_RANGE")
    return d.normalized()


@contextlib.contextmanager
def at_cursor_note(active, field, note):
    """Adds `note` to a library error about `field` when the value came
    from the 3D cursor, not from a property the user set."""
    try:
        yield
    except BanyanError as e:
        if not active or not e.message.startswith(field):
            raise
        raise BanyanError(e.status, "%s (%s)" % (e.message, note), e.name) from None


def select_only(context, objs):
    vl = getattr(context, "view_layer", None)
    if vl is None or not objs:
        return
    for o in list(context.selected_objects):
        o.select_set(False)
    for o in objs:
        if o.name in vl.objects:
            o.select_set(True)
    if objs[0].name in vl.objects:
        vl.objects.active = objs[0]


class HostsOperatorMixin(BanyanOperatorMixin):
    """An operator whose hosts are the selected objects: with host shape
    Surface every selected object that has a surface (mesh, curve,
    surface, text, metaball) as its evaluated mesh, in one host set built
    per execute; with Bounding box the selected mesh objects' boxes."""

    @classmethod
    def poll(cls, context):
        if not super().poll(context):
            return False
        if any(o.type in H.SURFACE_TYPES for o in getattr(context, "selected_objects", None) or ()):
            return True
        return why_not(cls, "Select the objects to grow on (meshes, curves, text)")

    def selected_hosts(self, context):
        """The selected host objects, the active one first."""
        surface = getattr(self, "host_shape", H.BOX) == H.SURFACE
        types = H.SURFACE_TYPES if surface else ('MESH',)
        hosts = [o for o in context.selected_objects if o.type in types]
        if not hosts:
            raise BanyanError(3, "select one or more %s as hosts" % (
                "objects with a surface (mesh, curve, text)" if surface else "mesh objects"), "BANYAN_E_NO_HOSTS")
        active = context.active_object
        if active in hosts:
            hosts.remove(active)
            hosts.insert(0, active)
        return hosts

    @contextlib.contextmanager
    def host_arg(self, context):
        """What the generator gets: the boxes of the selected meshes (Bounding
        box), or a host set of their surfaces, built once here and freed when
        the block ends (Surface)."""
        hosts = self.selected_hosts(context)
        if self.host_shape == H.BOX:
            yield H.boxes_from_objects(hosts)
            return
        with H.surface_host_set(hosts, context.evaluated_depsgraph_get()) as hs:
            yield hs


def host_shape_property():
    return EnumProperty(name="Host shape", default=H.SURFACE, items=H.HOST_SHAPES,
                        description="What the plant grows on: the selected objects' real surfaces (evaluated "
                                    "meshes, modifiers applied) or their oriented bounding boxes")


def make_operator(mixin, idname, label, description, gen, extra):
    """Builds an Operator class for gen: the table's properties plus
    `extra` (dict of non-table properties) plus the preset menu."""
    table = PP.annotations(gen)
    clash = set(table) & (set(extra) | {"banyan_preset", "banyan_preset_loaded"} | set(live.properties(gen)))
    if clash:
        raise BanyanError(14, "%s: operator property names clash with the table: %s" % (gen, sorted(clash)))
    ann = {}
    ann["banyan_preset"] = EnumProperty(name="Preset", items=_dynamic_items(gen),
                                        description="A JSON preset from presets/; applied once when chosen")
    ann["banyan_preset_loaded"] = StringProperty(default=NO_PRESET, options={'HIDDEN'})
    extra = dict(extra)
    extra["uv_map"] = BoolProperty(name="UV map", default=True,
                                   description="Copy the library's UVs into a UV map (costs about 0.1 us per "
                                               "triangle corner on top of Blender's own mesh building)")
    ann.update(extra)
    ann.update(live.properties(gen))
    ann.update(table)
    cls_name = "MESH_OT_" + idname.split(".", 1)[1]
    return type(cls_name, (mixin, bpy.types.Operator), {
        "bl_idname": idname, "banyan_idname": idname, "bl_label": label, "bl_description": description, "generator": gen,
        "extra_props": tuple(extra), "table_props": tuple(table), "__annotations__": ann,
        "execute": live.wrap(mixin.execute),
    })


class BANYAN_OT_preset_save(bpy.types.Operator):
    """Save the last values of a Banyan operator as a JSON preset (usable by the CLI too)"""
    bl_idname = "banyan.preset_save"
    bl_label = "Save Banyan Preset"
    bl_options = {'REGISTER', 'INTERNAL'}

    operator: StringProperty(name="Operator", options={'HIDDEN', 'SKIP_SAVE'})
    name: StringProperty(name="Name", default="my_preset", options={'SKIP_SAVE'})
    description: StringProperty(name="Description", default="", options={'SKIP_SAVE'})

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        p = LAST_PARAMS.get(self.operator)
        if p is None:
            self.report({'ERROR'}, "Banyan: '%s' has not run yet in this session" % self.operator)
            return {'CANCELLED'}
        try:
            path = PR.save(p.name, self.name, p.to_preset(self.description))
        except (BanyanError, OSError) as e:
            self.report({'ERROR'}, "Banyan: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "Banyan: saved %s" % path)
        return {'FINISHED'}

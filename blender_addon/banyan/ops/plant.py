"""Operators on the active plant (the sidebar's Plant panel, ui/plant.py):
Regenerate, Randomize Seed, Copy as Preset. The data and the rebuilding
are engine/plant.py's."""
import bpy
from bpy.props import StringProperty

from ..core.errors import BanyanError, report_error
from ..engine import plant as PL
from ..engine.plant import active_plant
from ..engine.regenerate import regenerate


def _poll(cls, context):
    if active_plant(context) is None:
        cls.poll_message_set("The active object is not a Banyan plant")
        return False
    if context.mode != 'OBJECT':
        cls.poll_message_set("Regenerating works in Object Mode")
        return False
    return True


class BANYAN_OT_regenerate(bpy.types.Operator):
    """Rebuild the active plant in place from its parameters (as edited in the sidebar) and its hosts,
    keeping its name, transform, materials and modifiers"""
    bl_idname = "banyan.regenerate"
    bl_label = "Regenerate"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _poll(cls, context)

    def execute(self, context):
        obj = active_plant(context)
        try:
            objs = regenerate(obj)
        except Exception as e:  # the object is left as it was
            return report_error(self.report, e)
        nv = sum(len(o.data.vertices) for o in objs if o.type == 'MESH')
        self.report({'INFO'}, "Banyan: regenerated %d object(s), %d vertices" % (len(objs), nv))
        return {'FINISHED'}


class BANYAN_OT_randomize_seed(bpy.types.Operator):
    """Give the active plant a new random seed and regenerate it"""
    bl_idname = "banyan.randomize_seed"
    bl_label = "Randomize Seed"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _poll(cls, context)

    def execute(self, context):
        obj = active_plant(context)
        view = getattr(obj.banyan_plant, obj.banyan_plant.generator)
        before = PL.randomize_seed(obj)
        try:
            regenerate(obj)
        except BanyanError as e:
            for k, v in before.items():  # nothing changes when it fails
                setattr(view, k, v)
            self.report({'ERROR'}, "Banyan: %s" % e.message)
            return {'CANCELLED'}
        self.report({'INFO'}, "Banyan: seed %s" % obj.banyan_plant.seed)
        return {'FINISHED'}


class BANYAN_OT_copy_preset(bpy.types.Operator):
    """Copy the active plant's parameters (with the sidebar's edits) to the clipboard as a JSON preset"""
    bl_idname = "banyan.copy_preset"
    bl_label = "Copy as Preset"
    bl_options = {'REGISTER'}

    description: StringProperty(name="Description", default="", options={'SKIP_SAVE'})

    @classmethod
    def poll(cls, context):
        if active_plant(context) is None:
            cls.poll_message_set("The active object is not a Banyan plant")
            return False
        return True

    def execute(self, context):
        obj = active_plant(context)
        try:
            text = PL.current_params(obj).to_preset(self.description or "from %s" % obj.name)
        except BanyanError as e:
            self.report({'ERROR'}, "Banyan: %s" % e.message)
            return {'CANCELLED'}
        context.window_manager.clipboard = text
        self.report({'INFO'}, "Banyan: %s preset copied" % obj.banyan_plant.generator)
        return {'FINISHED'}

"""Operators on plants already built: Add Wind (the Banyan Wind modifier
on the selected plants), Add Growth Animation (by `birth`) and Make LODs
(the active plant's LOD collection). The work is engine/production.py's
and engine/lod.py's."""
import bpy
from bpy.props import BoolProperty, FloatProperty, FloatVectorProperty

from .. import api
from ..core.errors import report_error
from ..engine import lod
from ..engine import plant as PL
from ..engine import wind as W


def _meshes(context):
    return [o for o in getattr(context, "selected_objects", None) or () if o.type == 'MESH']


def _windable(o):
    return W.has_wind(o.data) or PL.is_plant(o)


class BANYAN_OT_add_wind(bpy.types.Operator):
    """Add the Banyan Wind modifier (Geometry Nodes) to the selected plants; a plant grown without wind data is
    regrown with it first"""
    bl_idname = "banyan.add_wind"
    bl_label = "Add Wind"
    bl_options = {'REGISTER', 'UNDO'}

    strength: FloatProperty(name="Strength", default=W.INPUTS["Strength"][0], min=0.0, max=1.0,
                            description=W.INPUTS["Strength"][3])
    gust_strength: FloatProperty(name="Gust strength", default=W.INPUTS["Gust strength"][0], min=0.0, max=4.0,
                                 description=W.INPUTS["Gust strength"][3])
    gust_frequency: FloatProperty(name="Gust frequency", default=W.INPUTS["Gust frequency"][0], min=0.0,
                                  max=10.0, unit='NONE', description=W.INPUTS["Gust frequency"][3])
    direction: FloatProperty(name="Direction", default=0.0, min=-360.0, max=360.0,
                             description=W.INPUTS["Direction"][3])
    flutter: FloatProperty(name="Flutter", default=W.INPUTS["Flutter"][0], min=0.0, max=0.2,
                           description=W.INPUTS["Flutter"][3])

    @classmethod
    def poll(cls, context):
        if not any(_windable(o) for o in _meshes(context)):
            cls.poll_message_set("Select Banyan plants, or meshes with wind data")
            return False
        return True

    def execute(self, context):
        objs = [o for o in _meshes(context) if _windable(o)]
        try:
            api.add_wind(objs, strength=self.strength, gust_strength=self.gust_strength,
                         gust_frequency=self.gust_frequency, direction=self.direction, flutter=self.flutter)
        except Exception as e:
            return report_error(self.report, e)
        skipped = len(_meshes(context)) - len(objs)
        self.report({'INFO'}, "Banyan: wind on %d object(s)%s" % (
            len(objs), ", %d without wind data skipped" % skipped if skipped else ""))
        return {'FINISHED'}


class BANYAN_OT_add_growth(bpy.types.Operator):
    """Add a growth animation (Geometry Nodes, by the birth attribute) over the scene's frame range to the
    selected plants"""
    bl_idname = "banyan.add_growth"
    bl_label = "Add Growth Animation"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        if not any("birth" in o.data.attributes for o in _meshes(context)):
            cls.poll_message_set("Select plants with a birth attribute")
            return False
        return True

    def execute(self, context):
        objs = [o for o in _meshes(context) if "birth" in o.data.attributes]
        try:
            api.add_growth(objs)
        except Exception as e:
            return report_error(self.report, e)
        self.report({'INFO'}, "Banyan: growth on %d object(s)" % len(objs))
        return {'FINISHED'}


class BANYAN_OT_make_lods(bpy.types.Operator):
    """Make the active plant's levels of detail (the library's simplifier; billboard cards for trees) in a
    collection "<name> LODs\""""
    bl_idname = "banyan.make_lods"
    bl_label = "Make LODs"
    bl_options = {'REGISTER', 'UNDO'}

    ratios: FloatVectorProperty(name="Ratios", size=2, default=(0.5, 0.15), min=0.001, max=1.0,
                                description="Share of the triangles each level keeps, falling (each level is made from the one before)")
    billboard: BoolProperty(name="Billboard", default=True, description="Crossed cards as the last level (trees)")

    @classmethod
    def poll(cls, context):
        if not PL.is_plant(getattr(context, "active_object", None)):
            cls.poll_message_set("The active object is not a Banyan plant")
            return False
        return True

    def execute(self, context):
        obj = context.active_object
        try:
            objs = lod.make_lods(obj, tuple(self.ratios),
                                 billboard=self.billboard and obj.banyan_plant.generator in lod.TREES)
        except Exception as e:
            return report_error(self.report, e)
        self.report({'INFO'}, "Banyan: %d levels, %s triangles" % (
            len(objs), " / ".join(str(sum(len(p.vertices) - 2 for p in o.data.polygons)) for o in objs)))
        return {'FINISHED'}



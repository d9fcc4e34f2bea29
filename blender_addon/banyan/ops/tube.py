"""Add Banyan Tube: the library's smallest output (banyan_tube_generate),
a check that the library and the mesh hand-off work."""
import bpy
from bpy.props import FloatProperty, IntProperty, BoolProperty

from ..engine import build_mesh as BM
from ..core import mesh as M
from ..core.errors import BanyanError
from .base import cursor_location, select_only


class MESH_OT_banyan_tube(bpy.types.Operator):
    """Sweep a tube through the library's shared sweeper (a self-test)"""
    bl_idname = "mesh.banyan_tube"
    bl_label = "Add Banyan Tube"
    bl_options = {'REGISTER', 'UNDO', 'PRESET'}

    height: FloatProperty(name="Height", default=2.0, subtype='DISTANCE', unit='LENGTH')
    radius: FloatProperty(name="Radius", default=0.1, subtype='DISTANCE', unit='LENGTH')
    sides: IntProperty(name="Sides", default=12, soft_min=3, soft_max=256)
    caps: BoolProperty(name="Caps", default=True)

    def execute(self, context):
        created = BM.Created()
        try:
            c = cursor_location(context)
            # Swept about the origin; the object stands at the cursor (its origin at the tube's foot).
            pts = [(0.0, 0.0, 0.0), (0.0, 0.0, self.height * 0.5), (0.2 * self.height, 0.0, self.height)]
            d = M.tube(pts, [self.radius, self.radius * 0.8, self.radius * 0.5], self.sides, self.caps)
            obj = BM.object_from_mesh_data("Banyan Tube", d, context.collection, created)
            obj.location = c
        except BanyanError as e:
            created.rollback()
            self.report({'ERROR'}, "Banyan: %s" % e.message)
            return {'CANCELLED'}
        except Exception as e:
            created.rollback()
            self.report({'ERROR'}, "Banyan: unexpected %s: %s" % (type(e).__name__, e))
            return {'CANCELLED'}
        select_only(context, [obj])
        return {'FINISHED'}

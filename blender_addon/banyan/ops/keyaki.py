"""Add Keyaki Tree (its trunk foot at the 3D cursor, or Location, with
Blender's Align / Location / Rotation; the object's origin at the foot)
and Add Keyaki Avenue (along the active curve, a straight line from the
cursor, or the parameters' start-end line)."""
import math

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty
from bpy_extras.object_utils import AddObjectHelper
from mathutils import Matrix

from .. import api
from ..core.errors import BanyanError
from ..ui import live
from .base import BanyanOperatorMixin, at_cursor_note, cursor_axis, cursor_location, place_matrix, scene_point


class TreeMixin(BanyanOperatorMixin):
    def prepare(self, context, params):
        self._matrix = None
        with at_cursor_note(self.at_cursor, "position", "the tree stands at the 3D cursor"):
            if self.at_cursor:
                cursor_location(context)  # a NaN cursor is named as such
                self._matrix = place_matrix(context, self)
                # Recorded (save preset, the plant's parameters) as where it stands.
                params.set("position", scene_point(self, self._matrix.to_translation()))
            return api.keyaki_tree_job(params=params, collection=context.collection, uv=self.uv_map)

    def place(self, context, objs):
        """The foot at Location, turned by Rotation about the foot (the mesh
        is local to it); without At 3D cursor, at `position`, turned too.
        The mesh in metres, scaled to the scene's units (from_metres)."""
        m = self._matrix
        if m is None:
            m = Matrix.Translation(objs[0].location) @ place_matrix(context, self).to_3x3().to_4x4()
        objs[0].matrix_world = m @ Matrix.Scale(1.0 / self.unit_scale, 4)


class AvenueMixin(BanyanOperatorMixin):
    def prepare(self, context, params):
        path = None
        self.built_path = None  # the straight line, for the plant's record
        act = context.active_object
        if self.path_from == 'CURVE':
            if act is None or act.type != 'CURVE':
                raise BanyanError(1, "the active object is not a curve (choose 'Straight line')")
            path = act  # read in the scene's units by the API
        elif self.path_from == 'CURSOR':
            a = cursor_location(context)
            d = cursor_axis(context, 0)
            path = [scene_point(self, a), scene_point(self, tuple(a[k] + d[k] * self.line_length for k in range(3)))]
            self.built_path = path
            # Recorded as grown: a preset saved from this run draws this line.
            with at_cursor_note(True, "start", "the line starts at the 3D cursor"):
                params.set("start", path[0])
                params.set("end", path[1])
        with at_cursor_note(self.path_from == 'CURSOR', "path point", "the line starts at the 3D cursor"):
            return api.keyaki_avenue_job(path=path, params=params, merged=self.merged,
                                         collection=context.collection, uv=self.uv_map)

    def preset_loaded(self, values, has_hosts):
        # A preset that draws its line: the straight line from the cursor
        # takes its length (so its count too); Parameters use it as is.
        if "start" in values or "end" in values:
            a, b = self.properties.start, self.properties.end
            n = math.sqrt(sum((b[k] - a[k]) ** 2 for k in range(3)))
            if n > 0:
                self.line_length = n

    def invoke(self, context, event):
        act = context.active_object
        self.path_from = 'CURVE' if act is not None and act.type == 'CURVE' else 'CURSOR'
        return BanyanOperatorMixin.invoke(self, context, event)


class MESH_OT_banyan_keyaki_tree(TreeMixin, AddObjectHelper, bpy.types.Operator):
    """Grow one keyaki (Zelkova) tree"""
    bl_idname = "mesh.banyan_keyaki_tree"
    bl_label = "Add Keyaki Tree"
    generator = "keyaki"
    execute = live.wrap(TreeMixin.execute)

    at_cursor: BoolProperty(name="At 3D cursor", default=True,
                            description="Put the trunk foot at Location (the 3D cursor unless set), else at `position`")


class MESH_OT_banyan_keyaki_avenue(AvenueMixin, bpy.types.Operator):
    """Plant rows of keyaki trees along a curve or a line"""
    bl_idname = "mesh.banyan_keyaki_avenue"
    bl_label = "Add Keyaki Avenue"
    generator = "avenue"
    execute = live.wrap(AvenueMixin.execute)

    path_from: EnumProperty(name="Path", default='CURSOR', items=[
        ('CURVE', "Active curve", "Along the active curve object (its first spline)"),
        ('CURSOR', "Straight line", "From the 3D cursor along its X axis, `line length` metres (a preset's "
                                    "start-end length when it draws a line)"),
        ('PARAMS', "Parameters", "From `start` to `end`")])
    line_length: FloatProperty(name="Line length", default=60.0, min=0.1, soft_max=1000.0,
                               subtype='DISTANCE', unit='LENGTH')
    merged: BoolProperty(name="Merge trees", default=False,
                         description="One merged object (origin at the path's start) instead of one object "
                                     "per tree (origin at its foot) in a new collection")

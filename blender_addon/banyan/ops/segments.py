"""Add Segment Twigs: a tree of geometry-shader segments from a segments
preset (its segment list), or the random demo tree; its root at the 3D
cursor or Location, with Blender's Align / Location / Rotation."""
import bpy
from bpy_extras.object_utils import AddObjectHelper
from mathutils import Matrix

from .. import api
from ..ui import live
from .base import NO_PRESET, BanyanOperatorMixin, cursor_location, place_matrix


class SegmentsMixin(BanyanOperatorMixin):
    def prepare(self, context, params):
        key = self.banyan_preset if self.banyan_preset != NO_PRESET else None
        cursor_location(context)  # a NaN cursor is named as such
        self._matrix = place_matrix(context, self)
        return api.segment_twigs_job(preset=key, params=params, collection=context.collection, uv=self.uv_map)

    def place(self, context, objs):
        m = self._matrix @ Matrix.Scale(1.0 / self.unit_scale, 4)  # the mesh in metres (from_metres)
        for o in objs:
            o.matrix_world = m

    def load_preset_if_changed(self, scale=1.0):
        # The preset also supplies the segment list (read in build), so it stays selected.
        BanyanOperatorMixin.load_preset_if_changed(self, scale)


class MESH_OT_banyan_segment_twigs(SegmentsMixin, AddObjectHelper, bpy.types.Operator):
    """Branch segments sized for one geometry-shader call, from a segments preset"""
    bl_idname = "mesh.banyan_segment_twigs"
    bl_label = "Add Segment Twigs"
    generator = "segments"
    execute = live.wrap(SegmentsMixin.execute)

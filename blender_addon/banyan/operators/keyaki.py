"""Add Keyaki Tree (at the 3D cursor) and Add Keyaki Avenue (along the
active curve, or a straight line from the cursor)."""
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty

from .. import api
from ..core.errors import BanyanError
from .base import BanyanOperatorMixin, at_cursor_note, cursor_axis, cursor_location, make_operator

TREE_IDNAME = "mesh.banyan_keyaki_tree"
AVENUE_IDNAME = "mesh.banyan_keyaki_avenue"


class TreeMixin(BanyanOperatorMixin):
    def build(self, context, params):
        pos = cursor_location(context) if self.at_cursor else None
        with at_cursor_note(pos is not None, "position", "the tree stands at the 3D cursor"):
            if pos is not None:
                params.set("position", pos)  # on `params` itself: the plant's record keeps where it stands
            return api.keyaki_tree(params=params, position=pos, collection=context.collection, uv=self.uv_map)


class AvenueMixin(BanyanOperatorMixin):
    def build(self, context, params):
        path = None
        act = context.active_object
        if self.path_from == 'CURVE':
            if act is None or act.type != 'CURVE':
                raise BanyanError(1, "the active object is not a curve (choose 'Straight line')")
            path = act
        elif self.path_from == 'CURSOR':
            a = cursor_location(context)
            d = cursor_axis(context, 0)
            path = [a, tuple(a[k] + d[k] * self.line_length for k in range(3))]
            self.built_path = path  # the plant's record keeps the line
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            with at_cursor_note(self.path_from == 'CURSOR', "path point", "the line starts at the 3D cursor"):
                return api.keyaki_avenue(path=path, params=params, merged=self.merged,
                                         collection=context.collection, uv=self.uv_map,
                                         progress=lambda done, total: wm.progress_update(int(100 * done / total)))
        finally:
            wm.progress_end()

    def invoke(self, context, event):
        act = context.active_object
        self.path_from = 'CURVE' if act is not None and act.type == 'CURVE' else 'CURSOR'
        return self.execute(context)


def make_tree_class():
    extra = {"at_cursor": BoolProperty(name="At 3D cursor", default=True,
                                       description="Put the trunk base at the 3D cursor (else `position`)")}
    return make_operator(TreeMixin, TREE_IDNAME, "Add Keyaki Tree", "Grow one keyaki (Zelkova) tree",
                         "keyaki", extra)


def make_avenue_class():
    extra = {
        "path_from": EnumProperty(name="Path", default='CURSOR', items=[
            ('CURVE', "Active curve", "Along the active curve object (its first spline)"),
            ('CURSOR', "Straight line", "From the 3D cursor along its X axis, `line length` metres"),
            ('PARAMS', "Parameters", "From `start` to `end`")]),
        "line_length": FloatProperty(name="Line length", default=60.0, min=0.1, soft_max=1000.0,
                                     subtype='DISTANCE', unit='LENGTH'),
        "merged": BoolProperty(name="Merge trees", default=False,
                               description="One merged object instead of one object per tree in a new collection"),
    }
    return make_operator(AvenueMixin, AVENUE_IDNAME, "Add Keyaki Avenue",
                         "Plant rows of keyaki trees along a curve or a line", "avenue", extra)

"""Add Ivy: hosts are the selected mesh objects; the start is the 3D
cursor (the library snaps it to the nearest host surface)."""
from bpy.props import BoolProperty

from .. import api
from .. import hosts as H
from ..core.errors import BanyanError
from .base import BanyanOperatorMixin, make_operator

IDNAME = "mesh.banyan_ivy"


class IvyMixin(BanyanOperatorMixin):
    @classmethod
    def poll(cls, context):
        return any(o.type == 'MESH' for o in getattr(context, "selected_objects", ()))

    def build(self, context, params):
        hosts = [o for o in context.selected_objects if o.type == 'MESH']
        if not hosts:
            raise BanyanError(3, "select one or more mesh objects as hosts")
        boxes = H.boxes_from_objects(hosts)
        start = None
        if self.start_at_cursor:
            # Snap here too, so a cursor far from the hosts still starts on the nearest one.
            start, _box = H.closest_point(boxes, tuple(context.scene.cursor.location))
        return api.ivy(hosts=boxes, params=params, start=start, collection=context.collection, uv=self.uv_map,
                       animate=self.animate)


def make_class():
    extra = {
        "start_at_cursor": BoolProperty(name="Start at 3D cursor", default=True,
                                        description="Start at the host surface point nearest the 3D cursor "
                                                    "(else the `start` parameter)"),
        "animate": BoolProperty(name="Growth animation", default=False,
                                description="Add a Geometry Nodes modifier revealing the ivy by birth_step "
                                            "over the scene's frame range"),
    }
    return make_operator(IvyMixin, IDNAME, "Add Ivy", "Grow climbing ivy over the selected objects", "ivy", extra)

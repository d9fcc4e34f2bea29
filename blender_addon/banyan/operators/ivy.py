"""Add Ivy: hosts are the selected objects (their real surfaces, or their
bounding boxes: "Host shape"); the start is the 3D cursor (the library
snaps it to the nearest host surface)."""
from bpy.props import BoolProperty

from .. import api
from .. import hosts as H
from .base import HostsOperatorMixin, cursor_location, host_shape_property, make_operator

IDNAME = "mesh.banyan_ivy"


class IvyMixin(HostsOperatorMixin):
    def build(self, context, params):
        with self.host_arg(context) as hosts:
            start = None
            if self.start_at_cursor:
                # Snap here too, so a cursor far from the hosts still starts on the nearest one.
                cur = cursor_location(context)
                if isinstance(hosts, list):
                    start, _box = H.closest_point(hosts, cur)
                else:
                    start = H.closest_on_set(hosts, cur)
                params.set("start", start)  # on `params` itself: the plant's record keeps where it grew
            return api.ivy(hosts=hosts, params=params, start=start, collection=context.collection, uv=self.uv_map,
                           animate=self.animate)


def make_class():
    extra = {
        "host_shape": host_shape_property(),
        "start_at_cursor": BoolProperty(name="Start at 3D cursor", default=True,
                                        description="Start at the host surface point nearest the 3D cursor "
                                                    "(else the `start` parameter)"),
        "animate": BoolProperty(name="Growth animation", default=False,
                                description="Add a Geometry Nodes modifier revealing the ivy by birth_step "
                                            "over the scene's frame range"),
    }
    return make_operator(IvyMixin, IDNAME, "Add Ivy", "Grow climbing ivy over the selected objects", "ivy", extra)

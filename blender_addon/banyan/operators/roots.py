"""Add Strangler Roots: hosts are the selected mesh objects' world-space
oriented boxes; germination above the active object's top centre, at the
3D cursor, or as the parameters say."""
from bpy.props import EnumProperty

from .. import api
from .. import hosts as H
from .base import HostsOperatorMixin, cursor_location, make_operator

IDNAME = "mesh.banyan_roots"


class RootsMixin(HostsOperatorMixin):
    def build(self, context, params):
        hosts = self.selected_hosts(context)  # the active object is the first host
        boxes = H.boxes_from_objects(hosts)
        if self.germinate_at == 'CURSOR':
            api.set_roots_germination(params, cursor_location(context))
        elif self.germinate_at == 'ACTIVE_TOP':
            # The generator's own rule: top centre of hosts[0] (the active object), lifted by r.
            params.set("germination_auto", True)
        # Set on `params` itself so "save preset" records what was grown.
        return api.strangler_roots(hosts=boxes, params=params, collection=context.collection, uv=self.uv_map)


def make_class():
    extra = {"germinate_at": EnumProperty(
        name="Germinate at", default='ACTIVE_TOP',
        items=[('ACTIVE_TOP', "Active top", "Above the top centre of the active (first) host"),
               ('CURSOR', "3D cursor", "At the 3D cursor"),
               ('PARAMS', "Parameters", "Where the germination parameters say")])}
    return make_operator(RootsMixin, IDNAME, "Add Strangler Roots",
                         "Grow strangler-fig roots around the selected objects", "roots", extra)

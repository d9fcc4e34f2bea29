"""Add Strangler Roots: hosts are the selected objects (their real
surfaces, or their world-space oriented boxes: "Host shape");
germination above the active object's top, at the 3D cursor, or as the
parameters say."""
from bpy.props import EnumProperty

from .. import api
from .base import HostsOperatorMixin, cursor_location, host_shape_property, make_operator

IDNAME = "mesh.banyan_roots"


class RootsMixin(HostsOperatorMixin):
    def build(self, context, params):
        with self.host_arg(context) as hosts:  # the active object is the first host
            if self.germinate_at == 'CURSOR':
                api.set_roots_germination(params, cursor_location(context))
            elif self.germinate_at == 'ACTIVE_TOP':
                # The generator's own rule on hosts[0] (the active object): its top, lifted by r.
                params.set("germination_auto", True)
            # Set on `params` itself so "save preset" records what was grown.
            return api.strangler_roots(hosts=hosts, params=params, collection=context.collection, uv=self.uv_map)


def make_class():
    extra = {
        "host_shape": host_shape_property(),
        "germinate_at": EnumProperty(
            name="Germinate at", default='ACTIVE_TOP',
            items=[('ACTIVE_TOP', "Active top", "Above the top of the active (first) host"),
                   ('CURSOR', "3D cursor", "At the 3D cursor"),
                   ('PARAMS', "Parameters", "Where the germination parameters say")])}
    return make_operator(RootsMixin, IDNAME, "Add Strangler Roots",
                         "Grow strangler-fig roots around the selected objects", "roots", extra)

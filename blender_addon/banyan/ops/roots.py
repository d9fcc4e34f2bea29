"""Add Strangler Roots: hosts are the selected objects (their real
surfaces, or their world-space oriented boxes: "Host shape");
germination above the active object's top, at the 3D cursor, or as the
parameters say (a preset's germination point is relative to its hosts,
carried onto the selected objects' bounds). The object's origin is the
bottom centre of the active host's world bounds."""
import contextlib

import bpy
from bpy.props import EnumProperty

from .. import api
from ..ui import live
from .base import (NO_PRESET, HostsOperatorMixin, cursor_location, ground_at_hosts_property, host_shape_property,
                   scene_point, set_ground_at_hosts)


class RootsMixin(HostsOperatorMixin):
    def prepare(self, context, params):
        stack = contextlib.ExitStack()
        try:
            hosts = stack.enter_context(self.host_arg(context))  # the active object is the first host
            # Set on `params` itself so "save preset" records what was grown.
            if self.germinate_at == 'CURSOR':
                api.set_roots_germination(params, scene_point(self, cursor_location(context)))
            elif self.germinate_at == 'ACTIVE_TOP':
                # The generator's own rule on hosts[0] (the active object): its top, lifted by r.
                params.set("germination_auto", True)
            elif (self.banyan_preset != NO_PRESET and not params.get("germination_auto")
                  and "germination" in self.preset_params() and self.preset_has_hosts()):
                # From the preset's hosts (metres) onto the selected ones (Blender units), in metres.
                pt = api.preset_point_on("roots", self.banyan_preset, params.get("germination"),
                                         self.selected_hosts(context))
                api.set_roots_germination(params, scene_point(self, pt))
            set_ground_at_hosts(self, params, hosts)
            job = api.strangler_roots_job(hosts=hosts, params=params, collection=context.collection,
                                          uv=self.uv_map)
            return job.adopt(stack)
        except BaseException:
            stack.close()
            raise

    def preset_loaded(self, values, has_hosts):
        if "ground_z" in values and not has_hosts:  # the preset's own ground (else kept relative to its hosts)
            self.ground_at_hosts = False
        # The preset's own germination: its point (relative to its hosts) or the automatic one.
        if "germination" in values and not values.get("germination_auto", False):
            self.germinate_at = 'PARAMS'
        elif values.get("germination_auto", True):
            self.germinate_at = 'ACTIVE_TOP'


class MESH_OT_banyan_roots(RootsMixin, bpy.types.Operator):
    """Grow strangler-fig roots around the selected objects"""
    bl_idname = "mesh.banyan_roots"
    bl_label = "Add Strangler Roots"
    generator = "roots"
    execute = live.wrap(RootsMixin.execute)

    host_shape: host_shape_property()
    ground_at_hosts: ground_at_hosts_property()
    germinate_at: EnumProperty(
        name="Germinate at", default='ACTIVE_TOP',
        items=[('ACTIVE_TOP', "Active top", "Above the top of the active (first) host"),
               ('CURSOR', "3D cursor", "At the 3D cursor"),
               ('PARAMS', "Parameters", "Where the germination parameters say (a preset's point is "
                                        "relative to its hosts)")])

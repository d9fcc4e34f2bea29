"""Add Ivy: hosts are the selected objects (their real surfaces, or their
bounding boxes: "Host shape"); the start is the 3D cursor (the library
places it on the nearest host side where a stem can grow), or the
`start` parameter, which for a preset with hosts is read relative to
them and carried onto the selected objects' bounds. The object's origin
is the bottom centre of the active host's world bounds."""
import contextlib
import math

import bpy
from bpy.props import BoolProperty

from .. import api
from ..engine import hosts as H
from ..ui import live
from .base import (NO_PRESET, HostsOperatorMixin, cursor_location, ground_at_hosts_property, host_shape_property,
                   scene_point, set_ground_at_hosts)


class IvyMixin(HostsOperatorMixin):
    def prepare(self, context, params):
        stack = contextlib.ExitStack()
        try:
            hosts = stack.enter_context(self.host_arg(context))
            start = self._start_point(context, params, hosts)
            if start is not None:
                params.set("start", start)  # recorded as grown (save preset, the plant's parameters)
            set_ground_at_hosts(self, params, hosts)
            job = api.ivy_job(hosts=hosts, params=params, start=start, collection=context.collection,
                              uv=self.uv_map, animate=self.animate)
            return job.adopt(stack)
        except BaseException:
            stack.close()
            raise

    def _start_point(self, context, params, hosts):
        if not self.start_at_cursor:
            if self.banyan_preset != NO_PRESET and "start" in self.preset_params() and self.preset_has_hosts():
                # The preset's start is relative to its own hosts.
                self._start_from = "the preset's start"
                return scene_point(self, api.preset_point_on("ivy", self.banyan_preset, params.get("start"),
                                                             self.selected_hosts(context)))
            self._start_from = "start"
            return None
        # The cursor as it is, for the library to place (it knows where a
        # stem can grow); a cursor farther than start_snap_max from every
        # host first comes to the nearest host point, so it still grows.
        cur = scene_point(self, cursor_location(context))  # metres, as the hosts
        self._start_from = "the 3D cursor"
        near = H.closest_point(hosts, cur)[0] if isinstance(hosts, list) else H.closest_on_set(hosts, cur)
        if near is not None and math.dist(near, cur) > 0.99 * params.get("start_snap_max"):
            return near
        return cur

    def preset_loaded(self, values, has_hosts):
        if "ground_z" in values and not has_hosts:  # the preset's own ground (else kept relative to its hosts)
            self.ground_at_hosts = False
        # A start given relative to the preset's hosts is part of what it
        # describes (a preset saved from a run has no hosts: the cursor stays).
        if "start" in values and has_hosts:
            self.start_at_cursor = False

    def grew_message(self, context, job):
        if job.info.get("grew", True):
            return None
        where = getattr(self, "_start_from", "start")
        p = [c / self.unit_scale for c in job.params.get("start")]  # in the scene's units, as the cursor
        return ("the ivy could not grow from %s (%.3g, %.3g, %.3g) (move the 3D cursor to a side of the object)"
                % (where, p[0], p[1], p[2]))


class MESH_OT_banyan_ivy(IvyMixin, bpy.types.Operator):
    """Grow climbing ivy over the selected objects"""
    bl_idname = "mesh.banyan_ivy"
    bl_label = "Add Ivy"
    generator = "ivy"
    execute = live.wrap(IvyMixin.execute)

    host_shape: host_shape_property()
    ground_at_hosts: ground_at_hosts_property()
    start_at_cursor: BoolProperty(name="Start at 3D cursor", default=True,
                                  description="Start at the 3D cursor, placed by the library on the nearest "
                                              "host side where a stem can grow (else the `start` parameter; "
                                              "a preset's start is relative to its hosts). Off when a "
                                              "preset with a start is chosen")
    animate: BoolProperty(name="Growth animation", default=False,
                          description="Add a Geometry Nodes modifier revealing the ivy by birth_step "
                                      "over the scene's frame range")

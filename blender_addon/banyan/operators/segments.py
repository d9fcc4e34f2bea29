"""Add Segment Twigs: a tree of geometry-shader segments from a segments
preset (its segment list), or the random demo tree."""
from .. import api
from .base import NO_PRESET, BanyanOperatorMixin, cursor_location, make_operator

IDNAME = "mesh.banyan_segment_twigs"


class SegmentsMixin(BanyanOperatorMixin):
    def build(self, context, params):
        key = self.banyan_preset if self.banyan_preset != NO_PRESET else None
        at = cursor_location(context)
        objs = api.segment_twigs(preset=key, params=params, collection=context.collection, uv=self.uv_map)
        for o in objs:
            o.location = at
        return objs

    def load_preset_if_changed(self):
        # The preset also supplies the segment list (read in build), so it stays selected.
        BanyanOperatorMixin.load_preset_if_changed(self)


def make_class():
    return make_operator(SegmentsMixin, IDNAME, "Add Segment Twigs",
                         "Branch segments sized for one geometry-shader call, from a segments preset",
                         "segments", {})

"""Update while dragging: whether a change in the redo panel regrows the
plant at once.

Blender answers every change in the redo panel by undoing the operator's
last run and running execute() again with the new values. When that
run returns anything but FINISHED, Blender redoes the undone step, so the
plant built before is back, and the panel keeps the new values. wrap()
uses that: in a redo (Operator.options.is_repeat) it does not call the
generator and returns CANCELLED when

- the values are those the plant on screen was built from (a redo that
  changes nothing, e.g. opening a section of the panel on Blender < 4.1),
- or "Update while dragging" (live_update) is off and Update was not
  pressed: the panel then says the values changed and offers Update,
  a button that regrows once with the values shown.

A run from the menu or Repeat Last always grows. live_update defaults to
on except for the slow generators (SLOW).
"""
from bpy.props import BoolProperty

from ..core.errors import EXPECTED, report_error

SLOW = frozenset(("ivy", "avenue"))  # seconds per run on ordinary hosts
LIVE = "live_update"
UPDATE = "banyan_update"
UI_ONLY = frozenset((LIVE, UPDATE, "banyan_preset_loaded", "rna_type"))

BUILT = {}  # "mesh.banyan_ivy" -> signature of the values the visible plant was built from
RUNS = {}   # "mesh.banyan_ivy" -> generator runs (execute calls that were not skipped), for tests


def properties(generator):
    """The two operator properties (ops/base.complete adds them)."""
    return {
        LIVE: BoolProperty(
            name="Update while dragging", default=generator not in SLOW,
            description="Regrow the plant at every change in this panel. Off: changes wait until you press "
                        "Update (for generators that take seconds)"),
        UPDATE: BoolProperty(
            name="Update", default=False, options={'SKIP_SAVE'},
            description="Regrow the plant once with the values shown"),
    }


def _plain(v):
    try:
        return v if isinstance(v, (str, bytes)) else tuple(v)
    except TypeError:
        return v


def signature(props):
    """Every value of an operator's properties but the panel's own."""
    return tuple((k, _plain(getattr(props, k))) for k in props.bl_rna.properties.keys() if k not in UI_ONLY)


def pending(op):
    """True when the panel's values differ from those of the plant shown."""
    built = BUILT.get(_key(op))
    return built is not None and built != signature(op.properties)


def _key(op):
    return getattr(op, "banyan_idname", None) or op.bl_idname  # "mesh.banyan_ivy"


def _is_redo(op):
    opts = getattr(op, "options", None)
    return bool(getattr(opts, "is_repeat", False))


def wrap(execute):
    """execute() that skips the generator as the module says."""
    def run(self, context):
        props = self.properties
        idname = _key(self)
        if _is_redo(self):
            if getattr(props, UPDATE, False):
                setattr(props, UPDATE, False)
            elif signature(props) == BUILT.get(idname):
                return {'CANCELLED'}  # nothing changed: Blender puts the same plant back
            elif not getattr(props, LIVE, True):
                try:
                    self.load_preset_if_changed()  # so the panel shows a newly chosen preset's values
                except EXPECTED as e:
                    return report_error(self.report, e)
                self.report({'INFO'}, "Banyan: values changed; press Update to regrow")
                return {'CANCELLED'}
        RUNS[idname] = RUNS.get(idname, 0) + 1
        result = execute(self, context)
        if 'FINISHED' in result:
            BUILT[idname] = signature(props)
        return result
    run.__name__ = getattr(execute, "__name__", "execute")
    run.__doc__ = getattr(execute, "__doc__", None)
    return run


def draw_row(layout, op):
    """The "Update while dragging" switch, and Update when it is off."""
    props = op.properties
    row = layout.row(align=True)
    row.use_property_split = False
    row.prop(props, LIVE)
    if not getattr(props, LIVE, True):
        changed = pending(op)
        sub = row.row(align=True)
        sub.alert = changed
        sub.prop(props, UPDATE, toggle=True, icon='FILE_REFRESH', text="Update" if changed else "Up to date")

"""The redo panel of a Banyan operator: the preset row, the operator's own
options, the "Update while dragging" row, then the parameter table in
collapsible sections, one per group of the library's table
(banyan_param_info.group, in the table's order; the first open).

Blender 4.1+ has layout.panel(), whose open state Blender keeps per region
and which does not count as a change of the operator. Older Blender (3.4
to 4.0) gets a box per section with a disclosure triangle bound to a
window-manager property (WindowManager.banyan_sections), never to an
operator property: a click on it must not make the plant differ, and
live.py turns the redo Blender still runs for such a click into a no-op.
"""
import bpy
from bpy.props import BoolVectorProperty, PointerProperty

from . import live
from ..core import presets as PR
from ..core import params as P
from ..core import structs as S
from ..engine.props import prop_name

MAX_SECTIONS = 32  # BoolVectorProperty's largest size


def sections(gen):
    """[(group, [property name, ...])] of gen's table, in the table's order."""
    out = []
    for s in P.specs(gen):
        if not out or out[-1][0] != s.group:
            out.append((s.group, []))
        out[-1][1].append(prop_name(s.name))
    return out


class BANYAN_PG_sections(bpy.types.PropertyGroup):
    """Open state of the redo panel's sections on Blender before 4.1, one
    vector per generator (section i of that generator's table)."""
    __annotations__ = {g: BoolVectorProperty(size=MAX_SECTIONS, default=(True,) + (False,) * (MAX_SECTIONS - 1))
                       for g in S.GENERATORS}


CLASSES = (BANYAN_PG_sections,)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.WindowManager.banyan_sections = PointerProperty(type=BANYAN_PG_sections)


def unregister():
    if hasattr(bpy.types.WindowManager, "banyan_sections"):
        del bpy.types.WindowManager.banyan_sections
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)


def has_layout_panels(layout):
    return hasattr(layout, "panel")  # Blender 4.1+


def section(layout, context, gen, index, title):
    """The body layout of section `index` when it is open, else None."""
    if has_layout_panels(layout):
        header, body = layout.panel("banyan_%s_%d" % (gen, index), default_closed=index > 0)
        header.label(text=title)
        return body
    state = getattr(context.window_manager, "banyan_sections", None) if context else None
    box = layout.box()
    if state is None or index >= MAX_SECTIONS:  # not registered: show everything
        box.label(text=title)
        return box.column()
    is_open = getattr(state, gen)[index]
    head = box.row()
    head.use_property_split = False  # the triangle and the title on the left, as a panel header
    head.alignment = 'LEFT'
    head.prop(state, gen, index=index, text=title, emboss=False,
              icon='DISCLOSURE_TRI_DOWN' if is_open else 'DISCLOSURE_TRI_RIGHT')
    return box.column() if is_open else None


_JUNCTIONS = ("smoothing", "junction_start_scale", "junction_end_scale", "junction_reach", "junction_falloff")
# Fields that do nothing in a mode, greyed out in the redo panel and the
# Plant panel: gen -> [(test on the values, table keys it makes idle)].
# Each is checked against the library (tests/blender/test_ux_new_user.py:
# another value gives the same mesh).
IDLE = {
    "roots": [
        (lambda v: v("surface") == "fused", ("sides",) + _JUNCTIONS),  # the tube mesher's alone
        (lambda v: v("surface") == "tubes", ("fuse_radius", "voxel_size")),
        (lambda v: not v("first_branches"), ("branch_start", "branch_spacing", "branch_vertical", "branch_tilt", "branch_samples",
                                             "branch_jitter", "correction") + _JUNCTIONS),
        (lambda v: not v("second_branches"), ("second_lateral", "second_samples")),
        (lambda v: not v("hugging"), ("hug_range", "hug_pull")),
        (lambda v: not v("ground"), ("ground_z", "ground_step", "soil_reach", "flare", "buttress", "foot_roots")),
        (lambda v: not v("soil_entry"), ("soil_reach", "flare", "buttress")),
        (lambda v: v("germination_auto"), ("germination",)),
    ],
    "ivy": [
        (lambda v: v("ground") == "none", ("ground_z", "ground_branching")),
    ],
}
# An operator option that sets a table value itself: (option, value when
# it does, keys it sets).
OPTION_SETS = [
    ("ground_at_hosts", True, ("ground_z",)),
    ("germinate_at", 'ACTIVE_TOP', ("germination_auto", "germination")),
    ("germinate_at", 'CURSOR', ("germination_auto", "germination")),
    ("start_at_cursor", True, ("start",)),
    ("at_cursor", True, ("position",)),
    ("path_from", 'CURSOR', ("start", "end")),
    ("path_from", 'CURVE', ("start", "end")),
]


def idle(gen, holder, options=None):
    """Property names of gen's table that do nothing with holder's values
    (an operator's properties or a plant's) and the operator options
    (`options`: the operator's properties, or a plant's recorded options)."""

    def value(key):
        return getattr(holder, prop_name(key), None)
    out = set()
    for test, keys in IDLE.get(gen, ()):
        try:
            if test(value):
                out.update(prop_name(k) for k in keys)
        except (AttributeError, TypeError):
            continue
    if options is not None:
        get = options.get if isinstance(options, dict) else (lambda n: getattr(options, n, None))
        for name, when, keys in OPTION_SETS:
            if get(name) == when:
                out.update(prop_name(k) for k in keys)
    return out


def draw_prop(layout, data, name, idle_names, **kw):
    """layout.prop, greyed out (still editable) when the field does nothing now."""
    if name in idle_names:
        layout = layout.row()
        layout.active = False
    layout.prop(data, name, **kw)


def warnings(op, context):
    """What would make this run fail that the panel can say beforehand."""
    props = op.properties
    out = []
    if getattr(props, "path_from", None) == 'CURVE':
        act = getattr(context, "active_object", None) if context else None
        if act is None or act.type != 'CURVE':
            out.append("Path is 'Active curve' but the active object is not a curve")
    key = getattr(props, "banyan_preset", "")
    for bkey, _path, err in PR.broken_presets(op.generator):
        if bkey == key:
            out.append("Preset %s is broken: %s" % (bkey, err))
    return out


def draw_operator(op, context):
    """Operator.draw of every table-driven Banyan operator."""
    layout = op.layout
    props = op.properties
    layout.use_property_split = True
    layout.use_property_decorate = False

    row = layout.row(align=True)
    row.prop(props, "banyan_preset", text="Preset")
    row.operator("banyan.preset_save", text="", icon='ADD').operator = op.banyan_idname
    for text in warnings(op, context):
        box = layout.box()
        box.alert = True
        box.label(text=text, icon='ERROR')

    col = layout.column()
    for name in tuple(getattr(op, "placement_props", ())) + tuple(op.extra_props):
        col.prop(props, name)

    live.draw_row(layout, op)

    off = idle(op.generator, props, props)
    for i, (title, names) in enumerate(sections(op.generator)):
        body = section(layout, context, op.generator, i, title)
        if body is None:
            continue
        body.use_property_split = True
        body.use_property_decorate = False
        for name in names:
            draw_prop(body, props, name, off)

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
from . import presets as PR
from .core import params as P
from .core import structs as S

MAX_SECTIONS = 32  # BoolVectorProperty's largest size


def sections(gen):
    """[(group, [property name, ...])] of gen's table, in the table's order."""
    from .props import prop_name
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

    for i, (title, names) in enumerate(sections(op.generator)):
        body = section(layout, context, op.generator, i, title)
        if body is None:
            continue
        body.use_property_split = True
        body.use_property_decorate = False
        for name in names:
            body.prop(props, name)

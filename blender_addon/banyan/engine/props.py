"""Blender properties generated from a generator's parameter table, and
the way back from property values to a checked params struct.

Each row becomes one property named by the row's key and shown by its
label (banyan_param_info.label, words an artist knows); the tooltip is
the row's description with its range and unit. DOUBLE -> Float ("m" ->
DISTANCE, "deg" -> ANGLE shown in degrees and stored by Blender in
radians, "m/s^2" -> ACCELERATION, "kg" -> MASS, a unitless 0..1 value a
FACTOR slider), INT -> Int, BOOL -> Bool, ENUM -> Enum, VEC3 ->
FloatVector, COLOR -> FloatVector(COLOR, size 4), SEED -> Int (0 ..
2^31-1; larger seeds through banyan.api). Every unit a table uses is in
UNITS, so a new one fails the add-on's tests rather than showing a bare
number. The table's [min, max] is the soft range (the slider range);
values typed or set from Python outside it are refused by the library,
whose message becomes the operator's error report. Defaults come from
the generator's params_init.
"""
import math

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty

from ..core import params as P
from ..core import structs as S

INT_MAX = 2 ** 31 - 1
RESERVED = {"name", "bl_idname", "bl_label", "bl_description", "bl_options", "layout", "options", "properties",
            "rna_type", "macros", "has_reports", "bl_undo_group", "bl_translation_context", "report",
            "bl_cursor_pending"}


def prop_name(key):
    """Blender identifier of a table key ("tree.levels" -> "tree__levels")."""
    key = key.replace(".", "__")
    return "p_" + key if key in RESERVED else key


def _label(key):
    return key.replace(".", ": ").replace("_", " ").capitalize()


# unit of a table row -> (Float property keywords, words for the tooltip).
# "unit" lengths are in the generator's paper units (times its Scale), "r"
# in root radii: Blender has no unit for either, so they stay numbers.
UNITS = {
    "": ({}, ""),
    "m": (dict(subtype='DISTANCE', unit='LENGTH'), "m"),
    "deg": (dict(subtype='ANGLE', unit='ROTATION'), "degrees"),
    "m/s^2": (dict(unit='ACCELERATION'), "m/s\u00b2"),
    "kg": (dict(unit='MASS'), "kg"),
    "N m": ({}, "N\u00b7m"),
    "unit": ({}, "paper units (times Scale)"),
    "1/unit": ({}, "per paper unit"),
    "1/m": ({}, "per metre"),
    "r": ({}, "root radii"),
    "s": ({}, "seconds"),
    "MB": ({}, "MB of resident memory"),
}


def _clip_f32(x):
    """A double as a float32-safe value for Blender (finite, in range)."""
    return max(-3.0e38, min(3.0e38, float(x)))


def _desc(spec):
    d = spec.description
    d = d[:1].upper() + d[1:]
    if spec.type in (S.PT_DOUBLE, S.PT_INT, S.PT_VEC3):
        words = UNITS.get(spec.unit, ({}, spec.unit))[1]
        d += " [%g .. %g%s]" % (spec.min, spec.max, (" " + words) if words else "")
    return d


def wind_key(gen):
    """The parameter that asks the library for wind data."""
    return "tree.wind" if gen == "avenue" else "wind"


def addon_params(gen):
    """Params of gen with the add-on's defaults: the library's, except that
    the wind data is off (docs/addon.md, "Wind data: off unless asked").
    Only the Wind modifier reads its five layers, and they cost about a
    third of a tree's time in Blender; Wind setup and Add Wind turn it on."""
    p = P.Params(gen)
    if wind_key(gen) in p.by_name:
        p.set(wind_key(gen), False)
    return p


def annotations(gen):
    """{property name: bpy property} for every row of gen's table."""
    params = addon_params(gen)
    out = {}
    for s in params.specs:
        v = params.get(s.name)
        kw = dict(name=s.label, description=_desc(s))
        if s.type == S.PT_DOUBLE:
            extra = dict(UNITS.get(s.unit, ({}, ""))[0])
            if s.unit == "deg":
                prop = FloatProperty(default=math.radians(v), soft_min=math.radians(s.min),
                                     soft_max=math.radians(s.max), **extra, **kw)
            else:
                if not extra and s.unit == "" and s.min == 0 and s.max == 1:
                    extra = dict(subtype='FACTOR')  # a 0..1 share or chance: a slider
                prop = FloatProperty(default=_clip_f32(v), soft_min=_clip_f32(s.min), soft_max=_clip_f32(s.max),
                                     precision=4 if s.unit == "m" else 3, **extra, **kw)
        elif s.type == S.PT_INT:
            lo, hi = max(-INT_MAX - 1, int(s.min)), min(INT_MAX, int(s.max))
            prop = IntProperty(default=int(v), soft_min=lo, soft_max=hi, **kw)
        elif s.type == S.PT_BOOL:
            prop = BoolProperty(default=bool(v), **kw)
        elif s.type == S.PT_ENUM:
            items = [(c, _label(c), "") for c in s.choices]
            prop = EnumProperty(items=items, default=v if isinstance(v, str) else s.choices[0], **kw)
        elif s.type == S.PT_VEC3:
            extra = dict(subtype='TRANSLATION', unit='LENGTH') if s.unit == "m" else dict(subtype='XYZ')
            prop = FloatVectorProperty(size=3, default=tuple(_clip_f32(c) for c in v),
                                       soft_min=_clip_f32(s.min), soft_max=_clip_f32(s.max), **extra, **kw)
        elif s.type == S.PT_COLOR:
            prop = FloatVectorProperty(size=4, subtype='COLOR', default=tuple(v), min=0.0, max=1.0, **kw)
        elif s.type == S.PT_SEED:
            prop = IntProperty(default=int(v) if v <= INT_MAX else 0, min=0, soft_max=INT_MAX, **kw)
        else:
            continue
        out[prop_name(s.name)] = prop
    return out


def _nice(x):
    """float32 property value -> the double the user meant (7 digits)."""
    return float("%.7g" % x)


def _snap(x, spec, default):
    """Maps a float32-rounded value onto the exact default or a bound."""
    if isinstance(default, float) and _nice(default) == x:
        return default
    for b in (spec.min, spec.max):
        if b != 0 and abs(x - b) <= 1e-6 * abs(b):
            return b
    return x


_MISSING = object()


def length_props(gen):
    """Property names of gen's lengths in metres (the "m" rows): the ones a
    scene's unit scale applies to (to_params, write_props)."""
    return tuple(prop_name(s.name) for s in P.specs(gen)
                 if s.unit == "m" and s.type in (S.PT_DOUBLE, S.PT_VEC3))


def to_params(gen, holder, skip=(), scale=1.0):
    """A Params of gen filled from holder's properties (an operator or any
    object with the attributes); raises BanyanError on bad values. The
    lengths in metres ("m" rows) are held in Blender units of `scale`
    metres each (the scene's unit scale; 1: metres)."""
    p = addon_params(gen)
    defaults = addon_params(gen)
    for s in p.specs:
        v = getattr(holder, prop_name(s.name), _MISSING)
        if s.name in skip or v is _MISSING:
            continue
        d = defaults.get(s.name)
        k = scale if s.unit == "m" else 1.0
        if s.type == S.PT_DOUBLE:
            x = _nice(math.degrees(v)) if s.unit == "deg" else _nice(_nice(v) * k)
            v = _snap(x, s, d)
        elif s.type == S.PT_VEC3:
            v = tuple(_snap(_nice(_nice(c) * k), s, dc) for c, dc in zip(v, d))
        elif s.type == S.PT_COLOR:
            v = tuple(_snap(_nice(c), s, dc) for c, dc in zip(v, d))
        elif s.type == S.PT_SEED and v == 0 and d > INT_MAX:
            v = d
        p.set(s.name, v)
    return p


def write_props(holder, params, scale=1.0):
    """Copies a Params' values into holder's properties (e.g. after a
    preset); lengths in metres become Blender units of `scale` metres."""
    for s in params.specs:
        name = prop_name(s.name)
        if not hasattr(holder, name):
            continue
        v = params.get(s.name)
        if s.type == S.PT_DOUBLE and s.unit == "deg":
            v = math.radians(v)
        elif s.unit == "m" and scale != 1.0:
            v = tuple(c / scale for c in v) if s.type == S.PT_VEC3 else v / scale
        elif s.type == S.PT_SEED and v > INT_MAX:
            v = 0
        setattr(holder, name, v)


def has_bpy():
    return bpy is not None

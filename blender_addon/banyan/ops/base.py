"""The machinery every Banyan operator shares: properties generated from
the generator's parameter table, the JSON preset menu, and the run:
an operator's prepare() gives an api.Job (the scene read, host sets
built); execute() (scripts, the redo panel, background mode) computes
it on the spot, invoke() in a window on a worker thread under a modal
handler with a progress bar, Esc or right-click cancelling (Runner).
Either way Edit Mode is left first, the objects are built on the main
thread, and a library error or a cancel leaves the scene as it was
(api jobs roll back what they made; the mode is put back)."""
import contextlib
import json
import math
import threading
import time

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty
from bpy_extras.object_utils import AddObjectHelper, add_object_align_init

from .. import api
from ..engine import hosts as H
from ..ui import live
from ..ui import panels
from ..engine import plant
from ..core import presets as PR
from ..engine import props as PP
from ..core import lib as LIB
from ..core.errors import BanyanError, report_error

NO_PRESET = "NONE"
LAST_PARAMS = {}  # bl_idname -> Params of its last successful run (for "save preset")


_items_cache = {}  # Blender needs the enum strings kept alive


def preset_items(gen):
    """The preset menu, the operator's only one: (current values), the
    presets of gen (shipped and the user's) by their titles, then the
    broken ones, greyed by their icon and named with the library's error;
    choosing one reports that error. The tooltip gives the file name."""
    items = [(NO_PRESET, "(current values)", "Keep the values below", 'NONE', 0)]
    good = PR.list_presets(gen)
    titles = [PR.title(key, gen) for key, _path, _desc in good]
    for (key, _path, desc), name in zip(good, titles):
        if titles.count(name) > 1:
            name = key  # two files of one title: their names tell them apart
        items.append((key, name, "%s (%s.json)" % (desc or name, key), 'NONE', len(items)))
    for key, _path, err in PR.broken_presets(gen):
        items.append((key, "%s (broken: %s)" % (PR.title(key, gen), err), "Cannot be used: %s" % err, 'ERROR',
                      len(items)))
    _items_cache[gen] = items
    return items


def why_not(cls, message):
    """poll() failed: say why in the greyed menu entry's tooltip (Blender 3.0+)."""
    if hasattr(cls, "poll_message_set"):
        cls.poll_message_set(message)
    return False


def library_ready(cls):
    if LIB._lib is None:
        return why_not(cls, "The Banyan library is not loaded (see the Banyan tab in the sidebar)")
    return True


class BanyanOperatorMixin:
    """Subclasses set `generator` and implement prepare(context, params) ->
    api.Job. Properties come from complete(), at registration.
    No 'PRESET' option: Blender's own preset menu would be a second one
    beside the JSON presets (banyan_preset)."""
    bl_options = {'REGISTER', 'UNDO'}
    generator = ""
    extra_props = ()  # names of non-table properties, drawn first

    @classmethod
    def poll(cls, context):
        if not library_ready(cls):
            return False
        if getattr(context, "scene", None) is None:
            return why_not(cls, "No scene to add to")
        return True

    def load_preset_if_changed(self, scale=1.0):
        """A newly chosen JSON preset overwrites the table properties once
        (its lengths in metres become Blender units at `scale`, metres per
        unit); later edits in the redo panel then apply on top of it."""
        key = self.banyan_preset or NO_PRESET
        if key == self.banyan_preset_loaded:
            return
        if key != NO_PRESET:
            p = PP.addon_params(self.generator)
            path = PR.find(self.generator, key)
            text = PR.read(path)
            p.apply_preset(text, path)
            PP.write_props(self.properties, p, scale=scale)
            doc = json.loads(text)
            self.preset_loaded(dict(doc.get("params") or {}), bool(doc.get("hosts")))
        self.banyan_preset_loaded = key

    def explicit_values(self):
        """{property: value} the caller gave this call (keywords of
        bpy.ops...(banyan_preset=..., sides=4)), which win over the preset
        loaded with them. Only on an operator's first run: a preset chosen
        later in the redo panel applies whole."""
        props = self.properties
        if props.is_property_set("banyan_preset_loaded"):
            return {}
        names = tuple(self.table_props) + tuple(self.extra_props) + tuple(getattr(self, "placement_props", ()))
        out = {}
        for n in names:
            if props.is_property_set(n):
                v = getattr(props, n)
                out[n] = v if isinstance(v, (str, bool, int, float)) else tuple(v)
        return out

    def to_scene_units(self, context, explicit):
        """Puts the length properties (the table's "m" rows, Line length) in
        the Blender units of the scene's unit scale: a value is a length in
        Blender units, shown in the scene's units, and to_params() gives the
        library metres. Values not yet in this scene's units are converted
        keeping their metres: the defaults (the library's metres) and values
        remembered from a scene of another scale; the caller's own values
        (`explicit`) are Blender units already, as in Blender's own
        operators. Returns the scale (metres per Blender unit)."""
        s = H.unit_scale(context.scene)
        props = self.properties
        was = props.banyan_unit_scale  # 0: never converted (the defaults, in metres)
        if not (math.isfinite(was) and was > 0):
            was = 1.0
        if was != s:
            k = was / s
            for n in self.length_props:
                if n in explicit:
                    continue
                v = getattr(props, n)
                setattr(props, n, tuple(c * k for c in v) if hasattr(v, "__len__") else v * k)
        props.banyan_unit_scale = s
        return s

    def preset_loaded(self, values, has_hosts):
        """A newly chosen preset's own "params" (as written) and whether it
        names hosts: operators switch their options so that the preset
        applies whole (its path, its start)."""

    def params(self, scale=1.0):
        # Through self.properties: each attribute of the operator itself
        # costs a property lookup in Python (bpy_types.Operator), ~30 us.
        return PP.to_params(self.generator, self.properties, scale=scale)

    @property
    def unit_scale(self):
        """Metres per Blender unit of this run (see to_scene_units)."""
        s = getattr(getattr(self, "properties", None), "banyan_unit_scale", 1.0)
        return s if math.isfinite(s) and s > 0 else 1.0

    def preset_doc(self):
        """The chosen JSON preset as written ({} for none or a broken one)."""
        key = self.banyan_preset or NO_PRESET
        if key == NO_PRESET:
            return {}
        try:
            doc = json.loads(PR.read(PR.find(self.generator, key)))
            return doc if isinstance(doc, dict) else {}
        except (ValueError, TypeError, OSError, BanyanError):
            return {}

    def preset_params(self):
        p = self.preset_doc().get("params")
        return dict(p) if isinstance(p, dict) else {}

    def preset_has_hosts(self):
        return bool(self.preset_doc().get("hosts"))

    # Subclasses: prepare(context, params) -> api.Job; optionally
    # place(context, objs) (after the build), preset_loaded(values) and
    # grew_message(job) (a warning when the plant could not grow).
    def prepare(self, context, params):
        raise NotImplementedError

    def place(self, context, objs):
        pass

    def build(self, context, params, progress=None):
        """prepare + compute + build in one go (what execute() runs)."""
        with self.prepare(context, params) as job:
            job.compute(progress)
            objs = job.build()  # in the scene's units (api.from_metres)
        self.place(context, objs)
        return objs

    def _start(self, context):
        """Leaves Edit Mode, then params and the job; None after an error report."""
        self._mode = leave_edit_mode(context)
        try:
            explicit = self.explicit_values()
            scale = self.to_scene_units(context, explicit)
            self.load_preset_if_changed(scale)
            for n, v in explicit.items():  # the caller's keywords win over the preset
                setattr(self.properties, n, v)
            if "ground_z" in explicit and "ground_at_hosts" not in explicit and hasattr(self, "ground_at_hosts"):
                self.properties.ground_at_hosts = False  # a Ground height given wins over the hosts' foot
            params = self.params(scale)
            wind = bool(getattr(self, "wind_setup", False))
            if wind:  # the modifier needs the wind data
                params.set(PP.wind_key(self.generator), True)
            job = self.prepare(context, params)
            # The wind and growth setups (the ivy animates by its own birth_step).
            api.add_setups(job, wind=wind,
                           animate=bool(getattr(self, "animate", False)) and self.generator != "ivy")
            return params, job
        except BaseException as e:
            self._fail(context, e)
            return None

    def _fail(self, context, e, job=None):
        if job is not None:
            job.close()
        restore_mode(context, getattr(self, "_mode", None))
        if api.is_cancelled(e):
            self.report({'INFO'}, "Banyan: cancelled; nothing was added")
            return {'CANCELLED'}
        return report_error(self.report, e)

    def _finish(self, context, params, job):
        """Main thread, the job computed: the objects, then the report."""
        try:
            with job:
                objs = job.build()  # in the scene's units (api.from_metres)
            self.place(context, objs)
        except BaseException as e:
            return self._fail(context, e)
        LAST_PARAMS[self.banyan_idname] = params
        plant.record_operator(self, context, objs, params)  # never raises; first: it reads the selection (hosts, the active curve)
        select_only(context, objs)
        warning = self.grew_message(context, job)
        if warning:
            self.report({'WARNING'}, "Banyan: %s" % warning)
        else:
            nv = sum(len(o.data.vertices) for o in objs if o.type == 'MESH')
            self.report({'INFO'}, "Banyan: %d object(s), %d vertices" % (len(objs), nv))
        return {'FINISHED'}

    def grew_message(self, context, job):
        return None

    def execute(self, context):
        started = self._start(context)
        if started is None:
            return {'CANCELLED'}
        params, job = started
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            job.compute(_sync_progress(wm))
        except BaseException as e:
            return self._fail(context, e, job)
        finally:
            wm.progress_end()
        return self._finish(context, params, job)

    def invoke(self, context, event):
        if bpy.app.background or getattr(context, "window", None) is None:
            return self.execute(context)
        started = self._start(context)
        if started is None:
            return {'CANCELLED'}
        self._params, job = started
        self._runner = Runner(job).start()
        RUNNING.append(self._runner)
        wm = context.window_manager
        self._timer = wm.event_timer_add(TICK, window=context.window)
        self._shown = -1
        wm.progress_begin(0, 100)
        wm.modal_handler_add(self)
        return {'RUNNING_MODAL'}

    # Events that only move the view: passed on while the plant grows.
    VIEW_EVENTS = frozenset(('MIDDLEMOUSE', 'WHEELUPMOUSE', 'WHEELDOWNMOUSE', 'MOUSEMOVE', 'INBETWEEN_MOUSEMOVE',
                             'TRACKPADPAN', 'TRACKPADZOOM', 'MOUSEROTATE', 'NDOF_MOTION'))

    def modal(self, context, event):
        r = self._runner
        if event.type in {'ESC', 'RIGHTMOUSE'} and event.value == 'PRESS':
            r.cancel()
        if event.type == 'TIMER':
            shown = (int(100 * r.done), r.cancelled)
            if shown != getattr(self, "_shown", None):  # redraw the bar and status line only when they change
                self._shown = shown
                context.window_manager.progress_update(shown[0])
                _status(context, "Banyan: growing %s %d %%%s" % (self.generator, shown[0],
                                                                  " (cancelling)" if r.cancelled else
                                                                  " - Esc or right-click to cancel"))
            if r.finished:
                return self._modal_end(context)
        if event.type in self.VIEW_EVENTS:
            return {'PASS_THROUGH'}
        return {'RUNNING_MODAL'}

    def _modal_end(self, context):
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        _status(context, None)
        r = self._runner
        if r in RUNNING:
            RUNNING.remove(r)
        if r.cancelled and r.error is None:
            r.error = api.Cancelled()  # finished before it saw the cancel: dropped all the same
        if r.error is not None:
            return self._fail(context, r.error, r.job)
        result = self._finish(context, self._params, r.job)
        if 'FINISHED' in result:
            _note_built(self)
        return result

    def cancel(self, context):  # Blender ends the modal (window closed, file loaded)
        r = getattr(self, "_runner", None)
        if r is not None:
            if r in RUNNING:
                RUNNING.remove(r)
            r.cancel()
            r.wait()
            r.job.close()
            if self._timer is not None:
                context.window_manager.event_timer_remove(self._timer)
                self._timer = None
            context.window_manager.progress_end()
            _status(context, None)
            restore_mode(context, getattr(self, "_mode", None))

    def draw(self, context):
        panels.draw_operator(self, context)


def cursor_location(context):
    """The 3D cursor's location; BanyanError when it is not finite (a
    script can put it at NaN, and the library would name a parameter the
    user never set)."""
    loc = tuple(context.scene.cursor.location)
    if not all(math.isfinite(c) for c in loc):
        raise BanyanError(2, "the 3D cursor is at (%s); move it to a finite location" % ", ".join(
            "%g" % c for c in loc), "BANYAN_E_RANGE")
    return loc


def cursor_axis(context, k=0):
    """Unit world direction of the 3D cursor's local axis k."""
    d = context.scene.cursor.matrix.to_3x3().col[k]
    if not all(math.isfinite(c) for c in d) or d.length < 1e-9:
        raise BanyanError(2, "the 3D cursor's rotation is not finite; reset it (Shift+C)", "BANYAN_E_RANGE")
    return d.normalized()


@contextlib.contextmanager
def at_cursor_note(active, field, note):
    """Adds `note` to a library error about `field` when the value came
    from the 3D cursor, not from a property the user set."""
    try:
        yield
    except BanyanError as e:
        if not active or not e.message.startswith(field):
            raise
        raise BanyanError(e.status, "%s (%s)" % (e.message, note), e.name) from None


def select_only(context, objs):
    vl = getattr(context, "view_layer", None)
    if vl is None or not objs:
        return
    for o in list(context.selected_objects):
        o.select_set(False)
    for o in objs:
        if o.name in vl.objects:
            o.select_set(True)
    if objs[0].name in vl.objects:
        vl.objects.active = objs[0]


RUNNING = []  # the Runners of modal runs in progress (the sidebar or a test may look)
# s between the modal handler's timer events. Blender's idle event loop
# does not hold the GIL: the worker's progress calls cost about 10 % of the
# run under Xvfb (ivy 450 steps: 2.24 s with, 2.01 s without; there the
# software-drawn window, not the GIL, is what slows the worker).
TICK = 0.1


class Runner:
    """job.compute(progress) on a worker thread (the library's C call
    releases the GIL; its progress callback takes it back). `done` (0..1)
    and `cancelled` are shared with the callback, which returns the
    cancel flag to the library; `error` is what compute raised."""

    def __init__(self, job):
        self.job = job
        self.done = 0.0
        self.cancelled = False
        self.error = None
        self.thread = None
        self.cancelled_at = self.ended_at = None  # time.monotonic(), for tests and the status line

    def progress(self, done):
        self.done = max(self.done, float(done))
        return self.cancelled

    def _run(self):
        try:
            self.job.compute(self.progress)
        except BaseException as e:  # handed to the main thread
            self.error = e
        finally:
            self.ended_at = time.monotonic()

    def start(self):
        self.thread = threading.Thread(target=self._run, name="banyan-grow", daemon=True)
        self.thread.start()
        return self

    def cancel(self):
        if not self.cancelled:
            self.cancelled_at = time.monotonic()
        self.cancelled = True

    @property
    def finished(self):
        return self.thread is not None and not self.thread.is_alive()

    def wait(self, timeout=None):
        if self.thread is not None:
            self.thread.join(timeout)
        return self.finished


def _note_built(op):
    """A run that ended in modal() (not through execute) tells the redo
    panel's "Update while dragging" (live.py) which values the plant on
    screen was built from."""
    key = getattr(op, "banyan_idname", None)
    if key and getattr(op, "properties", None) is not None:
        live.BUILT[key] = live.signature(op.properties)


def _sync_progress(wm):
    def progress(done):
        wm.progress_update(int(100 * done))
        return False  # no way to cancel a synchronous run
    return progress


def _status(context, text):
    ws = getattr(context, "workspace", None)
    if ws is not None:
        with contextlib.suppress(RuntimeError, AttributeError):
            ws.status_text_set(text)


def leave_edit_mode(context):
    """Puts the active object back in Object Mode (the host's edits then
    reach its mesh, and the new plant does not become active beside an
    object left in Edit Mode); returns what restore_mode needs."""
    ob = getattr(context, "active_object", None)
    if ob is None or ob.mode == 'OBJECT' or not bpy.ops.object.mode_set.poll():
        return None
    mode = ob.mode
    bpy.ops.object.mode_set(mode='OBJECT')
    return ob.name, mode


def restore_mode(context, state):
    """The mode leave_edit_mode left, after a failure or a cancel."""
    if not state:
        return
    name, mode = state
    ob = bpy.data.objects.get(name)
    vl = getattr(context, "view_layer", None)
    if ob is None or vl is None or ob.name not in vl.objects:
        return
    vl.objects.active = ob
    ob.select_set(True)
    with contextlib.suppress(RuntimeError):
        bpy.ops.object.mode_set(mode=mode)


class HostsOperatorMixin(BanyanOperatorMixin):
    """An operator whose hosts are the selected objects: with host shape
    Surface every selected object that has a surface (mesh, curve,
    surface, text, metaball) as its evaluated mesh, in one host set built
    per execute; with Bounding box the selected mesh objects' boxes."""

    @classmethod
    def poll(cls, context):
        if not super().poll(context):
            return False
        if any(o.type in H.SURFACE_TYPES for o in getattr(context, "selected_objects", None) or ()):
            return True
        return why_not(cls, "Select the objects to grow on (meshes, curves, text)")

    def selected_hosts(self, context):
        """The selected host objects, the active one first."""
        surface = getattr(self, "host_shape", H.BOX) == H.SURFACE
        types = H.SURFACE_TYPES if surface else ('MESH',)
        hosts = [o for o in context.selected_objects if o.type in types]
        if not hosts:
            raise BanyanError(3, "select one or more %s as hosts" % (
                "objects with a surface (mesh, curve, text)" if surface else "mesh objects"), "BANYAN_E_NO_HOSTS")
        active = context.active_object
        if active in hosts:
            hosts.remove(active)
            hosts.insert(0, active)
        return hosts

    @contextlib.contextmanager
    def host_arg(self, context):
        """What the generator gets: the boxes of the selected meshes (Bounding
        box), or a host set of their surfaces, built once here and freed when
        the block ends (Surface)."""
        hosts = self.selected_hosts(context)
        if self.host_shape == H.BOX:
            yield H.boxes_from_objects(hosts, scale=self.unit_scale)
            return
        with H.surface_host_set(hosts, context.evaluated_depsgraph_get(), scale=self.unit_scale) as hs:
            yield hs


def scene_point(op, point):
    """A point of the scene (Blender units) in the library's metres."""
    s = op.unit_scale
    return tuple(c * s for c in point)


def ground_at_hosts_property():
    return BoolProperty(name="Ground at hosts' foot", default=True,
                        description="Put the ground plane at the lowest point of the hosts, so that the plant reaches "
                                    "their foot and spreads on the ground there (else at Ground height)")


def set_ground_at_hosts(op, params, hosts):
    """The ground plane at the lowest point of the hosts (metres), when the
    operator's Ground at hosts' foot is on; with a preset that has hosts,
    as high above (or below) that point as the preset's ground is above
    its own hosts' lowest point (a boulder sunk into the ground stays so)."""
    if getattr(op, "ground_at_hosts", False):
        api.set_ground_at_hosts(op.generator, params, hosts,
                                op.banyan_preset if op.banyan_preset != NO_PRESET else None)


def host_shape_property():
    return EnumProperty(name="Host shape", default=H.SURFACE, items=H.HOST_SHAPES,
                        description="What the plant grows on: the selected objects' real surfaces (evaluated "
                                    "meshes, modifiers applied) or their oriented bounding boxes")


PLACEMENT_PROPS = ("align", "location", "rotation")


def _is_length(prop):
    """Whether a bpy property definition (a _PropertyDeferred) is a length."""
    kw = getattr(prop, "keywords", None) or {}
    return kw.get("unit") == 'LENGTH'


def preset_property(gen):
    return EnumProperty(name="Preset", items=lambda self, context: preset_items(gen),
                        description="A JSON preset from presets/; applied once when chosen")


def complete(cls):
    """Gives a generator's operator class, before registration, the
    properties that come from the library: the table's rows (PP.annotations)
    after the preset menu, the class's own options, the shared options
    (wind, growth animation, UV map) and "Update while dragging"; with
    AddObjectHelper among its bases, Blender's Align / Location / Rotation
    (place_matrix). Done again at every registration, from the annotations
    written in the class."""
    own = cls.__dict__.get("own_annotations")
    if own is None:
        own = dict(cls.__dict__.get("__annotations__", {}))
        cls.own_annotations = own
    gen = cls.generator
    table = PP.annotations(gen)
    clash = set(table) & (set(own) | {"banyan_preset", "banyan_preset_loaded", "banyan_unit_scale"}
                          | set(live.properties(gen)))
    if clash:
        raise BanyanError(14, "%s: operator property names clash with the table: %s" % (gen, sorted(clash)))
    ann = {}
    ann["banyan_preset"] = preset_property(gen)
    ann["banyan_preset_loaded"] = StringProperty(default=NO_PRESET, options={'HIDDEN'})
    # Metres per Blender unit the length properties hold (0: the defaults, metres).
    ann["banyan_unit_scale"] = FloatProperty(default=0.0, min=0.0, max=1e5, options={'HIDDEN'})
    extra = dict(own)
    extra["wind_setup"] = BoolProperty(name="Wind setup", default=False,
                                       description="Add the Banyan Wind modifier (Geometry Nodes: strength, gusts, "
                                                   "direction, flutter), driven by the plant's wind data")
    if "animate" not in extra:
        extra["animate"] = BoolProperty(name="Growth animation", default=False,
                                        description="Add a Geometry Nodes modifier growing the plant by its birth "
                                                    "attribute over the scene's frame range")
    extra["uv_map"] = BoolProperty(name="UV map", default=True,
                                   description="Copy the library's UVs into a UV map (costs about 0.1 us per "
                                               "triangle corner on top of Blender's own mesh building)")
    ann.update(extra)
    ann.update(live.properties(gen))
    ann.update(table)
    placement = issubclass(cls, AddObjectHelper)
    if placement:
        clash = set(table) & set(PLACEMENT_PROPS)
        if clash:
            raise BanyanError(14, "%s: table names clash with Align/Location/Rotation: %s" % (gen, sorted(clash)))
    cls.__annotations__ = ann
    cls.banyan_idname = cls.bl_idname
    cls.extra_props = tuple(extra)
    cls.table_props = tuple(table)
    cls.length_props = PP.length_props(gen) + tuple(n for n, p in extra.items() if _is_length(p))
    cls.placement_props = PLACEMENT_PROPS if placement else ()
    return cls


def place_matrix(context, op):
    """The new object's world matrix from Align / Location / Rotation, as
    Blender's Add operators compute it (object_utils.add_object_align_init:
    Location defaults to the 3D cursor and is then written back; Align
    View takes the 3D view's rotation, World when there is no view)."""
    sd = getattr(context, "space_data", None)
    if op.align == 'VIEW' and (sd is None or sd.type != 'VIEW_3D'):
        op.align = 'WORLD'
    props = op.properties
    if props.is_property_set("align") and not props.is_property_set("rotation"):
        # An Align given without a Rotation is kept (add_object_align_init
        # would take the preferences' instead, as for a first run); the
        # rotation is then computed from it.
        op.rotation = (0.0, 0.0, 0.0)
    try:
        return add_object_align_init(context, op)
    except AttributeError:  # the preferences' align is View, and there is no view
        op.align = 'WORLD'
        return add_object_align_init(context, op)


class BANYAN_OT_preset_save(bpy.types.Operator):
    """Save the last values of a Banyan operator as a JSON preset (usable by the CLI too)"""
    bl_idname = "banyan.preset_save"
    bl_label = "Save Banyan Preset"
    bl_options = {'REGISTER', 'INTERNAL'}

    operator: StringProperty(name="Operator", options={'HIDDEN', 'SKIP_SAVE'})
    name: StringProperty(name="Name", default="my_preset", options={'SKIP_SAVE'})
    description: StringProperty(name="Description", default="", options={'SKIP_SAVE'})

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        p = LAST_PARAMS.get(self.operator)
        if p is None:
            self.report({'ERROR'}, "Banyan: '%s' has not run yet in this session" % self.operator)
            return {'CANCELLED'}
        try:
            path = PR.save(p.name, self.name, p.to_preset(self.description))
        except (BanyanError, OSError) as e:
            self.report({'ERROR'}, "Banyan: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "Banyan: saved %s" % path)
        return {'FINISHED'}

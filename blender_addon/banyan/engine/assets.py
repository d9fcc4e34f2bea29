"""The shipped presets in Blender's Asset Browser (Blender 4.2 and up).

install() writes one asset library, a folder in the add-on's user data
(the extension's user folder, or <user datafiles>/banyan/assets for the
legacy add-on) holding banyan_presets.blend and its catalog file
blender_assets.cats.txt, and adds it to the preferences' asset libraries
as "Banyan Presets". Each shipped preset is one asset: a small Empty,
named after the preset, in the catalog of its generator
(Banyan/Roots, ...), with the preset's description and the gallery's
thumbnail (docs/img/presets, shipped in presets/thumbnails/) as its
preview. The library is written again when the shipped presets or the
add-on's version change.

Dragging an asset into the 3D view appends its Empty where it is
dropped. A depsgraph handler sees the new Empty and, on a timer (not
inside the depsgraph update), grow_pending() grows the preset through
banyan.api in its place: a tree or an avenue, twigs, at the drop point;
roots and ivy around the selected mesh objects when there are some,
else on the preset's own hosts, moved to the drop point. The Empty is
removed once the plant is there; a failure leaves it, renamed to say
why, and prints the error."""
import hashlib
import os
import uuid

import bpy

from .. import api
from ..core import lib
from ..core import presets as core_presets
from ..core.structs import GENERATORS

LIBRARY_NAME = "Banyan Presets"
BLEND = "banyan_presets.blend"
CATS = "blender_assets.cats.txt"
STAMP = "banyan_presets.stamp"
PRESET_PROP = "banyan_asset_preset"
GENERATOR_PROP = "banyan_asset_generator"
PREVIEW_SIZE = 256
# One catalog a generator; the ids are fixed so a user's own catalogs and
# saved files keep pointing at them across versions.
CATALOGS = {gen: (str(uuid.uuid5(uuid.NAMESPACE_URL, "banyan/catalog/" + gen)), "Banyan/" + title)
            for gen, title in (("roots", "Roots"), ("keyaki", "Keyaki"), ("avenue", "Avenues"), ("ivy", "Ivy"),
                               ("segments", "Segments"))}
assert set(CATALOGS) == set(GENERATORS)


def supported():
    """The Asset Browser with catalogs and Python-made previews: 4.2 on."""
    return bpy.app.version >= (4, 2, 0)


ADDON = __package__.rpartition(".")[0]  # "banyan" or "bl_ext.<repository>.banyan"


def library_dir(create=True):
    """The library's folder (None when Blender gives no user folder)."""
    try:
        d = bpy.utils.extension_path_user(ADDON, path="assets", create=create)
    except (ValueError, AttributeError):  # the legacy add-on: not an extension
        d = bpy.utils.user_resource('DATAFILES', path=os.path.join("banyan", "assets"), create=create)
    return d or None


def shipped_presets():
    """[(key, path, generator, description)] of the presets that ship with
    the add-on (not a user's own), by generator then key."""
    shipped = {os.path.realpath(d) for d in core_presets.shipped_dirs()}
    out = []
    for gen in GENERATORS:
        for key, path, desc in core_presets.list_presets(gen):
            if os.path.realpath(os.path.dirname(path)) in shipped:
                out.append((key, path, gen, desc))
    return out


def thumbnail(key):
    """The gallery picture of preset `key`, or None."""
    for d in core_presets.shipped_dirs():  # the zips' presets/thumbnails/, the repository's docs/img/presets/
        for p in (os.path.join(d, "thumbnails", key + ".png"),
                  os.path.join(d, "..", "docs", "img", "presets", key + ".png")):
            if os.path.isfile(p):
                return os.path.normpath(p)
    return None


def _stamp(items):
    h = hashlib.sha256(("%s|%s" % (lib.version(), bpy.app.version_string)).encode())
    for key, path, gen, desc in items:
        with open(path, "rb") as f:
            h.update(key.encode() + b"\0" + f.read())
        t = thumbnail(key)
        h.update(b"thumb:" + (str(os.path.getsize(t)).encode() if t else b"-"))
    return h.hexdigest()


def _preview(obj, path):
    """The picture at path as obj's preview, its longer side PREVIEW_SIZE."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        s = PREVIEW_SIZE / max(w, h, 1)
        w, h = max(1, round(w * s)), max(1, round(h * s))
        img.scale(w, h)
        px = [0.0] * (4 * w * h)
        img.pixels.foreach_get(px)
    finally:
        bpy.data.images.remove(img)
    p = obj.preview_ensure()
    p.image_size = (w, h)
    p.image_pixels_float.foreach_set(px)


def _write_cats(directory):
    lines = ["# Banyan's preset catalogs (written by the add-on; engine/assets.py).", "VERSION 1", ""]
    lines += ["%s:%s:%s" % (cid, path, path.replace("/", "-")) for cid, path in CATALOGS.values()]
    tmp = os.path.join(directory, "." + CATS + ".tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, os.path.join(directory, CATS))


def build(directory):
    """Writes the library into directory (the .blend by rename, then the
    catalogs and the stamp); returns the number of assets."""
    items = shipped_presets()
    objs = []
    try:
        for key, path, gen, desc in items:
            o = bpy.data.objects.new(key, None)
            o.empty_display_type = 'SINGLE_ARROW'
            o[PRESET_PROP] = key
            o[GENERATOR_PROP] = gen
            o.asset_mark()
            o.asset_data.description = desc or core_presets.title(key, gen)
            o.asset_data.catalog_id = CATALOGS[gen][0]
            o.asset_data.tags.new(gen)
            if hasattr(o.asset_data, "use_preferred_import_method"):  # 5.x: each drop a new Empty
                o.asset_data.use_preferred_import_method = True
                o.asset_data.preferred_import_method = 'APPEND'
            t = thumbnail(key)
            if t:
                _preview(o, t)
            objs.append(o)
        tmp = os.path.join(directory, ".tmp_" + BLEND)
        bpy.data.libraries.write(tmp, set(objs), fake_user=True)
        os.replace(tmp, os.path.join(directory, BLEND))
    finally:
        for o in objs:
            bpy.data.objects.remove(o)
    _write_cats(directory)
    with open(os.path.join(directory, STAMP), "w") as f:
        f.write(_stamp(items))
    return len(items)


def install(directory=None):
    """Builds the library (in library_dir(), or `directory`) where it is
    missing or stale and adds it to the preferences' asset libraries
    (once); returns (directory, assets built now or 0)."""
    if not supported():
        raise RuntimeError("the Asset Browser's preset catalog needs Blender 4.2 or later (this is %s)"
                           % bpy.app.version_string)
    d = directory or library_dir(create=True)
    if not d:
        raise RuntimeError("Blender gives no user folder for the asset library")
    os.makedirs(d, exist_ok=True)
    built = 0
    try:
        with open(os.path.join(d, STAMP)) as f:
            fresh = f.read() == _stamp(shipped_presets()) and os.path.isfile(os.path.join(d, BLEND))
    except OSError:
        fresh = False
    if not fresh:
        built = build(d)
    libs = bpy.context.preferences.filepaths.asset_libraries
    if not any(os.path.realpath(bpy.path.abspath(x.path)) == os.path.realpath(d) for x in libs):
        libs.new(name=LIBRARY_NAME, directory=d)
    return d, built


def _entries(directory=None):
    """The preferences' asset libraries that are this library: by name, or
    by its folder (library_dir(), or `directory`)."""
    d = directory or library_dir(create=False)
    return [x for x in bpy.context.preferences.filepaths.asset_libraries
            if x.name == LIBRARY_NAME or (d and os.path.realpath(bpy.path.abspath(x.path)) == os.path.realpath(d))]


def installed(directory=None):
    """Whether the preferences list the library."""
    return supported() and bool(_entries(directory))


def uninstall(directory=None):
    """Takes the library out of the preferences (its folder stays);
    returns how many entries went."""
    gone = _entries(directory)
    libs = bpy.context.preferences.filepaths.asset_libraries
    for x in gone:
        libs.remove(x)
    return len(gone)


# ------------------------------------------------------------------ drops


def _pending(scene):
    return [o for o in scene.objects if o.type == 'EMPTY' and o.library is None and PRESET_PROP in o
            and not o.get("banyan_asset_failed")]


def grow_from_asset(empty, context=None):
    """Grows the preset the Empty stands for in its place; returns the
    objects made. The Empty is removed."""
    context = context or bpy.context
    key, gen = str(empty[PRESET_PROP]), str(empty.get(GENERATOR_PROP, ""))
    at = empty.matrix_world.translation.copy()
    hosts = [o for o in context.selected_objects if o.type == 'MESH' and o != empty] if gen in ("roots", "ivy") else []
    if gen == "keyaki":
        objs = api.keyaki_tree(preset=key, position=tuple(at))
    elif gen == "avenue":
        objs = api.keyaki_avenue(preset=key)
    elif gen == "segments":
        objs = api.segment_twigs(preset=key)
    elif gen == "roots":
        objs = api.strangler_roots(hosts, preset=key)
    elif gen == "ivy":
        objs = api.ivy(hosts, preset=key)
    else:
        raise ValueError("%s: unknown generator '%s'" % (empty.name, gen))
    if gen != "keyaki" and not hosts and objs:  # moved so that the plant stands where it was dropped
        context.view_layer.update()
        shift = at - objs[0].matrix_world.translation
        for o in objs:
            if o.parent is None:
                o.location += shift
    bpy.data.objects.remove(empty)
    return objs


def grow_pending():
    """Grows every dropped preset Empty of the current scene; a timer
    callback (returns None: runs once)."""
    scene = bpy.context.scene
    bpy.context.view_layer.update()  # the drop point in the Empties' world matrices
    for empty in _pending(scene):
        name = empty.name
        try:
            grow_from_asset(empty)
        except Exception as e:  # the Empty stays, saying why
            print("banyan: the dropped preset %s could not grow: %s" % (name, e))
            empty["banyan_asset_failed"] = str(e)[:200]
            empty.name = (name + " (failed)")[:63]
    return None


@bpy.app.handlers.persistent
def _on_depsgraph(scene, depsgraph=None):
    """Looks only at the IDs this update touched (a drop adds its Empty):
    a scene of many objects pays nothing on its other updates."""
    if bpy.app.timers.is_registered(grow_pending):
        return
    ids = (u.id for u in depsgraph.updates) if depsgraph is not None else ()
    if any(isinstance(i, bpy.types.Object) and PRESET_PROP in i.original for i in ids):
        bpy.app.timers.register(grow_pending, first_interval=0.0)


def register():
    if supported() and _on_depsgraph not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(_on_depsgraph)


def unregister():
    if _on_depsgraph in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_on_depsgraph)
    if bpy.app.timers.is_registered(grow_pending):
        bpy.app.timers.unregister(grow_pending)

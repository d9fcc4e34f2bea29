"""The shipped presets in the Asset Browser (engine/assets.py, Blender 4.2
on): the library written into a folder of its own holds one asset a
shipped preset, in its generator's catalog (the catalog file lists the
five), with the preset's description and the gallery's picture as its
preview; installing adds it to the preferences once, and again is free; the
remove operator takes it out again (its folder stays);
a drop, done as Blender's drag does it (the asset's Empty appended and
linked where it lands), grows the preset there through the depsgraph
handler's callback: a keyaki at the drop point, twigs moved to it, roots
around the selected cube; the Empty is removed. A failing preset leaves
its Empty, renamed. In Blender 3.4 the operator is unavailable and says
why."""
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bt  # noqa: E402

import bpy  # noqa: E402

OUT = os.path.join(bt.OUT_DIR, "assets_%d_%d" % bpy.app.version[:2])


def module():
    for name in ("bl_ext.user_default.banyan", "banyan"):
        m = sys.modules.get(name + ".engine.assets")
        if m:
            return m
    import importlib
    return importlib.import_module(bt.ADDON + ".engine.assets" if hasattr(bt, "ADDON") else "banyan.engine.assets")


def drop(path, key, at):
    """What a drag from the Asset Browser does: the asset's object appended
    and linked into the scene where it lands."""
    with bpy.data.libraries.load(path, link=False, assets_only=True) as (src, dst):
        dst.objects = [key]
    o = dst.objects[0]
    bpy.context.scene.collection.objects.link(o)
    o.location = at
    return o


def main():
    A = module()
    if not A.supported():
        bt.check(not bpy.ops.banyan.presets_to_assets.poll(), "the operator is unavailable before 4.2")
        return
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    items = A.shipped_presets()
    n = A.build(OUT)
    bt.check(n == len(items) and n >= 29, "%d assets for %d shipped presets" % (n, len(items)))
    cats = open(os.path.join(OUT, A.CATS)).read()
    for gen, (cid, path) in A.CATALOGS.items():
        bt.check("%s:%s:" % (cid, path) in cats, "catalog %s in %s" % (path, A.CATS))
    blend = os.path.join(OUT, A.BLEND)
    with bpy.data.libraries.load(blend, assets_only=True) as (src, dst):
        names = list(src.objects)
        dst.objects = list(src.objects)
    bt.check(sorted(names) == sorted(k for k, _, _, _ in items), "one asset a preset: %s" % names[:5])
    by = {o.name: o for o in dst.objects}
    for key, path, gen, desc in items:
        o = by.get(key)
        ok = o is not None and o.asset_data is not None
        bt.check(ok and o.asset_data.catalog_id == A.CATALOGS[gen][0] and o[A.PRESET_PROP] == key,
                 "%s: in the %s catalog, naming its preset" % (key, gen))
        bt.check(ok and o.asset_data.description, "%s: a description" % key)
        if ok and A.thumbnail(key):
            p = o.preview
            bt.check(p is not None and p.image_size[0] == A.PREVIEW_SIZE and max(p.image_pixels_float[:4000]) > 0,
                     "%s: the gallery picture as preview: %s" % (key, p and tuple(p.image_size)))
    for o in dst.objects:
        bpy.data.objects.remove(o)
    bt.check(all(A.thumbnail(k) for k, _, _, _ in items), "every shipped preset has a thumbnail")

    # install: into the preferences once
    libs = bpy.context.preferences.filepaths.asset_libraries
    before = len(libs)
    home = os.path.join(OUT, "installed")
    d, built = A.install(home)
    bt.check(d == home and built == n and len(libs) == before + 1 and any(x.name == A.LIBRARY_NAME for x in libs),
             "installed once, built")
    d2, built2 = A.install(home)
    bt.check(d2 == d and built2 == 0 and len(libs) == before + 1, "installing again is free")
    with open(os.path.join(home, A.STAMP), "w") as f:
        f.write("an older add-on")
    bt.check(A.install(home)[1] == n and len(libs) == before + 1, "a stale library is written again")
    bt.check(A.installed(home) and bpy.ops.banyan.presets_from_assets.poll(), "the remove operator is offered")
    bt.check(bpy.ops.banyan.presets_from_assets() == {'FINISHED'} and len(libs) == before and not A.installed(home),
             "the remove operator takes the library out of the preferences")
    bt.check(os.path.isfile(os.path.join(home, A.BLEND)), "its folder stays")
    bt.check(not bpy.ops.banyan.presets_from_assets.poll(), "with nothing to remove the operator is unavailable")
    A.install(home)
    bt.check(A.uninstall(home) == 1 and len(libs) == before, "uninstalled")

    # drops
    bt.check(A._on_depsgraph in bpy.app.handlers.depsgraph_update_post, "the drop handler is registered")
    scene = bpy.context.scene
    made = set(bpy.data.objects)
    bpy.context.view_layer.update()
    bt.check(not bpy.app.timers.is_registered(A.grow_pending), "an update without a drop schedules nothing")
    e = drop(blend, "keyaki_young", (6.0, -2.0, 0.0))
    bpy.context.view_layer.update()  # Blender's update after the drop runs the handler
    bt.check(bpy.app.timers.is_registered(A.grow_pending), "a drop schedules the growth")
    bpy.app.timers.unregister(A.grow_pending)
    A.grow_pending()
    bpy.context.view_layer.update()
    trees = [o for o in bpy.data.objects if o not in made and o.type == 'MESH']
    bt.check(len(trees) == 1 and (trees[0].location - __import__("mathutils").Vector((6, -2, 0))).length < 1e-4,
             "the keyaki stands where it was dropped: %s" % [tuple(o.location) for o in trees])
    bt.check("keyaki_young" not in bpy.data.objects, "the Empty is gone")
    e = drop(blend, "segments_paper", (0.0, 5.0, 1.0))
    made = set(bpy.data.objects)
    A.grow_pending()
    bpy.context.view_layer.update()
    new = [o for o in bpy.data.objects if o not in made and o.type == 'MESH']
    bt.check(len(new) >= 1 and (new[0].matrix_world.translation - __import__("mathutils").Vector((0, 5, 1))).length
             < 1e-4, "twigs moved to the drop point: %s" % [tuple(o.matrix_world.translation) for o in new])
    bpy.ops.mesh.primitive_cube_add(location=(10, 10, 1))
    cube = bpy.context.active_object
    for o in scene.objects:
        o.select_set(o == cube)
    e = drop(blend, "roots_column", (0.0, 0.0, 0.0))
    made = set(bpy.data.objects)
    A.grow_pending()
    bpy.context.view_layer.update()
    new = [o for o in bpy.data.objects if o not in made and o.type == 'MESH']
    plant = new[0] if new else None
    rec = getattr(plant, "banyan_plant", None) if plant else None
    hosts = [h.object for h in rec.hosts] if rec is not None else []
    bt.check(plant is not None and (plant.matrix_world.translation.xy - cube.location.xy).length < 2.0,
             "roots grow around the selected cube: %s" % str(plant and tuple(plant.matrix_world.translation)))
    bt.check(cube in hosts and rec.generator == "roots", "the plant's record: roots, the cube its host")
    e = drop(blend, "keyaki_young", (0.0, 0.0, 0.0))
    e[A.PRESET_PROP] = "no_such_preset"
    A.grow_pending()
    bt.check(e.name.endswith("(failed)") and e.get("banyan_asset_failed"), "a failing drop leaves its Empty, saying why")


main()
bt.done()

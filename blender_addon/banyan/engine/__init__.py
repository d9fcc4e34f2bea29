"""The bpy side of a run: jobs (jobs.py, one per generator in grow.py),
placement, host objects, the mesh hand-off, materials, wind, growth
animation, levels of detail, instances, the plant's record and
Regenerate. No operator, panel or property group of the UI here."""


def register():
    # Imported here: the package itself imports without bpy (the add-on's
    # __init__ takes the glTF import hook from it in plain Python too).
    from . import assets, plant
    plant.register()  # Object.banyan_plant and its per-generator views
    assets.register()  # presets dropped from the Asset Browser grow


def unregister():
    from . import assets, plant
    assets.unregister()
    plant.unregister()

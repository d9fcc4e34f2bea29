"""--set arguments that make a preset's file small with the same parts,
materials and attributes: the file-format tests write every preset this
way (tests/blender/test_gltf_import.py, tests/usd/test_usd_presets.py)."""


def shrink(gen, params):
    """--set values ("key=value") for a preset of generator `gen` with `params`."""
    if gen == "keyaki":
        return ["levels=%d" % min(params.get("levels", 21), 6)]
    if gen == "avenue":
        return ["placement=count", "count=1", "tree.levels=%d" % min(params.get("tree.levels", 21), 6)]
    if gen == "ivy":
        return ["steps=%d" % min(params.get("steps", 450), 50)]
    if gen == "roots":
        return ["growth_points=%d" % min(params.get("growth_points", 40), 6),
                "main_roots=%d" % min(params.get("main_roots", 6), 3)]
    if gen == "segments" and "demo_segments" in params:
        return ["demo_segments=%d" % min(params["demo_segments"], 30)]
    return []

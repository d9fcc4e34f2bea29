"""The JSON presets shipped in presets/ (no bpy needed).

Looked up in banyan/presets/ (the zip carries a copy) and, for an add-on
used from the repository, in <repo>/presets/. A preset belongs to the
generator its "generator" key names. User presets are Blender's own
operator presets (bl_options 'PRESET'), saved from the redo panel.
"""
import json
import os

from .core import lib
from .core.errors import PresetNotFound


def user_dir(create=False):
    """Where users' own JSON presets go: <user scripts>/presets/banyan
    (None outside Blender)."""
    try:
        import bpy
    except ImportError:
        return None
    return bpy.utils.user_resource('SCRIPTS', path=os.path.join("presets", "banyan"), create=create) or None


def preset_dirs():
    """User presets first (they may shadow shipped ones), then shipped."""
    out = []
    u = user_dir()
    if u:
        out.append(u)
    out.append(os.path.join(lib.package_dir(), "presets"))
    real = os.path.dirname(os.path.realpath(os.path.join(lib.package_dir(), "__init__.py")))
    out.append(os.path.normpath(os.path.join(real, "..", "..", "presets")))
    return [d for d in out if os.path.isdir(d)]


NAME_MAX = 64  # characters of a user preset's name kept in its file name
_parsed = {}  # path -> (mtime_ns, generator, description): presets are read once per change


def _preset_info(path):
    """(generator, description) of a preset file, or None; cached by mtime."""
    try:
        mtime = os.stat(path).st_mtime_ns
    except OSError:
        return None
    hit = _parsed.get(path)
    if hit and hit[0] == mtime:
        return hit[1:]
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        doc = None
    info = (doc.get("generator"), str(doc.get("description", ""))) if isinstance(doc, dict) else (None, "")
    _parsed[path] = (mtime,) + info
    return info


def list_presets(generator):
    """[(key, path, description)] of the presets for generator, by key.
    Blender asks for these on every operator call (the preset enum), so
    files are parsed only when they change."""
    seen = {}
    for d in preset_dirs():
        for fn in sorted(os.listdir(d)):
            if not fn.endswith(".json"):
                continue
            key = fn[:-5]
            if key in seen:
                continue
            path = os.path.join(d, fn)
            info = _preset_info(path)
            if info and info[0] == generator:
                seen[key] = (key, path, info[1])
    return [seen[k] for k in sorted(seen)]


def find(generator, key):
    """Path of preset `key` (file name without .json) or a path as given;
    PresetNotFound (a BanyanError and a FileNotFoundError) if neither."""
    if not isinstance(key, (str, os.PathLike)):
        raise TypeError("a preset is a name or a path, not %s" % type(key).__name__)
    if os.path.isfile(key):
        return key
    for k, path, _ in list_presets(generator):
        if k == key:
            return path
    raise PresetNotFound("no %s preset '%s' (have: %s)" % (
        generator, key, ", ".join(k for k, _, _ in list_presets(generator)) or "none"))


def save(generator, name, text):
    """Writes a user preset <user dir>/<generator>_<name>.json; returns its path."""
    d = user_dir(create=True)
    if not d:
        raise OSError("no user preset directory")
    safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in name.strip()[:NAME_MAX]) or "preset"
    key = safe if safe.startswith(generator + "_") else "%s_%s" % (generator, safe)
    path = os.path.join(d, key + ".json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def read(path):
    with open(path, "rb") as f:
        return f.read()

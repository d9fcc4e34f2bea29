"""The JSON presets shipped in presets/ (no bpy needed).

Looked up in banyan/presets/ (the zip carries a copy) and, for an add-on
used from the repository, in <repo>/presets/. A preset belongs to the
generator its "generator" key names. User presets are JSON files too,
saved by the redo panel's `+` (save()) into user_dir(), and listed in the
same menu, each under a readable title().
"""
import json
import os

from .core import lib
from .core.atomic_file import write_atomic
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
_parsed = {}  # path -> (mtime_ns, generator, description, error): presets are read once per change


def _guess_generator(path):
    """The generator a preset file is named after ("ivy_wall.json" -> "ivy"), or None."""
    from .core.structs import GENERATORS
    head = os.path.basename(path).split("_", 1)[0].split(".", 1)[0]
    return head if head in GENERATORS else None


def _library_error(generator, data, path):
    """The library's message refusing preset `data` ("<file>:<line>: ..."), or
    "" when it applies; "" too when the library or the generator is missing."""
    from .core.errors import BanyanError, GeneratorMissing, LoadError
    try:
        from .core.params import Params
        Params(generator).apply_preset(data, os.path.basename(path))
    except (GeneratorMissing, LoadError):
        return ""  # nothing to check it with; the JSON checks below still run
    except BanyanError as e:
        return e.message
    except OSError:
        return ""
    return ""


def _preset_info(path):
    """(generator, description, error) of a preset file, or None when it
    cannot be read; error is "" for a good preset. Cached by mtime."""
    try:
        mtime = os.stat(path).st_mtime_ns
        hit = _parsed.get(path)
        if hit and hit[0] == mtime:
            return hit[1:]
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    try:
        doc = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError):
        doc = None
    gen = doc.get("generator") if isinstance(doc, dict) else None
    desc = str(doc.get("description", "")) if isinstance(doc, dict) else ""
    if not isinstance(gen, str):
        gen = None
    lib_gen = gen if gen in _known() else _guess_generator(path)
    name = os.path.basename(path)
    if isinstance(doc, dict) and not lib_gen:
        error = "%s: \"generator\" is %s, not one of %s" % (name, json.dumps(doc.get("generator")),
                                                              ", ".join(_known()))
    else:
        # The library's own reading (for any generator when the JSON does not
        # even parse: then its syntax message is what matters).
        error = _library_error(lib_gen or _known()[0], data, path)
        if not error and not isinstance(doc, dict):
            error = "%s: not a JSON object" % name
    info = (gen if gen in _known() else lib_gen, desc, error)
    _parsed[path] = (mtime,) + info
    return info


def _known():
    from .core.structs import GENERATORS
    return GENERATORS


def _scan():
    """{key: (key, path, generator, description, error)}, user files first."""
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
            if info:
                seen[key] = (key, path) + info
    return seen


def list_presets(generator):
    """[(key, path, description)] of the good presets for generator, by key.
    Blender asks for these on every operator call (the preset enum), so
    files are parsed only when they change."""
    seen = _scan()
    return [(k, e[1], e[3]) for k, e in sorted(seen.items()) if e[2] == generator and not e[4]]


def broken_presets(generator=None):
    """[(key, path, error)] of the preset files the library refuses, for
    generator (by their "generator" key, else their file name's prefix;
    None: all). They are listed, never hidden."""
    seen = _scan()
    return [(k, e[1], e[4]) for k, e in sorted(seen.items())
            if e[4] and (generator is None or e[2] == generator or e[2] is None)]


def title(key, generator=None):
    """A preset's menu name: its file name without the generator's prefix,
    in words ("roots_mature_fig" -> "Mature fig")."""
    gen = generator or _guess_generator(key + ".json")
    words = key[len(gen) + 1:] if gen and key.startswith(gen + "_") and len(key) > len(gen) + 1 else key
    words = " ".join(words.replace("_", " ").replace("-", " ").split()) or key
    return words[:1].upper() + words[1:]


def find(generator, key):
    """Path of preset `key` (file name without .json) or a path as given;
    PresetNotFound (a BanyanError and a FileNotFoundError) if neither."""
    if not isinstance(key, (str, os.PathLike)):
        raise TypeError("a preset is a name or a path, not %s" % type(key).__name__)
    if os.path.isfile(key):
        return key
    for k, path, _ in list_presets(generator) + broken_presets(generator):
        if k == key:
            return path  # a broken one too: reading it gives the library's error
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
    write_atomic(path, text)  # a failed save keeps the old preset of that name
    return path


def read(path):
    with open(path, "rb") as f:
        return f.read()

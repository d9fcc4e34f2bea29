"""The JSON presets shipped in presets/ (no bpy needed).

Looked up in banyan/presets/ (the zip carries a copy) and, for an add-on
used from the repository, in <repo>/presets/. A preset belongs to the
generator its "generator" key names. User presets are JSON files too,
saved by the redo panel's `+` (save()) into user_dir(), and listed in the
same menu, each under a readable title().

Only regular files (after following links) of at most MAX_BYTES are read:
a FIFO, a device, a folder or a dangling link named like a preset, or a
file too large, is listed among the broken presets with the reason,
never read (a FIFO would block, /dev/zero would fill the memory). Keys
and messages spell file names with control characters and bytes that
are not UTF-8 escaped.
"""
import json
import os
import stat

from . import lib
from .atomic_file import write_atomic
from .errors import BanyanError, LoadError, PresetNotFound
from .params import Params
from .structs import GENERATORS


def user_dir(create=False):
    """Where users' own JSON presets go: <user scripts>/presets/banyan
    (None outside Blender)."""
    try:
        import bpy
    except ImportError:
        return None
    return bpy.utils.user_resource('SCRIPTS', path=os.path.join("presets", "banyan"), create=create) or None


def shipped_dirs():
    """The presets that ship: the package's presets/, then (an add-on run
    from the repository) the repository's."""
    real = os.path.dirname(os.path.realpath(os.path.join(lib.package_dir(), "__init__.py")))
    out = [os.path.join(lib.package_dir(), "presets"), os.path.normpath(os.path.join(real, "..", "..", "presets"))]
    return [d for d in out if os.path.isdir(d)]


def preset_dirs():
    """User presets first (they may shadow shipped ones), then shipped."""
    u = user_dir()
    return ([u] if u and os.path.isdir(u) else []) + shipped_dirs()


NAME_MAX = 64  # characters of a user preset's name kept in its file name
MAX_BYTES = 4 << 20  # the library's BANYAN_PRESET_MAX_BYTES: it refuses longer preset texts
_parsed = {}  # path -> (mtime_ns, size, generator, description, error): presets are read once per change
IO_ERROR = 9  # BANYAN_E_IO
LIMIT = 11  # BANYAN_E_LIMIT

_KINDS = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a folder"))


def _not_regular(mode):
    """Why a file of this st_mode cannot be a preset, or "" for a regular file."""
    if stat.S_ISREG(mode):
        return ""
    return next((what for test, what in _KINDS if test(mode)), "a special file")


def _printable(text):
    """text with control characters escaped (\\x1b), for messages."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))


def _refuse(path, why, status=IO_ERROR):
    return BanyanError(status, "%s: %s" % (_printable(os.path.basename(path)), why),
                       "BANYAN_E_LIMIT" if status == LIMIT else "BANYAN_E_IO")


def _missing(path):
    """PresetNotFound for a path that is not there: a dangling link says
    where it points."""
    try:
        target = os.readlink(path)
    except OSError:
        return PresetNotFound("%s: no such file" % _printable(path))
    return PresetNotFound("%s: is a link to a missing file (%s): remove it or put a JSON preset there"
                          % (_printable(os.path.basename(path)), _printable(target)))


def _checked(path, st):
    """Refuses (BanyanError) a file that is not a regular one or is larger than MAX_BYTES."""
    why = _not_regular(st.st_mode)
    if why:
        if os.path.islink(path):
            why = "a link to %s (%s)" % (why, _printable(os.path.realpath(path)))
        raise _refuse(path, "is %s, not a preset file: remove it or put a JSON preset there" % why)
    if st.st_size > MAX_BYTES:
        raise _refuse(path, "is %d bytes; a preset takes at most %d (%d MiB)" % (st.st_size, MAX_BYTES,
                                                                                 MAX_BYTES >> 20), LIMIT)


def _guess_generator(path):
    """The generator a preset file is named after ("ivy_wall.json" -> "ivy"), or None."""
    head = os.path.basename(path).split("_", 1)[0].split(".", 1)[0]
    return head if head in GENERATORS else None


def _library_error(generator, data, path):
    """The library's message refusing preset `data` ("<file>:<line>: ..."), or
    "" when it applies; "" too when there is no library to ask (plain Python)."""
    try:
        Params(generator).apply_preset(data, _printable(os.path.basename(path)))
    except LoadError:
        return ""  # nothing to check it with; the JSON checks below still run
    except BanyanError as e:
        return e.message
    except OSError:
        return ""
    return ""


def _preset_info(path):
    """(generator, description, error) of a preset file, or None when it
    vanished; error is "" for a good preset. A file that cannot be read
    (not a regular file, too large, no permission) gets the reason as its
    error. Cached by modification time and size."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        if not os.path.islink(path):
            return None  # removed since it was listed
        return (_guess_generator(path), "", _missing(path).message)
    except OSError as e:
        return (_guess_generator(path), "", "%s: %s" % (_printable(os.path.basename(path)), e.strerror or e))
    hit = _parsed.get(path)
    if hit and hit[:2] == (st.st_mtime_ns, st.st_size):
        return hit[2:]
    try:
        data = read(path)
    except FileNotFoundError:
        return None  # removed since it was listed
    except BanyanError as e:
        return (_guess_generator(path), "", e.message)  # not cached: a FIFO's mtime moves as it is written
    try:
        doc = json.loads(data.decode("utf-8"))
    except (ValueError, RecursionError):  # not UTF-8, not JSON, nested too deep for Python's parser
        doc = None
    gen = doc.get("generator") if isinstance(doc, dict) else None
    desc = str(doc.get("description", "")) if isinstance(doc, dict) else ""
    if not isinstance(gen, str):
        gen = None
    lib_gen = gen if gen in _known() else _guess_generator(path)
    name = _printable(os.path.basename(path))
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
    _parsed[path] = (st.st_mtime_ns, st.st_size) + info
    return info


def _known():
    return GENERATORS


def _scan():
    """{key: (key, path, generator, description, error)}, user files first."""
    seen = {}
    for d in preset_dirs():
        for fn in sorted(os.listdir(d)):
            if not fn.endswith(".json"):
                continue
            # The menu's identifier: control characters and bytes that are
            # not UTF-8 escaped (Blender's enum refuses the whole list otherwise).
            key = _printable(fn[:-5])
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
    """The bytes of preset file `path`. Refuses (BanyanError naming the
    file, BANYAN_E_IO / BANYAN_E_LIMIT) what is not a regular file after
    following links, and files larger than MAX_BYTES, before reading them:
    opened without blocking (a FIFO swapped in after the check does not
    hang) and read to at most MAX_BYTES + 1 bytes. A file that cannot be
    opened or read is refused the same way (PresetNotFound, also a
    FileNotFoundError, when it does not exist)."""
    try:
        _checked(path, os.stat(path))
        flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0) | getattr(os, "O_CLOEXEC", 0)
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise _missing(path) from None
    except OSError as e:
        raise _refuse(path, "cannot be opened: %s" % (e.strerror or e)) from None
    try:
        _checked(path, os.fstat(fd))  # the file opened is the file checked
        chunks, size = [], 0
        while size <= MAX_BYTES:
            try:
                b = os.read(fd, min(1 << 20, MAX_BYTES + 1 - size))
            except BlockingIOError:
                raise _refuse(path, "could not be read without waiting") from None
            except OSError as e:
                raise _refuse(path, "cannot be read: %s" % (e.strerror or e)) from None
            if not b:
                break
            chunks.append(b)
            size += len(b)
        if size > MAX_BYTES:  # grew after the check
            raise _refuse(path, "is more than %d bytes; a preset takes at most %d" % (MAX_BYTES, MAX_BYTES), LIMIT)
        return b"".join(chunks)
    finally:
        os.close(fd)

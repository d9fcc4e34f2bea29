"""Finding, loading and checking libbanyan (ctypes; no bpy).

Search order for the shared library:
  1. the BANYAN_LIB environment variable (a file path), which overrides all;
  2. banyan/lib/<name> beside this package (the installed add-on / zip);
  3. <repo>/build/<name>, for an add-on used straight from the repository
     (blender_addon/banyan -> ../../build), following symlinks.
<name> is libbanyan.so on Linux, libbanyan.dylib on macOS, banyan.dll on
Windows. On Windows the library's folder is added to the DLL search
(os.add_dll_directory) so the DLLs packed beside it (Embree, TBB, the
mingw runtime) are found. At load the ABI version and every banyan_sizeof_* are compared
with the ctypes structures; a mismatch raises LoadError.
"""
import ctypes as C
import os
import sys
import threading

from . import structs as S
from .errors import BanyanError, Cancelled, LoadError

_lock = threading.Lock()
_lib = None
_dll_dirs = []  # os.add_dll_directory handles, kept for the process


class Handle:
    """Base of the wrappers of a library object that close() frees: a
    with-block and garbage collection close it too."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


def library_filename():
    if sys.platform.startswith("win"):
        return "banyan.dll"
    if sys.platform == "darwin":
        return "libbanyan.dylib"
    return "libbanyan.so"


def package_dir():
    """The add-on folder (banyan/), as installed or linked."""
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def candidate_paths():
    """Where the loader looks, in order (BANYAN_LIB first when set)."""
    name = library_filename()
    env = os.environ.get("BANYAN_LIB")
    if env:
        return [env]
    out = [os.path.join(package_dir(), "lib", name)]
    real = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    out.append(os.path.normpath(os.path.join(real, "..", "..", "build", name)))
    return out


def _bind(lib):
    """Prototypes of the core calls (generator calls: generators.py)."""
    P = C.POINTER
    vp = C.c_void_p
    err = P(S.Error)
    sigs = {
        "banyan_status_name": (C.c_char_p, [C.c_int]),
        "banyan_box_validate": (C.c_int, [P(S.Box), C.c_uint32, err]),
        "banyan_mesh_free": (None, [P(S.Mesh)]),
        "banyan_mesh_hash": (C.c_uint64, [P(S.Mesh)]),
        "banyan_mesh_corner_uvs": (C.c_int, [P(S.Mesh), vp, C.c_uint64, err]),
        "banyan_group_localize": (C.c_int, [vp, C.c_uint32, vp, C.c_uint64, C.c_uint32, P(C.c_double), err]),
        "banyan_triangle_edges": (C.c_int, [vp, C.c_uint64, C.c_uint32, vp, vp, C.c_uint64, P(C.c_uint64), vp, err]),
        "banyan_abi_version": (C.c_int32, []),
        "banyan_version_string": (C.c_char_p, []),
        "banyan_generator_name": (C.c_char_p, [C.c_int]),
        "banyan_generator_from_name": (C.c_int32, [C.c_char_p]),
        "banyan_param_count": (C.c_int32, [C.c_int]),
        "banyan_param_get": (P(S.ParamInfo), [C.c_int, C.c_int32]),
        "banyan_param_find": (P(S.ParamInfo), [C.c_int, C.c_char_p]),
        "banyan_param_set_text": (C.c_int, [C.c_int, vp, C.c_char_p, C.c_char_p, err]),
        "banyan_params_check": (C.c_int, [C.c_int, vp, err]),
        "banyan_preset_apply": (C.c_int, [C.c_int, vp, C.c_char_p, C.c_size_t, C.c_char_p, err]),
        "banyan_preset_hosts": (C.c_int, [C.c_char_p, C.c_size_t, C.c_char_p, P(S.Box), C.c_uint32,
                                          P(C.c_uint32), err]),
        "banyan_gltf_write": (C.c_int, [C.c_char_p, P(P(S.Mesh)), P(C.c_char_p), C.c_uint32, err]),
        "banyan_tube_generate": (C.c_int, [P(C.c_double), P(C.c_double), C.c_uint32, C.c_int32,
                                           C.c_int32, P(P(S.Mesh)), err]),
        # Host sets (banyan/hosts.h): core API, bound here.
        "banyan_hosts_create": (C.c_int, [P(S.Box), C.c_uint32, P(S.HostMesh), C.c_uint32, P(vp), err]),
        "banyan_hosts_free": (None, [vp]),
        "banyan_hosts_count": (C.c_uint32, [vp]),
        "banyan_hosts_info": (C.c_int, [vp, C.c_uint32, P(S.HostInfo), err]),
        "banyan_hosts_closest": (C.c_int, [vp, P(C.c_double), C.c_double, P(S.HostHit), err]),
        "banyan_hosts_raycast": (C.c_int, [vp, P(C.c_double), P(C.c_double), C.c_double, P(S.HostHit), err]),
        "banyan_hosts_sweep_sphere": (C.c_int, [vp, P(C.c_double), P(C.c_double), C.c_double, P(S.HostHit),
                                                err]),
        "banyan_hosts_inside": (C.c_int32, [vp, P(C.c_double)]),
        # Mesh hosts from .glb files and presets (banyan.h).
        "banyan_glb_read_host": (C.c_int, [C.c_char_p, P(C.c_double), C.c_int32, P(P(S.HostMesh)), err]),
        "banyan_host_mesh_free": (None, [P(S.HostMesh)]),
        "banyan_preset_meshes": (C.c_int, [C.c_char_p, C.c_size_t, C.c_char_p, C.c_char_p, P(S.PresetMesh), C.c_uint32,
                                           P(C.c_uint32), err]),
        "banyan_preset_host_set": (C.c_int, [C.c_char_p, C.c_size_t, C.c_char_p, C.c_char_p, P(S.HostMesh),
                                             C.c_uint32, P(vp), err]),
        # Textures (banyan/textures.h).
        "banyan_texture_layout": (C.c_int, [C.c_int32, P(S.AtlasLayout), err]),
        "banyan_texture_params_init": (None, [P(S.TextureParams)]),
        "banyan_texture_generate": (C.c_int, [P(S.TextureParams), P(P(S.Image)), P(P(S.Image)), err]),
        "banyan_image_free": (None, [P(S.Image)]),
        "banyan_image_png": (C.c_int, [P(S.Image), P(P(C.c_uint8)), P(C.c_size_t), err]),
        "banyan_png_free": (None, [P(C.c_uint8)]),
        # Levels of detail (banyan/lod.h).
        "banyan_lod_params_init": (None, [P(S.LodParams)]),
        "banyan_mesh_lod": (C.c_int, [P(S.Mesh), P(S.LodParams), P(P(S.Mesh)), err]),
        "banyan_mesh_lods": (C.c_int, [P(S.Mesh), P(C.c_double), C.c_uint32, P(S.LodParams), C.c_int32, C.c_void_p,
                                       P(P(S.Mesh)), err]),
    }
    for key in S.SIZED:
        sigs["banyan_sizeof_" + key] = (C.c_size_t, [])
    for name, (res, args) in sigs.items():
        try:
            f = getattr(lib, name)
        except AttributeError:
            raise LoadError("libbanyan at %s lacks %s(); it is older than this add-on" % (lib._name, name))
        f.restype = res
        f.argtypes = args


def _check_abi(lib, path):
    abi = lib.banyan_abi_version()
    if abi != S.ABI_VERSION:
        raise LoadError("libbanyan at %s has ABI version %d but this add-on needs %d; rebuild the library "
                        "and the add-on from the same source" % (path, abi, S.ABI_VERSION))
    bad = []
    for key, cls in S.SIZED.items():
        theirs = getattr(lib, "banyan_sizeof_" + key)()
        if theirs != C.sizeof(cls):
            bad.append("banyan_%s: library %d bytes, add-on %d" % (key, theirs, C.sizeof(cls)))
    if bad:
        raise LoadError("libbanyan at %s does not match the add-on's structures (%s); rebuild both from the "
                        "same source" % (path, "; ".join(bad)))


def load(path=None):
    """Loads (once) and returns the checked ctypes.CDLL. Raises LoadError."""
    global _lib
    with _lock:
        if _lib is not None and path is None:
            return _lib
        tried = [path] if path else candidate_paths()
        found = [p for p in tried if os.path.isfile(p)]
        if not found:
            raise LoadError("libbanyan not found; looked at: %s. Build it (cmake --build build) or set "
                            "BANYAN_LIB to the library's path" % ", ".join(tried))
        if hasattr(os, "add_dll_directory"):  # Windows, Python 3.8+
            try:
                _dll_dirs.append(os.add_dll_directory(os.path.dirname(os.path.abspath(found[0]))))
            except OSError:
                pass
        try:
            lib = C.CDLL(found[0])
        except OSError as e:
            raise LoadError("libbanyan at %s could not be loaded: %s" % (found[0], e))
        _bind(lib)
        _check_abi(lib, found[0])
        lib.banyan_path = found[0]
        _lib = lib
        return lib


def symbol(name):
    """The library function `name`, or None when this build lacks it."""
    try:
        return getattr(load(), name)
    except AttributeError:
        return None


def status_name(code):
    s = load().banyan_status_name(int(code))
    return s.decode() if s else "BANYAN_E_%d" % code


def source_name(text):
    """A preset's source name (a file name, for the library's messages) as
    UTF-8 bytes: characters UTF-8 cannot hold (a file name's bytes that are
    not UTF-8, kept by Python as surrogate escapes) as backslash escapes."""
    return str(text).encode("utf-8", "backslashreplace")


def raise_for(status, err):
    """Turns a non-zero status + filled banyan_error into BanyanError."""
    if status:
        msg = err.text() if err.code else ""
        if status == Cancelled.STATUS:
            raise Cancelled(msg or status_name(status))
        raise BanyanError(status, msg or status_name(status), status_name(status))


def version():
    return load().banyan_version_string().decode()

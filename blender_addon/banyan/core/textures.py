"""The library's textures (banyan/textures.h) as PNG bytes (ctypes; no
bpy). The pixels never pass through Python: C draws them and encodes the
PNG, Python copies the PNG bytes once."""
import ctypes as C

from . import lib as L
from . import structs as S

KIND_NAMES = {S.TEX_KEYAKI_LEAF: "Keyaki Leaf", S.TEX_IVY_LEAF: "Ivy Leaf", S.TEX_KEYAKI_BARK: "Keyaki Bark",
              S.TEX_FIG_BARK: "Fig Bark", S.TEX_IVY_STEM: "Ivy Stem"}
LEAVES = (S.TEX_KEYAKI_LEAF, S.TEX_IVY_LEAF)
DEFAULT_SIZE = 1024
SIZES = (256, 512, 1024, 2048, 4096)


def layout(kind):
    """banyan_texture_layout: (cols, rows, leaf_aspect)."""
    lib = L.load()
    out = S.AtlasLayout()
    err = S.Error()
    st = lib.banyan_texture_layout(int(kind), C.byref(out), C.byref(err))
    if st:
        L.raise_for(st, err)
    return out.cols, out.rows, out.leaf_aspect


def _png(lib, img):
    """PNG bytes of a banyan_image (freed by the caller)."""
    buf = C.POINTER(C.c_uint8)()
    n = C.c_size_t()
    err = S.Error()
    st = lib.banyan_image_png(img, C.byref(buf), C.byref(n), C.byref(err))
    if st:
        L.raise_for(st, err)
    try:
        return C.string_at(buf, n.value)
    finally:
        lib.banyan_png_free(buf)


def generate_png(kind, season=S.SEASON_SUMMER, size=DEFAULT_SIZE, seed=1, normal=True):
    """(base colour PNG, normal PNG or None) of one texture, with each
    image's (width, height, channels): ((png, w, h, c), (png, w, h, c) | None).
    Raises BanyanError (naming the field) on a bad kind, season or size."""
    lib = L.load()
    p = S.TextureParams()
    lib.banyan_texture_params_init(C.byref(p))
    p.kind, p.season, p.size, p.seed = int(kind), int(season), int(size), int(seed)
    base = C.POINTER(S.Image)()
    nrm = C.POINTER(S.Image)()
    err = S.Error()
    st = lib.banyan_texture_generate(C.byref(p), C.byref(base), C.byref(nrm) if normal else None, C.byref(err))
    if st:
        L.raise_for(st, err)
    try:
        out = []
        for img in (base, nrm):
            if not img:
                out.append(None)
                continue
            i = img.contents
            out.append((_png(lib, img), i.width, i.height, i.channels))
        return out[0], out[1]
    finally:
        lib.banyan_image_free(base)
        if nrm:
            lib.banyan_image_free(nrm)

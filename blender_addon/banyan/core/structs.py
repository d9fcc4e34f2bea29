"""ctypes mirrors of the public structs in banyan.h. The loader compares
each ctypes.sizeof with the library's banyan_sizeof_* at load time."""
import ctypes as C

NAME_MAX = 32        # BANYAN_NAME_MAX
MAX_HOSTS = 256      # BANYAN_MAX_HOSTS
ABI_VERSION = 22     # BANYAN_ABI_VERSION this binding was written for


class Error(C.Structure):
    _fields_ = [("code", C.c_int32), ("message", C.c_char * 256)]

    def text(self):
        return self.message.decode("utf-8", "replace")


class Box(C.Structure):
    _fields_ = [("center", C.c_double * 3), ("half", C.c_double * 3),
                ("rotation", C.c_double * 9)]

    @classmethod
    def make(cls, center, half, rotation=(1, 0, 0, 0, 1, 0, 0, 0, 1)):
        b = cls()
        b.center[:] = [float(x) for x in center]
        b.half[:] = [float(x) for x in half]
        b.rotation[:] = [float(x) for x in rotation]
        return b

    def as_dict(self):
        return {"center": list(self.center), "half": list(self.half),
                "rotation": list(self.rotation)}


class Attribute(C.Structure):
    _fields_ = [("name", C.c_char * NAME_MAX), ("data", C.POINTER(C.c_float))]


class Material(C.Structure):
    _fields_ = [("name", C.c_char * NAME_MAX), ("base_color", C.c_float * 4),
                ("roughness", C.c_float), ("double_sided", C.c_int32), ("texture", C.c_int32),
                ("season", C.c_int32), ("alpha_cutoff", C.c_float), ("translucency", C.c_float),
                ("image", C.c_int32)]


class Part(C.Structure):
    _fields_ = [("vertex_offset", C.c_uint32), ("vertex_count", C.c_uint32),
                ("index_offset", C.c_uint32), ("index_count", C.c_uint32),
                ("material", C.c_uint32), ("group", C.c_uint32)]


class Image(C.Structure):
    _fields_ = [("width", C.c_uint32), ("height", C.c_uint32), ("channels", C.c_uint32),
                ("pixels", C.POINTER(C.c_uint8))]


class Instance(C.Structure):
    _fields_ = [("variant", C.c_uint32), ("translation", C.c_float * 3), ("rotation_z", C.c_float),
                ("scale", C.c_float)]


class Mesh(C.Structure):
    _fields_ = [
        ("vertex_count", C.c_uint32),
        ("index_count", C.c_uint32),
        ("positions", C.POINTER(C.c_float)),
        ("normals", C.POINTER(C.c_float)),
        ("uvs", C.POINTER(C.c_float)),
        ("colors", C.POINTER(C.c_float)),
        ("indices", C.POINTER(C.c_uint32)),
        ("attribute_count", C.c_uint32),
        ("attributes", C.POINTER(Attribute)),
        ("material_count", C.c_uint32),
        ("materials", C.POINTER(Material)),
        ("part_count", C.c_uint32),
        ("parts", C.POINTER(Part)),
        ("skel_point_count", C.c_uint32),
        ("skel_points", C.POINTER(C.c_float)),
        ("skel_radius", C.POINTER(C.c_float)),
        ("skel_tag", C.POINTER(C.c_int32)),
        ("skel_edge_count", C.c_uint32),
        ("skel_edges", C.POINTER(C.c_uint32)),
        ("origin", C.c_double * 3),
        ("image_count", C.c_uint32),
        ("images", C.POINTER(Image)),
        ("instance_count", C.c_uint32),
        ("instances", C.POINTER(Instance)),
    ]


class ParamInfo(C.Structure):
    _fields_ = [
        ("name", C.c_char_p),
        ("unit", C.c_char_p),
        ("description", C.c_char_p),
        ("type", C.c_int32),
        ("min", C.c_double),
        ("max", C.c_double),
        ("choices", C.c_char_p),
        ("offset", C.c_size_t),
        ("label", C.c_char_p),
        ("group", C.c_char_p),
    ]


class HostMesh(C.Structure):
    """banyan_host_mesh (banyan/hosts.h): one triangle mesh host. The
    arrays are read during banyan_hosts_create only."""
    _fields_ = [
        ("positions", C.POINTER(C.c_float)),
        ("indices", C.POINTER(C.c_uint32)),
        ("vertex_count", C.c_uint32),
        ("triangle_count", C.c_uint32),
        ("transform", C.c_double * 12),
        ("closed", C.c_int32),
        ("reserved", C.c_int32),
    ]


class HostHit(C.Structure):
    _fields_ = [("host", C.c_int32), ("primitive", C.c_uint32), ("distance", C.c_double),
                ("point", C.c_double * 3), ("normal", C.c_double * 3)]


# banyan_progress: done 0..1 -> nonzero cancels (banyan.h).
PROGRESS_FN = C.CFUNCTYPE(C.c_int32, C.c_void_p, C.c_double)


class Progress(C.Structure):
    _fields_ = [("fn", PROGRESS_FN), ("user", C.c_void_p)]


# banyan_status
E_CANCELLED = 15


# banyan_ivy_growth (banyan_ivy_stats.cannot_grow)
IVY_GREW, IVY_BLOCKED, IVY_STUNTED = 0, 1, 2


class IvyStats(C.Structure):
    """banyan_ivy_stats; checked against banyan_sizeof_ivy_stats when ivy
    is first used (generators.py), as the ivy generator may be absent."""
    _fields_ = [("steps", C.c_int32), ("buds", C.c_int32), ("by_state", C.c_int32 * 5), ("attached", C.c_int32),
                ("branch_points", C.c_int32), ("crossings", C.c_int32), ("cannot_grow", C.c_int32),
                ("attached_fraction", C.c_double), ("covered_area", C.c_double), ("density", C.c_double),
                ("stem_length", C.c_double), ("step_seconds", C.c_double)]


KEYAKI_MAX_ORDER = 32  # BANYAN_KEYAKI_MAX_ORDER


class KeyakiStats(C.Structure):
    """banyan_keyaki_stats; checked against banyan_sizeof_keyaki_stats when
    keyaki is first used (generators.py)."""
    _fields_ = [("node_count", C.c_int32), ("tip_count", C.c_int32), ("fork_count", C.c_int32),
                ("break_count", C.c_int32), ("max_level", C.c_int32), ("max_order", C.c_int32),
                ("stream_count", C.c_int32 * KEYAKI_MAX_ORDER), ("bifurcation_ratio", C.c_double * KEYAKI_MAX_ORDER),
                ("mean_bifurcation_ratio", C.c_double), ("height", C.c_double), ("crown_width", C.c_double),
                ("mean_run_length", C.c_double)]


class HostInfo(C.Structure):
    _fields_ = [("kind", C.c_int32), ("closed", C.c_int32), ("triangle_count", C.c_uint32),
                ("dropped_triangles", C.c_uint32), ("boundary_edges", C.c_uint32), ("shells", C.c_uint32),
                ("lo", C.c_double * 3), ("hi", C.c_double * 3)]


# banyan_host_closed
HOST_CLOSED_AUTO, HOST_OPEN, HOST_CLOSED = -1, 0, 1
HOSTS_MAX_TRIANGLES = 1 << 25  # BANYAN_HOSTS_MAX_TRIANGLES

# banyan_param_type
PT_DOUBLE, PT_INT, PT_BOOL, PT_ENUM, PT_VEC3, PT_COLOR, PT_SEED = range(7)

# banyan_generator
GENERATORS = ("roots", "keyaki", "avenue", "ivy", "segments")

# Textures (banyan/textures.h).
TEX_NONE, TEX_KEYAKI_LEAF, TEX_IVY_LEAF, TEX_KEYAKI_BARK, TEX_FIG_BARK, TEX_IVY_STEM = range(6)  # NONE: no texture
SEASON_SUMMER, SEASON_AUTUMN = 0, 1


class AtlasLayout(C.Structure):
    _fields_ = [("cols", C.c_int32), ("rows", C.c_int32), ("leaf_aspect", C.c_float)]




class TextureParams(C.Structure):
    _fields_ = [("kind", C.c_int32), ("season", C.c_int32), ("size", C.c_int32), ("reserved", C.c_int32),
                ("seed", C.c_uint64)]


class LodParams(C.Structure):
    """banyan_lod_params (banyan/lod.h)."""
    _fields_ = [("ratio", C.c_double), ("billboard", C.c_int32), ("billboard_planes", C.c_int32),
                ("billboard_size", C.c_int32), ("reserved", C.c_int32), ("seed", C.c_uint64)]


class PresetMesh(C.Structure):
    """banyan_preset_mesh (banyan.h): one mesh host entry of a preset."""
    _fields_ = [("index", C.c_uint32), ("closed", C.c_int32), ("transform", C.c_double * 12),
                ("path", C.c_char * 4096), ("name", C.c_char * 256)]


# Checked against banyan_sizeof_<key>() at load.
SIZED = {"error": Error, "box": Box, "attribute": Attribute, "material": Material,
         "part": Part, "mesh": Mesh, "param_info": ParamInfo, "host_mesh": HostMesh, "host_hit": HostHit,
         "host_info": HostInfo, "image": Image, "texture_params": TextureParams, "instance": Instance,
         "lod_params": LodParams, "preset_mesh": PresetMesh}

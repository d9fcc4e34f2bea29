"""Generic parameter structs driven by the library's parameter tables.

Params("roots") allocates banyan_sizeof_roots_params() bytes, fills them
with banyan_roots_params_init and reads / writes fields by the table's
offset and type. Setting goes through banyan_param_set_text, so the
library does every range and type check and its message is the error.
"""
import ctypes as C
import json

from . import lib as L
from . import structs as S
from .errors import BanyanError, LoadError


class ParamSpec:
    """One row of a parameter table, as plain Python values."""
    __slots__ = ("name", "unit", "description", "type", "min", "max", "choices", "offset", "label", "group")

    def __init__(self, info):
        self.name = info.name.decode()
        self.unit = (info.unit or b"").decode()
        self.description = (info.description or b"").decode()
        self.type = info.type
        self.min = info.min
        self.max = info.max
        self.choices = info.choices.decode().split("|") if info.choices else []
        self.offset = info.offset
        # What a panel shows (banyan_param_info.label / .group, ABI 5).
        self.label = (info.label or b"").decode() or info.name.decode()
        self.group = (info.group or b"").decode() or "Parameters"

    @property
    def size(self):
        return {S.PT_DOUBLE: 8, S.PT_INT: 4, S.PT_BOOL: 4, S.PT_ENUM: 4, S.PT_VEC3: 24,
                S.PT_COLOR: 32, S.PT_SEED: 8}[self.type]

    def __repr__(self):
        return "ParamSpec(%s)" % self.name


def generator_id(gen):
    if isinstance(gen, int):
        return gen
    g = L.load().banyan_generator_from_name(gen.encode())
    if g < 0:
        raise BanyanError(1, "unknown generator '%s' (one of %s)" % (gen, ", ".join(S.GENERATORS)))
    return g


_spec_cache = {}


def specs(gen):
    """The parameter table of `gen` as a list of ParamSpec."""
    g = generator_id(gen)
    if g in _spec_cache:
        return _spec_cache[g]
    lib = L.load()
    n = lib.banyan_param_count(g)
    name = S.GENERATORS[g]
    if n <= 0:
        raise LoadError("the library has no parameter table for '%s'" % name)
    out = [ParamSpec(lib.banyan_param_get(g, i).contents) for i in range(n)]
    _spec_cache[g] = out
    return out


def _struct_name(g):
    return S.GENERATORS[g]


class Params:
    """A generator's params struct in a ctypes buffer."""

    def __init__(self, gen):
        self.gen = generator_id(gen)
        self.name = _struct_name(self.gen)
        self.specs = specs(self.gen)
        self.by_name = {p.name: p for p in self.specs}
        sizeof = L.symbol("banyan_sizeof_%s_params" % self.name)
        init = L.symbol("banyan_%s_params_init" % self.name)
        if not sizeof or not init:
            raise LoadError("banyan_sizeof_%s_params or banyan_%s_params_init is not in the library"
                            % (self.name, self.name))
        sizeof.restype = C.c_size_t
        sizeof.argtypes = []
        self.size = sizeof()
        for p in self.specs:
            if p.offset + p.size > self.size:
                raise BanyanError(14, "%s.%s at offset %d does not fit in %d bytes"
                                  % (self.name, p.name, p.offset, self.size))
        # uint64 words: 8-byte alignment for double and uint64_t fields.
        self.buf = (C.c_uint64 * ((self.size + 7) // 8))()
        init.restype = None
        init.argtypes = [C.c_void_p]
        init(self.ptr)

    @property
    def ptr(self):
        return C.cast(self.buf, C.c_void_p)

    def copy(self):
        other = Params.__new__(Params)
        other.__dict__.update(self.__dict__)
        other.buf = type(self.buf).from_buffer_copy(self.buf)
        return other

    # --- reading -------------------------------------------------------
    def _addr(self, p):
        return C.addressof(self.buf) + p.offset

    def get(self, name):
        p = self.spec(name)
        a = self._addr(p)
        t = p.type
        if t == S.PT_DOUBLE:
            return C.c_double.from_address(a).value
        if t == S.PT_INT:
            return C.c_int32.from_address(a).value
        if t == S.PT_BOOL:
            return bool(C.c_int32.from_address(a).value)
        if t == S.PT_ENUM:
            i = C.c_int32.from_address(a).value
            return p.choices[i] if 0 <= i < len(p.choices) else i
        if t == S.PT_SEED:
            return C.c_uint64.from_address(a).value
        if t == S.PT_VEC3:
            return tuple((C.c_double * 3).from_address(a))
        if t == S.PT_COLOR:
            return tuple((C.c_double * 4).from_address(a))
        raise BanyanError(14, "%s has unknown type %d" % (p.name, t))

    def spec(self, name):
        try:
            return self.by_name[name]
        except KeyError:
            raise BanyanError(11, "unknown %s parameter '%s'" % (self.name, name), "BANYAN_E_UNKNOWN_KEY")

    def as_dict(self):
        return {p.name: self.get(p.name) for p in self.specs}

    # --- writing (checked by the library) -------------------------------
    @staticmethod
    def to_text(value):
        if isinstance(value, bool):
            return "true" if value else "false"
        if isinstance(value, float):
            return repr(value)
        if isinstance(value, (list, tuple)) or hasattr(value, "__len__") and not isinstance(value, str):
            return ",".join(Params._number_text(v) for v in value)
        return str(value)

    @staticmethod
    def _number_text(v):
        try:
            return repr(float(v))
        except (TypeError, ValueError):
            return str(v)  # the library refuses it, naming the field

    def set(self, name, value):
        """Sets one parameter; raises BanyanError with the library's message
        (unknown key, wrong type, out of range) and leaves the field as it was."""
        err = S.Error()
        st = L.load().banyan_param_set_text(self.gen, self.ptr, name.encode(),
                                            self.to_text(value).encode(), C.byref(err))
        L.raise_for(st, err)

    def update(self, values):
        for k, v in values.items():
            self.set(k, v)

    def check(self):
        err = S.Error()
        L.raise_for(L.load().banyan_params_check(self.gen, self.ptr, C.byref(err)), err)

    # --- presets ---------------------------------------------------------
    def apply_preset(self, text, source="<preset>"):
        """Applies a preset's "params" (JSON text or bytes) on top of the
        current values, through banyan_preset_apply."""
        data = text.encode() if isinstance(text, str) else bytes(text)
        err = S.Error()
        trial = self.copy()  # the library may leave a failed apply half done
        st = L.load().banyan_preset_apply(self.gen, trial.ptr, data, len(data), L.source_name(source), C.byref(err))
        L.raise_for(st, err)
        C.memmove(self.buf, trial.buf, C.sizeof(self.buf))

    def to_preset(self, description="", hosts=None):
        """A preset JSON text that banyan_preset_apply reads back to these values."""
        params = {}
        for p in self.specs:
            v = self.get(p.name)
            params[p.name] = list(v) if isinstance(v, tuple) else v
        doc = {"generator": self.name, "schema": 1, "description": description, "params": params}
        if hosts:
            doc["hosts"] = [h.as_dict() if hasattr(h, "as_dict") else h for h in hosts]
        return json.dumps(doc, indent=2) + "\n"

    def raw(self):
        return bytes(self.buf)[: self.size]


def preset_hosts(text, source="<preset>"):
    """The "hosts" of a preset as a list of structs.Box (may be empty)."""
    data = text.encode() if isinstance(text, str) else bytes(text)
    out = (S.Box * S.MAX_HOSTS)()
    count = C.c_uint32(0)
    err = S.Error()
    st = L.load().banyan_preset_hosts(data, len(data), L.source_name(source), out, S.MAX_HOSTS, C.byref(count),
                                      C.byref(err))
    L.raise_for(st, err)
    return [S.Box.from_buffer_copy(out[i]) for i in range(count.value)]


def preset_generator(text):
    """The "generator" named by a preset text, or None."""
    try:
        return json.loads(text).get("generator")
    except (ValueError, AttributeError):
        return None

"""Python values -> C arguments. ctypes would silently wrap an int that
does not fit in int32 and pack a 2-number point into the next point's
slot, so these refuse such values with a BanyanError; ranges are checked
by the library."""
import ctypes as C
import numbers

from .errors import BanyanError

E_RANGE, E_TYPE = 2, 12


def int32(name, value):
    """value as a C int32: whole numbers only (3.0 is fine, 2.5 and NaN are not)."""
    if isinstance(value, bool) or not (isinstance(value, numbers.Integral) or
                                       isinstance(value, float) and value.is_integer()):
        raise BanyanError(E_TYPE, "%s = %r must be a whole number" % (name, value), "BANYAN_E_TYPE")
    v = int(value)
    if not -2 ** 31 <= v < 2 ** 31:
        raise BanyanError(E_RANGE, "%s = %d does not fit in 32 bits" % (name, v), "BANYAN_E_RANGE")
    return v


def points(name, pts):
    """A list of (x, y, z) as (c_double * 3n, n); each point must be 3 numbers."""
    flat = []
    for i, p in enumerate(pts):
        try:
            c = [float(x) for x in p]
        except (TypeError, ValueError):
            raise BanyanError(E_TYPE, "%s point %d = %r must be 3 numbers" % (name, i, p), "BANYAN_E_TYPE")
        if len(c) != 3:
            raise BanyanError(E_TYPE, "%s point %d has %d coordinates, want 3" % (name, i, len(c)), "BANYAN_E_TYPE")
        flat.extend(c)
    return (C.c_double * max(1, len(flat)))(*flat), len(flat) // 3


def numbers_of(name, values):
    """A list of numbers as (c_double * n, n)."""
    try:
        v = [float(x) for x in values]
    except (TypeError, ValueError):
        raise BanyanError(E_TYPE, "%s must be numbers, got %r" % (name, values), "BANYAN_E_TYPE")
    return (C.c_double * max(1, len(v)))(*v), len(v)

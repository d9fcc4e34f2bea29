"""Operator classes, built at register time from the library's parameter
tables. Each entry: (generator names it needs, module, factory name)."""
from . import ivy, keyaki, roots, segments, tube  # noqa: F401

FACTORIES = [
    (("roots",), roots, "make_class"),
    (("keyaki",), keyaki, "make_tree_class"),
    (("avenue",), keyaki, "make_avenue_class"),
    (("ivy",), ivy, "make_class"),
    (("segments",), segments, "make_class"),
]

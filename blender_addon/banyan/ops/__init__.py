"""Operator classes, built at register time from the library's parameter
tables. Each entry: (module, factory name)."""
from . import ivy, keyaki, roots, segments, tube  # noqa: F401

FACTORIES = [
    (roots, "make_class"),
    (keyaki, "make_tree_class"),
    (keyaki, "make_avenue_class"),
    (ivy, "make_class"),
    (segments, "make_class"),
]

"""What register() found: the operators it made, the generators the
library lacks, and a load error (then nothing else is registered)."""
VERSION = "?"
LOAD_ERROR = ""
MISSING = set()     # generators without table or symbols in this library
ERRORS = []         # generators whose operator could not be built
OPERATORS = []      # (bl_idname, label) in menu order


def operator_entries():
    return list(OPERATORS)

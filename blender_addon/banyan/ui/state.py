"""What register() found: the operators it made and a load error (then
nothing else is registered)."""
VERSION = "?"
LOAD_ERROR = ""
ERRORS = []         # generators whose operator could not be built
OPERATORS = []      # (bl_idname, label) in menu order


def operator_entries():
    return list(OPERATORS)

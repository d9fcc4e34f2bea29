"""Exceptions raised by the binding."""


class BanyanError(Exception):
    """A libbanyan call failed: `status` is the banyan_status code, `name`
    its fixed name ("BANYAN_E_RANGE"), `message` the library's message."""

    def __init__(self, status, message, name=""):
        self.status = int(status)
        self.name = name
        self.message = message
        super().__init__(message)


class LoadError(BanyanError):
    """The library could not be found or does not match this binding."""

    def __init__(self, message):
        super().__init__(-1, message, "LOAD")


class PresetNotFound(BanyanError, FileNotFoundError):
    """No preset of that name or path (BANYAN_E_IO); also a FileNotFoundError."""

    def __init__(self, message):
        BanyanError.__init__(self, 9, message, "BANYAN_E_IO")


class Cancelled(BanyanError):
    """A generation stopped because its progress callback asked it to
    (BANYAN_E_CANCELLED): nothing was made. When the callback itself
    raised, that exception is raised instead (generators.py)."""

    STATUS = 15

    def __init__(self, message="cancelled by the progress callback"):
        super().__init__(self.STATUS, message, "BANYAN_E_CANCELLED")


# What an operator reports as a plain error: the library's message, a
# missing file, a bad value. Anything else is a bug, reported with its type
# and traceback (the scene is left as it was either way).
EXPECTED = (BanyanError, FileNotFoundError, ValueError)


def report_error(report, e):
    """Reports exception e through an operator's report(); returns
    {'CANCELLED'} for the operator to return."""
    if isinstance(e, EXPECTED):
        report({'ERROR'}, "Banyan: %s" % (e.message if isinstance(e, BanyanError) else e))
    else:
        import traceback
        traceback.print_exception(type(e), e, e.__traceback__)
        report({'ERROR'}, "Banyan: unexpected %s: %s" % (type(e).__name__, e))
    return {'CANCELLED'}

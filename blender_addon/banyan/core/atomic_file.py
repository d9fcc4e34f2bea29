"""Writing a file without ever destroying the old one (as the library's
csrc/base/atomic_file.c does for glTF and PNG): the bytes go to a
temporary ".<name>.XXXXXX.tmp" in the same folder, flushed, synced and
renamed over the target (os.replace) only when all of them are written.
A failure removes the temporary file and leaves the old file as it was; a
killed Blender may leave the temporary file, never a cut target. A
symlink is followed (its target is replaced, the link stays); the old
file's mode is kept; a read-only old file is refused."""
import errno
import os
import random
import stat

_LETTERS = "abcdefghijklmnopqrstuvwxyz0123456789"


def write_atomic(path, data):
    """data (bytes, or str written as UTF-8) as the whole new contents of
    path. Raises OSError and leaves the old file when it cannot."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    target = os.path.realpath(path)
    folder, name = os.path.split(target)
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        mode = None
    if mode is not None and not os.access(target, os.W_OK):
        raise PermissionError(errno.EACCES, "the file is read-only", path)
    rng = random.SystemRandom()
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0)
    for attempt in range(100):
        tmp = os.path.join(folder, ".%s.%s.tmp" % (name[:200], "".join(rng.choice(_LETTERS) for _ in range(6))))
        try:
            fd = os.open(tmp, flags, 0o666)  # the umask applies, as for open()
            break
        except FileExistsError:
            if attempt == 99:
                raise
    try:
        with os.fdopen(fd, "wb") as f:
            if mode is not None and hasattr(os, "fchmod"):
                os.fchmod(f.fileno(), mode)
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise

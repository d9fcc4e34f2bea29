"""The batch runner's files on shared storage: per-seed locks, private
temporary folders, writes by rename that never follow a symlink, the
removal of a dead runner's leftovers, and a watch on the parent process.

Rules (docs/batch.md, "Locks, temporary files and symlinks"):

- A seed is made only by the process holding its lock: an exclusive POSIX
  record lock (fcntl.lockf, F_SETLK on the whole file) on
  DIR/manifest/.<name>.lock, opened with O_NOFOLLOW. The lock file holds
  "<host> <pid>" of its owner (for messages only). The kernel (or the NFS
  lock manager / lease) drops the lock when its owner dies, so a dead
  owner's lock file is taken over, never waited on. The file is unlinked
  by its owner on release; a waiter that locked an unlinked file (its
  inode no longer at the path) tries again.
- Everything of a seed is first written into a private folder
  DIR/.<name>.<host>.<pid>.<random>.tmp (mkdtemp: mode 0700, a fresh
  name) and renamed into place, the record last. rename() replaces a
  symlink at the target with the file; it never writes through it.
- Leftovers of a seed (".<name>." ... ".tmp" or ".tmp.png", and the glTF
  writer's "..<name>..." temporaries) are removed only by the holder of
  that seed's lock, so they belong to a dead process; nothing else in the
  folder is ever removed.

Python 3.11 stdlib only (Blender 3.4's Python and plain python3).
"""
import errno
import os
import platform
import re
import shutil
import stat
import sys
import tempfile
import threading
import time

try:
    import fcntl
except ImportError:  # Windows
    fcntl = None
    import msvcrt

LOCK_SUFFIX = ".lock"
_O_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_O_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
_O_BINARY = getattr(os, "O_BINARY", 0)


def host():
    return platform.node() or "host"


def _safe(text):
    """A host name as a file name part (letters, digits, '-', '_')."""
    return re.sub(r"[^A-Za-z0-9_-]", "_", text)[:64] or "host"


class Busy(Exception):
    """The seed's lock is held by a live process (the message names it)."""


class SeedLock:
    """An exclusive lock on one seed (see the module's rules). Use
    acquire(wait) / release(), or `with`."""

    def __init__(self, folder, name):
        self.path = os.path.join(folder, "." + name + LOCK_SUFFIX)
        self.fd = None

    def _try(self):
        flags = os.O_RDWR | os.O_CREAT | _O_NOFOLLOW | _O_CLOEXEC | _O_BINARY
        try:
            fd = os.open(self.path, flags, 0o666)
        except OSError as e:
            if e.errno == errno.ELOOP:
                raise OSError(e.errno, "a symlink stands at the lock file's name: refused", self.path)
            raise
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise OSError(errno.EINVAL, "the lock file is not a regular file", self.path)
            try:
                if fcntl is not None:
                    fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                else:
                    msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
            except OSError as e:
                if e.errno in (errno.EACCES, errno.EAGAIN, errno.EDEADLK):
                    raise Busy(self._owner_of(fd))
                raise
            # Locked; but is it still the file at the path (not unlinked
            # by an owner that released it while we waited)?
            try:
                st = os.stat(self.path, follow_symlinks=False)
            except FileNotFoundError:
                st = None
            fst = os.fstat(fd)
            if st is None or (st.st_ino, st.st_dev) != (fst.st_ino, fst.st_dev):
                os.close(fd)
                return False
            os.ftruncate(fd, 0)
            os.lseek(fd, 0, os.SEEK_SET)
            os.write(fd, ("%s %d\n" % (host(), os.getpid())).encode())
            self.fd = fd
            return True
        except BaseException:
            if self.fd != fd:
                try:
                    os.close(fd)
                except OSError:
                    pass
            raise

    @staticmethod
    def _owner_of(fd):
        try:
            os.lseek(fd, 0, os.SEEK_SET)
            text = os.read(fd, 200).decode("utf-8", "replace").strip()
        except OSError:
            text = ""
        return "held by %s" % (text.replace(" ", " pid ", 1) if text else "another process")

    def acquire(self, wait=True, poll=0.2, on_wait=None):
        """Takes the lock; with wait, polls until the owner is done (calling
        on_wait(message) once), else raises Busy."""
        told = False
        while True:
            try:
                if self._try():
                    return self
            except Busy as e:
                if not wait:
                    raise
                if on_wait and not told:
                    on_wait(str(e))
                    told = True
                time.sleep(poll)

    def release(self):
        if self.fd is None:
            return
        try:
            os.unlink(self.path)  # still ours: we hold the lock on this inode
        except OSError:
            pass
        os.close(self.fd)  # drops the lock
        self.fd = None

    def __enter__(self):
        return self.acquire()

    def __exit__(self, *exc):
        self.release()


def stale_pattern(name):
    """Names in a folder that are leftovers of seed `name`'s writers and of
    nothing else: the private folders (".<name>.<host>.<pid>.<random>.tmp"),
    the glTF and USD writers' and records' temporaries (".<name>.glb.XXXXXX.tmp",
    ".<name>.usda.XXXXXX.tmp",
    ".<name>.json.XXXXXX.tmp") and a render's (".<name>.png.<pid>.tmp.png")."""
    n = re.escape(name)
    return re.compile(r"^\.%s\.(?:(?:glb|usda|png|json)\.[A-Za-z0-9]{6}\.tmp|png\.[0-9]+\.tmp\.png"
                      r"|[A-Za-z0-9_-]+\.[0-9]+\.[a-z0-9_]+\.tmp)$" % n)


def remove_stale_temps(folder, names):
    """Removes the leftovers of the given file names in folder (call only
    while holding their seed's lock). Symlinks are removed, not followed.
    Returns the names removed."""
    pats = [stale_pattern(n) for n in names]
    removed = []
    try:
        entries = os.listdir(folder)
    except FileNotFoundError:
        return removed
    for e in entries:
        if not any(p.match(e) for p in pats):
            continue
        path = os.path.join(folder, e)
        try:
            st = os.lstat(path)
            if stat.S_ISDIR(st.st_mode):
                shutil.rmtree(path)
            else:
                os.unlink(path)
            removed.append(e)
        except OSError:
            pass
    return removed


def private_folder(folder, name):
    """A fresh folder only this process writes into (mode 0700), named
    after the seed and its owner."""
    return tempfile.mkdtemp(prefix=".%s.%s.%d." % (name, _safe(host()), os.getpid()), suffix=".tmp", dir=folder)


def place(src, dst):
    """Renames src over dst (same file system). A symlink at dst is
    replaced by the file itself; a folder at dst is refused."""
    try:
        st = os.lstat(dst)
    except FileNotFoundError:
        st = None
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise OSError(errno.EISDIR, "a folder stands at the output's name", dst)
    os.replace(src, dst)


def write_new(path, data, mode=0o666):
    """Writes data (bytes or str as UTF-8) to a file that must not exist
    (O_CREAT|O_EXCL|O_NOFOLLOW), flushed and synced."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _O_NOFOLLOW | _O_CLOEXEC | _O_BINARY, mode)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
    except BaseException:
        try:
            os.unlink(path)
        except OSError:
            pass
        raise


def write_atomic(path, data):
    """data as the whole new contents of path: written to a fresh
    ".<name>.<owner>.<random>.tmp" beside it (O_EXCL, never through a
    symlink) and renamed over path. A symlink at path is replaced, not
    followed; the old file is left as it was when anything fails."""
    folder, name = os.path.split(os.path.abspath(path))
    tmp = None
    for _ in range(100):
        cand = os.path.join(folder, ".%s.%s.%d.%s.tmp" % (name[:200], _safe(host()), os.getpid(),
                                                            os.urandom(4).hex()))
        try:
            write_new(cand, data)
            tmp = cand
            break
        except FileExistsError:
            continue
    if tmp is None:
        raise OSError(errno.EEXIST, "no free temporary name", path)
    try:
        place(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def open_regular(path):
    """A file object for reading path, or None when path is missing, a
    symlink or not a regular file (outputs are never read through links)."""
    try:
        fd = os.open(path, os.O_RDONLY | _O_NOFOLLOW | _O_CLOEXEC | _O_BINARY)
    except OSError:
        return None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return None
    return os.fdopen(fd, "rb")


class ParentWatch:
    """Stops this process when its parent dies (the scheduler's worker was
    killed and this runner was left an orphan): a daemon thread compares
    os.getppid() with the first one every `period` seconds and, when it
    changed, prints a message and ends the process with exit status 3
    (os._exit: a seed being made is dropped; its lock dies with the
    process and its private folder is a dead owner's leftover)."""

    def __init__(self, period=0.5, log=None):
        self.ppid = os.getppid()
        self.period = period
        self.log = log
        self.thread = None

    def start(self):
        if self.ppid <= 1:  # started by init (a container's entry point): nothing to watch
            return self
        self.thread = threading.Thread(target=self._run, name="banyan-parent-watch", daemon=True)
        self.thread.start()
        return self

    def _run(self):
        while True:
            time.sleep(self.period)
            if os.getppid() != self.ppid:
                msg = "batch_run: error: parent process %d is gone (the scheduler's worker died): stopping\n" % self.ppid
                try:
                    sys.stderr.write(msg)
                    sys.stderr.flush()
                finally:
                    os._exit(3)

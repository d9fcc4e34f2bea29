/* atomic_file.c - write a temporary file, then rename it (atomic_file.h). */
#ifdef __linux__
#define _GNU_SOURCE /* sync_file_range */
#else
#define _POSIX_C_SOURCE 200809L
#endif
#include "atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

enum { MAX_LINKS = 40, MAX_BASE = 200 };

static char *dup_n(const char *s, size_t n) {
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

/* Length of path's folder part including its last '/', 0 when none. */
static size_t dir_len(const char *path) {
    const char *slash = strrchr(path, '/');
    return slash ? (size_t)(slash - path) + 1 : 0;
}

/* path with its symbolic links followed to the last link's target, which
 * need not exist yet (a dangling link is written through, like fopen).
 * malloc'd; NULL with *e set on failure. */
static char *final_target(const char *path, int *e) {
    char *p = dup_n(path, strlen(path));
    for (int hops = 0; p; hops++) {
        struct stat st;
        if (lstat(p, &st) != 0 || !S_ISLNK(st.st_mode)) return p;
        char link[4096];
        ssize_t n = hops < MAX_LINKS ? readlink(p, link, sizeof link - 1) : -1;
        if (n < 0) {
            *e = hops < MAX_LINKS ? errno : ELOOP;
            free(p);
            return NULL;
        }
        link[n] = '\0';
        size_t d = link[0] == '/' ? 0 : dir_len(p);
        char *q = malloc(d + (size_t)n + 1);
        if (q) {
            memcpy(q, p, d);
            memcpy(q + d, link, (size_t)n + 1);
        }
        free(p);
        p = q;
    }
    *e = ENOMEM;
    return NULL;
}

/* A fresh name per attempt: no global counter (the library keeps no
 * global state); pid, clock and the caller's address differ enough, and
 * O_EXCL catches the rest. */
static void fill_random(char *x, int attempt, const void *salt) {
    static const char digits[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t v = (uint64_t)getpid() * 0x9E3779B97F4A7C15ull ^ (uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec << 30 ^
                 (uint64_t)(uintptr_t)salt ^ (uint64_t)attempt * 0xBF58476D1CE4E5B9ull;
    v ^= v >> 31;
    v *= 0x94D049BB133111EBull;
    v ^= v >> 29;
    for (int i = 0; i < 6; i++, v /= 36) x[i] = digits[v % 36];
}

static void clear(atomic_file *af) {
    free(af->path);
    free(af->temp);
    af->f = NULL;
    af->path = af->temp = NULL;
    af->sync = 1;
}

int atomic_open(atomic_file *af, const char *path) {
    af->f = NULL;
    af->path = af->temp = NULL;
    af->sync = 1;
    int e = 0;
    if (!path || !path[0]) return ENOENT;
    af->path = final_target(path, &e);
    if (!af->path) return e;
    struct stat st;
    int exists = stat(af->path, &st) == 0;
    if (exists && S_ISDIR(st.st_mode)) e = EISDIR;
    else if (exists && !S_ISREG(st.st_mode)) { /* a FIFO or device: nothing to rename over */
        af->f = fopen(af->path, "wb");
        if (!af->f) e = errno;
    } else if (exists && access(af->path, W_OK) != 0) {
        e = errno; /* a read-only file is not replaced behind its back */
    } else {
        size_t d = dir_len(af->path), b = strlen(af->path) - d;
        if (b == 0) e = EISDIR;
        else if (!(af->temp = malloc(d + b + 16))) e = ENOMEM;
        int fd = -1;
        for (int attempt = 0; !e && fd < 0; attempt++) {
            /* "<folder>/.<name>.XXXXXX.tmp", the name cut so the whole stays under NAME_MAX */
            int n = snprintf(af->temp, d + b + 16, "%.*s.%.*s.XXXXXX.tmp", (int)d, af->path,
                             (int)(b < MAX_BASE ? b : MAX_BASE), af->path + d);
            fill_random(af->temp + n - 10, attempt, af);
            fd = open(af->temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd < 0 && (errno != EEXIST || attempt == 99)) e = errno;
        }
        if (!e && exists) {
            /* Best effort: the old file's owner and mode (fchown fails for
             * a non-root user giving the file away; the mode still holds). */
            if (fchown(fd, st.st_uid, st.st_gid) != 0) (void)0;
            if (fchmod(fd, st.st_mode & 07777) != 0) (void)0;
        }
        if (!e && !(af->f = fdopen(fd, "wb"))) e = errno;
        if (e && fd >= 0) {
            close(fd);
            unlink(af->temp);
        }
    }
    if (e) clear(af);
    return e;
}

void atomic_abort(atomic_file *af) {
    if (af->f) fclose(af->f);
    if (af->temp) unlink(af->temp);
    clear(af);
}

int atomic_commit(atomic_file *af) {
    if (!af->f) {
        clear(af);
        return EBADF;
    }
    int e = 0;
    errno = 0;
    if (fflush(af->f) != 0 || ferror(af->f)) e = errno ? errno : EIO;
    /* With sync, synced before the rename, so a crash after it finds the
     * new bytes, not an empty file under the old name. */
    if (!e && af->temp && af->sync && fsync(fileno(af->f)) != 0) e = errno;
    errno = 0;
    if (fclose(af->f) != 0 && !e) e = errno ? errno : EIO;
    af->f = NULL;
    if (!e && af->temp && rename(af->temp, af->path) != 0) e = errno;
    if (e && af->temp) unlink(af->temp);
    if (!e && af->temp && af->sync) { /* the rename itself made durable; best effort */
        size_t d = dir_len(af->path);
        char *dir = d ? dup_n(af->path, d) : NULL;
        int fd = open(dir ? dir : ".", O_RDONLY | O_CLOEXEC);
        if (fd >= 0) {
            if (fsync(fd) != 0) (void)0;
            close(fd);
        }
        free(dir);
    }
    clear(af);
    return e;
}

void atomic_start_writeback(atomic_file *af) {
#ifdef __linux__
    /* nbytes 0: up to the end; SYNC_FILE_RANGE_WRITE only queues the I/O */
    if (af->f && fflush(af->f) == 0 && sync_file_range(fileno(af->f), 0, 0, SYNC_FILE_RANGE_WRITE) != 0) (void)0;
#else
    (void)af;
#endif
}

int atomic_write(const char *path, const void *data, size_t len) {
    atomic_file af;
    int e = atomic_open(&af, path);
    if (e) return e;
    errno = 0;
    if (len && fwrite(data, 1, len, af.f) != len) {
        e = errno ? errno : EIO;
        atomic_abort(&af);
        return e;
    }
    return atomic_commit(&af);
}

int atomic_check(const char *path, char *why, size_t cap) {
    int e = 0;
    char *t = path && path[0] ? final_target(path, &e) : NULL;
    if (!t) {
        e = e ? e : ENOENT;
        snprintf(why, cap, "%s", strerror(e));
        return e;
    }
    struct stat st;
    size_t d = dir_len(t);
    char *dir = d ? dup_n(t, d > 1 ? d - 1 : d) : NULL; /* "/a/b" for "/a/b/x.glb" */
    const char *shown = dir ? dir : ".";
    if (stat(t, &st) == 0 && S_ISDIR(st.st_mode)) {
        e = EISDIR;
        snprintf(why, cap, "'%s' is a folder, not a file", t);
    } else if (stat(t, &st) == 0 && !S_ISREG(st.st_mode)) {
        if (access(t, W_OK) != 0) snprintf(why, cap, "'%s' is not writable (%s)", t, strerror(e = errno));
    } else if (d && t[d] == '\0') {
        e = EISDIR;
        snprintf(why, cap, "'%s' names a folder, not a file", t);
    } else if (stat(dir ? dir : ".", &st) != 0) {
        e = errno;
        snprintf(why, cap, e == ENAMETOOLONG ? "folder '%s' cannot be reached (%s)" : "folder '%s' does not exist (%s)",
                 shown, strerror(e));
    } else if (!S_ISDIR(st.st_mode)) {
        e = ENOTDIR;
        snprintf(why, cap, "'%s' is not a folder", shown);
    } else if (access(dir ? dir : ".", W_OK | X_OK) != 0) {
        e = errno;
        snprintf(why, cap, "folder '%s' is not writable (%s)", shown, strerror(e));
    } else if (access(t, F_OK) == 0 && access(t, W_OK) != 0) {
        e = errno;
        snprintf(why, cap, "'%s' is not writable (%s)", t, strerror(e));
    } else {
        /* The name must fit the folder's file system, or the rename at the
         * end of a long run fails (the temporary name is cut to fit). */
        long most = pathconf(dir ? dir : ".", _PC_NAME_MAX);
        size_t b = strlen(t + d);
        if (most > 0 && b > (size_t)most) {
            e = ENAMETOOLONG;
            snprintf(why, cap, "the file name is %zu bytes, longer than the %ld the folder '%s' allows; choose a "
                     "shorter name", b, most, shown);
        }
    }
    free(dir);
    free(t);
    return e;
}

/* atomic_file.c - write a temporary file, then rename it (atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "platform.h"

enum { MAX_LINKS = 40, MAX_BASE = 200 };

static char *dup_n(const char *s, size_t n) {
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

/* Length of path's folder part including its last separator, 0 when none. */
static size_t dir_len(const char *path) {
    size_t d = 0;
    for (size_t i = 0; path[i]; i++)
        if (plat_is_sep(path[i])) d = i + 1;
    return d;
}

/* path with its symbolic links followed to the last link's target, which
 * need not exist yet (a dangling link is written through, like fopen).
 * malloc'd; NULL with *e set on failure. */
static char *final_target(const char *path, int *e) {
    char *p = dup_n(path, strlen(path));
    for (int hops = 0; p; hops++) {
        plat_info st;
        if (plat_stat(p, &st, 0) != 0 || st.kind != PLAT_LINK) return p;
        char *link = hops < MAX_LINKS ? plat_readlink(p, e) : NULL;
        if (!link) {
            if (hops >= MAX_LINKS) *e = ELOOP;
            free(p);
            return NULL;
        }
        size_t n = strlen(link), d = plat_is_absolute(link) ? 0 : dir_len(p);
        char *q = malloc(d + n + 1);
        if (q) {
            memcpy(q, p, d);
            memcpy(q + d, link, n + 1);
        }
        free(link);
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
    double now = plat_wall();
    uint64_t sec = (uint64_t)now, nsec = (uint64_t)((now - (double)sec) * 1e9);
    uint64_t v = plat_pid() * 0x9E3779B97F4A7C15ull ^ nsec ^ sec << 30 ^ (uint64_t)(uintptr_t)salt ^
                 (uint64_t)attempt * 0xBF58476D1CE4E5B9ull;
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
    plat_info st;
    int exists = plat_stat(af->path, &st, 1) == 0;
    if (exists && st.kind == PLAT_DIR) e = EISDIR;
    else if (exists && st.kind != PLAT_FILE) { /* a FIFO or device: nothing to rename over */
        af->f = plat_fopen(af->path, "wb");
        if (!af->f) e = errno;
    } else if (exists && (e = plat_access(af->path, 1)) != 0) {
        /* a read-only file is not replaced behind its back */
    } else {
        size_t d = dir_len(af->path), b = strlen(af->path) - d;
        if (b == 0) e = EISDIR;
        else if (!(af->temp = malloc(d + b + 16))) e = ENOMEM;
        for (int attempt = 0; !e && !af->f; attempt++) {
            /* "<folder>/.<name>.XXXXXX.tmp", the name cut so the whole stays under NAME_MAX */
            int n = snprintf(af->temp, d + b + 16, "%.*s.%.*s.XXXXXX.tmp", (int)d, af->path,
                             (int)(b < MAX_BASE ? b : MAX_BASE), af->path + d);
            fill_random(af->temp + n - 10, attempt, af);
            int c = plat_create_new(af->temp, exists ? &st : NULL, &af->f);
            if (c && (c != EEXIST || attempt == 99)) e = c;
        }
    }
    if (e) clear(af);
    return e;
}

void atomic_abort(atomic_file *af) {
    if (af->f) fclose(af->f);
    if (af->temp) plat_remove(af->temp);
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
    if (!e && af->temp && af->sync) e = plat_sync(af->f);
    errno = 0;
    if (fclose(af->f) != 0 && !e) e = errno ? errno : EIO;
    af->f = NULL;
    if (!e && af->temp) e = plat_replace(af->temp, af->path);
    if (e && af->temp) plat_remove(af->temp);
    if (!e && af->temp && af->sync) { /* the rename itself made durable; best effort */
        size_t d = dir_len(af->path);
        char *dir = d ? dup_n(af->path, d) : NULL;
        plat_sync_dir(dir ? dir : ".");
        free(dir);
    }
    clear(af);
    return e;
}

void atomic_start_writeback(atomic_file *af) {
    if (af->f && fflush(af->f) == 0) plat_start_writeback(af->f);
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
    plat_info st;
    size_t d = dir_len(t);
    char *dir = d ? dup_n(t, d > 1 ? d - 1 : d) : NULL; /* "/a/b" for "/a/b/x.glb" */
    const char *shown = dir ? dir : ".";
    int exists = plat_stat(t, &st, 1) == 0;
    if (exists && st.kind == PLAT_DIR) {
        e = EISDIR;
        snprintf(why, cap, "'%s' is a folder, not a file", t);
    } else if (exists && st.kind != PLAT_FILE) {
        if ((e = plat_access(t, 1)) != 0) snprintf(why, cap, "'%s' is not writable (%s)", t, strerror(e));
    } else if (d && t[d] == '\0') {
        e = EISDIR;
        snprintf(why, cap, "'%s' names a folder, not a file", t);
    } else if ((e = plat_stat(dir ? dir : ".", &st, 1)) != 0) {
        snprintf(why, cap, e == ENAMETOOLONG ? "folder '%s' cannot be reached (%s)" : "folder '%s' does not exist (%s)",
                 shown, strerror(e));
    } else if (st.kind != PLAT_DIR) {
        e = ENOTDIR;
        snprintf(why, cap, "'%s' is not a folder", shown);
    } else if ((e = plat_access(dir ? dir : ".", 1)) != 0) {
        snprintf(why, cap, "folder '%s' is not writable (%s)", shown, strerror(e));
    } else if (plat_access(t, 0) == 0 && (e = plat_access(t, 1)) != 0) {
        snprintf(why, cap, "'%s' is not writable (%s)", t, strerror(e));
    } else {
        /* The name must fit the folder's file system, or the rename at the
         * end of a long run fails (the temporary name is cut to fit). */
        long most = plat_name_max(dir ? dir : ".");
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

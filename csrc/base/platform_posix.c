/* platform_posix.c - platform.h on Linux and other POSIX systems. */
#ifdef __linux__
#define _GNU_SOURCE /* sync_file_range, dladdr */
#else
#define _POSIX_C_SOURCE 200809L
#endif
#include "base/platform.h"

#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

double plat_clock(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

double plat_wall(void) {
    struct timespec t;
    if (timespec_get(&t, TIME_UTC) != TIME_UTC) return 0.0;
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

void plat_sleep_us(long us) {
    struct timespec t = {us / 1000000, (us % 1000000) * 1000};
    nanosleep(&t, NULL);
}

int plat_cpus(void) {
    long c = sysconf(_SC_NPROCESSORS_ONLN);
    return c < 1 ? 1 : c > 1 << 20 ? 1 << 20 : (int)c;
}

uint64_t plat_pid(void) { return (uint64_t)getpid(); }

double plat_rss_mb(void) {
#if defined(__linux__)
    /* statm's second field: resident pages. Counts every thread's memory,
     * which is what a budget for threads must see. */
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return 0.0;
    unsigned long long size = 0, res = 0;
    int n = fscanf(f, "%llu %llu", &size, &res);
    fclose(f);
    return n == 2 ? (double)res * 4096.0 / (1024.0 * 1024.0) : 0.0;
#else
    return 0.0;
#endif
}

int plat_thread_start(plat_thread *t, plat_thread_fn fn, void *arg) { return pthread_create(&t->id, NULL, fn, arg); }

void plat_thread_join(plat_thread *t) { pthread_join(t->id, NULL); }

void plat_lock_take(plat_lock *l) { pthread_mutex_lock(&l->m); }

void plat_lock_give(plat_lock *l) { pthread_mutex_unlock(&l->m); }

int plat_stat(const char *path, plat_info *info, int follow) {
    struct stat st;
    memset(info, 0, sizeof *info);
    if ((follow ? stat(path, &st) : lstat(path, &st)) != 0) return errno;
    info->kind = S_ISREG(st.st_mode) ? PLAT_FILE : S_ISDIR(st.st_mode) ? PLAT_DIR : S_ISLNK(st.st_mode) ? PLAT_LINK
                                                                                                      : PLAT_OTHER;
    info->size = (uint64_t)st.st_size;
    info->mtime = (int64_t)st.st_mtime;
    info->mode = (unsigned)st.st_mode & 07777;
    info->uid = (int64_t)st.st_uid;
    info->gid = (int64_t)st.st_gid;
    return 0;
}

char *plat_readlink(const char *path, int *e) {
    char link[4096];
    ssize_t n = readlink(path, link, sizeof link - 1);
    if (n < 0) {
        *e = errno;
        return NULL;
    }
    char *s = malloc((size_t)n + 1);
    if (!s) {
        *e = ENOMEM;
        return NULL;
    }
    memcpy(s, link, (size_t)n);
    s[n] = '\0';
    return s;
}

int plat_access(const char *path, int w) {
    struct stat st;
    int dir = w && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
    return access(path, w ? (dir ? W_OK | X_OK : W_OK) : F_OK) == 0 ? 0 : errno;
}

FILE *plat_fopen(const char *path, const char *mode) { return fopen(path, mode); }

int plat_create_new(const char *path, const plat_info *like, FILE **out) {
    *out = NULL;
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return errno;
    if (like) {
        /* Best effort: the old file's owner and mode (fchown fails for
         * a non-root user giving the file away; the mode still holds). */
        if (fchown(fd, (uid_t)like->uid, (gid_t)like->gid) != 0) (void)0;
        if (fchmod(fd, (mode_t)like->mode) != 0) (void)0;
    }
    if (!(*out = fdopen(fd, "wb"))) {
        int e = errno;
        close(fd);
        unlink(path);
        return e;
    }
    return 0;
}

int plat_sync(FILE *f) { return fsync(fileno(f)) == 0 ? 0 : errno; }

void plat_start_writeback(FILE *f) {
#ifdef __linux__
    /* nbytes 0: up to the end; SYNC_FILE_RANGE_WRITE only queues the I/O */
    if (sync_file_range(fileno(f), 0, 0, SYNC_FILE_RANGE_WRITE) != 0) (void)0;
#else
    (void)f;
#endif
}

void plat_sync_dir(const char *dir) {
    int fd = open(dir, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        if (fsync(fd) != 0) (void)0;
        close(fd);
    }
}

int plat_replace(const char *from, const char *to) { return rename(from, to) == 0 ? 0 : errno; }

int plat_remove(const char *path) { return unlink(path) == 0 ? 0 : errno; }

int plat_mkdir(const char *path) { return mkdir(path, 0700) == 0 ? 0 : errno; }

void plat_touch(const char *path) {
    if (utimensat(AT_FDCWD, path, NULL, 0) != 0) (void)0;
}

long plat_name_max(const char *dir) {
    long most = pathconf(dir, _PC_NAME_MAX);
    return most > 0 ? most : 0;
}

int plat_is_sep(char c) { return c == '/'; }

int plat_is_absolute(const char *path) { return path[0] == '/'; }

struct plat_dir {
    DIR *d;
};

plat_dir *plat_dir_open(const char *path) {
    DIR *d = opendir(path);
    if (!d) return NULL;
    plat_dir *p = malloc(sizeof *p);
    if (!p) {
        closedir(d);
        return NULL;
    }
    p->d = d;
    return p;
}

const char *plat_dir_next(plat_dir *p) {
    struct dirent *de;
    while ((de = readdir(p->d)) != NULL)
        if (strcmp(de->d_name, ".") != 0 && strcmp(de->d_name, "..") != 0) return de->d_name;
    return NULL;
}

void plat_dir_close(plat_dir *p) {
    closedir(p->d);
    free(p);
}

int plat_user_cache(char *out, size_t cap, const char *sub) {
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (xdg && xdg[0] == '/') n = snprintf(out, cap, "%s/%s", xdg, sub); /* the spec: relative is ignored */
    else if (home && home[0]) n = snprintf(out, cap, "%s/.cache/%s", home, sub);
    else return 0;
    return n > 0 && (size_t)n < cap;
}

void *plat_module_open_beside(const void *here, const char *name) {
    Dl_info self;
    if (!dladdr(here, &self) || !self.dli_fname) return NULL;
    const char *slash = strrchr(self.dli_fname, '/');
    size_t dir = slash ? (size_t)(slash - self.dli_fname + 1) : 0, len = strlen(name) + 1;
    char path[4096];
    if (dir + len > sizeof path) return NULL;
    memcpy(path, self.dli_fname, dir);
    memcpy(path + dir, name, len);
    return dlopen(slash ? path : name, RTLD_NOW | RTLD_LOCAL);
}

void (*plat_module_fn(void *module, const char *name))(void) {
    void (*fn)(void);
    void *sym = dlsym(module, name);
    memcpy(&fn, &sym, sizeof fn); /* ISO C has no object-to-function pointer cast */
    return fn;
}

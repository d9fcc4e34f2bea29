/* platform.h - what POSIX and Windows do differently, in one place:
 * the clock and sleeping, processors and resident memory, threads and a
 * lock, files (stat, exclusive create, sync, atomic replace, folders),
 * user folders and loading a module that sits beside the library.
 * platform_posix.c and platform_win.c implement it; nothing else in the
 * library includes an operating system's header.
 *
 * Paths are UTF-8 on both (Windows converts them to UTF-16 for its wide
 * calls). Functions that can fail return 0 or an errno value. */
#ifndef BANYAN_BASE_PLATFORM_H
#define BANYAN_BASE_PLATFORM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ time, CPUs */
/* Seconds on a monotonic clock (for intervals only). */
double plat_clock(void);
/* Seconds on the wall clock (UTC); 0 where it cannot be read. */
double plat_wall(void);
/* Sleeps at least us microseconds (Windows: whole milliseconds). */
void plat_sleep_us(long us);
/* Processors online, at least 1. */
int plat_cpus(void);
/* This process's id. */
uint64_t plat_pid(void);
/* Resident memory of the process in MB, every thread's; 0 where it
 * cannot be read. */
double plat_rss_mb(void);

/* --------------------------------------------------------------- threads */
/* POSIX threads, or Win32 threads (platform_win.c says why not
 * winpthreads). The two types are the only #ifdef outside the two files. */
#ifdef _WIN32
typedef struct plat_thread {
    void *handle; /* HANDLE */
} plat_thread;
typedef struct plat_lock {
    void *srw; /* SRWLOCK */
} plat_lock;
#define PLAT_LOCK_INIT {0}
#else
#include <pthread.h>
typedef struct plat_thread {
    pthread_t id;
} plat_thread;
typedef struct plat_lock {
    pthread_mutex_t m;
} plat_lock;
#define PLAT_LOCK_INIT {PTHREAD_MUTEX_INITIALIZER}
#endif
typedef void *(*plat_thread_fn)(void *arg);
/* Starts fn(arg) on a new thread; 0 on success. */
int plat_thread_start(plat_thread *t, plat_thread_fn fn, void *arg);
/* Waits for the thread and releases it. */
void plat_thread_join(plat_thread *t);

/* A lock that needs no set-up: a static one is PLAT_LOCK_INIT. */
void plat_lock_take(plat_lock *l);
void plat_lock_give(plat_lock *l);

/* ----------------------------------------------------------------- files */
enum { PLAT_MISSING = 0, PLAT_FILE, PLAT_DIR, PLAT_LINK, PLAT_OTHER };
typedef struct plat_info {
    int kind;          /* PLAT_* */
    uint64_t size;     /* bytes */
    int64_t mtime;     /* seconds since 1970 */
    unsigned mode;     /* permission bits (POSIX) */
    int64_t uid, gid;  /* owner (POSIX; -1 elsewhere) */
} plat_info;
/* What path is; follow = 0 describes a symbolic link itself. ENOENT when
 * it does not exist (info->kind PLAT_MISSING). */
int plat_stat(const char *path, plat_info *info, int follow);
/* The text of a symbolic link, malloc'd; NULL with *e set when path is
 * not one or on failure (Windows follows no links: EINVAL). */
char *plat_readlink(const char *path, int *e);
/* 0 when path can be written (w) or just exists (!w), else errno. For a
 * folder, writable means files can be created in it. */
int plat_access(const char *path, int w);
/* fopen with a UTF-8 path; binary is up to mode ("rb", "wb"). */
FILE *plat_fopen(const char *path, const char *mode);
/* Creates path, which must not exist yet, for binary writing, not
 * inherited by child processes; like (when not NULL) gives the mode and
 * owner to copy, best effort. */
int plat_create_new(const char *path, const plat_info *like, FILE **out);
/* Syncs f's written bytes to the disk (after fflush). */
int plat_sync(FILE *f);
/* Starts writing f back to the disk without waiting; best effort. */
void plat_start_writeback(FILE *f);
/* Makes a rename in folder dir durable; best effort. */
void plat_sync_dir(const char *dir);
/* Renames from over to in one step: a reader sees the old or the new. */
int plat_replace(const char *from, const char *to);
/* Removes a file. */
int plat_remove(const char *path);
/* Creates a folder (0700 where modes exist); EEXIST when it is there. */
int plat_mkdir(const char *path);
/* Sets path's modification time to now; best effort. */
void plat_touch(const char *path);
/* The longest file name the folder allows, 0 when unknown. */
long plat_name_max(const char *dir);
/* Whether c separates a path's folders ('/'; '\\' too on Windows). */
int plat_is_sep(char c);
/* Whether path is absolute ("/..."; "C:\...", "\\server\..." on Windows). */
int plat_is_absolute(const char *path);

/* A folder's entries, "." and ".." left out. */
typedef struct plat_dir plat_dir;
plat_dir *plat_dir_open(const char *path);
/* The next entry's name, NULL at the end; valid until the next call. */
const char *plat_dir_next(plat_dir *d);
void plat_dir_close(plat_dir *d);

/* The user's cache folder (XDG_CACHE_HOME or ~/.cache; Windows:
 * %LOCALAPPDATA%) followed by sub; 1 when it fit in cap. */
int plat_user_cache(char *out, size_t cap, const char *sub);

/* --------------------------------------------------------------- modules */
/* Loads the module file name from the folder of the module (shared
 * library or program) that holds the address here; NULL on failure. */
void *plat_module_open_beside(const void *here, const char *name);
/* The module's function name, or NULL. */
void (*plat_module_fn(void *module, const char *name))(void);

#ifdef __cplusplus
}
#endif
#endif

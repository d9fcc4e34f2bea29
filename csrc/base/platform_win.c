/* platform_win.c - platform.h on Windows (built with mingw-w64).
 *
 * Threads are Win32's own, not winpthreads: the library needs a thread
 * start and join and one static lock, which CreateThread and an SRWLOCK
 * give directly, so its C code does not depend on a POSIX emulation (the
 * winpthreads DLL still ships: mingw's libstdc++, built for the posix
 * thread model that TBB and OpenVDB need, imports it).
 *
 * Paths are UTF-8 and go to the wide (UTF-16) calls. Symbolic links are
 * not followed by hand (Windows resolves them itself). */
#define WIN32_LEAN_AND_MEAN
#include <windows.h>
#include <psapi.h>

#include <errno.h>
#include <fcntl.h>
#include <io.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <wchar.h>

#include "base/platform.h"

/* path as a malloc'd UTF-16 string, NULL on failure (errno set). */
static wchar_t *wide(const char *path) {
    int n = MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, NULL, 0);
    if (n <= 0) {
        errno = EINVAL;
        return NULL;
    }
    wchar_t *w = malloc((size_t)n * sizeof *w);
    if (!w) {
        errno = ENOMEM;
        return NULL;
    }
    MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, w, n);
    return w;
}

/* The errno value closest to GetLastError's. */
static int win_errno(DWORD e) {
    switch (e) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND:
    case ERROR_INVALID_DRIVE: return ENOENT;
    case ERROR_ACCESS_DENIED:
    case ERROR_SHARING_VIOLATION:
    case ERROR_LOCK_VIOLATION: return EACCES;
    case ERROR_FILE_EXISTS:
    case ERROR_ALREADY_EXISTS: return EEXIST;
    case ERROR_NOT_ENOUGH_MEMORY:
    case ERROR_OUTOFMEMORY: return ENOMEM;
    case ERROR_DISK_FULL:
    case ERROR_HANDLE_DISK_FULL: return ENOSPC;
    case ERROR_FILENAME_EXCED_RANGE: return ENAMETOOLONG;
    case ERROR_DIRECTORY: return ENOTDIR;
    case ERROR_WRITE_PROTECT: return EROFS;
    default: return EIO;
    }
}

double plat_clock(void) {
    LARGE_INTEGER f, c;
    QueryPerformanceFrequency(&f);
    QueryPerformanceCounter(&c);
    return (double)c.QuadPart / (double)f.QuadPart;
}

double plat_wall(void) {
    FILETIME ft;
    GetSystemTimePreciseAsFileTime(&ft);
    uint64_t t = (uint64_t)ft.dwHighDateTime << 32 | ft.dwLowDateTime; /* 100 ns since 1601 */
    return (double)(t - 116444736000000000ull) * 1e-7;
}

void plat_sleep_us(long us) { Sleep((DWORD)((us + 999) / 1000)); }

int plat_cpus(void) {
    DWORD n = GetActiveProcessorCount(ALL_PROCESSOR_GROUPS);
    return n < 1 ? 1 : (int)n;
}

uint64_t plat_pid(void) { return (uint64_t)GetCurrentProcessId(); }

double plat_rss_mb(void) {
    PROCESS_MEMORY_COUNTERS pmc;
    if (!GetProcessMemoryInfo(GetCurrentProcess(), &pmc, sizeof pmc)) return 0.0;
    return (double)pmc.WorkingSetSize / (1024.0 * 1024.0);
}

typedef struct start {
    plat_thread_fn fn;
    void *arg;
} start;

static DWORD WINAPI trampoline(LPVOID p) {
    start s = *(start *)p;
    free(p);
    s.fn(s.arg);
    return 0;
}

int plat_thread_start(plat_thread *t, plat_thread_fn fn, void *arg) {
    start *s = malloc(sizeof *s);
    if (!s) return ENOMEM;
    s->fn = fn;
    s->arg = arg;
    t->handle = CreateThread(NULL, 0, trampoline, s, 0, NULL);
    if (!t->handle) {
        free(s);
        return EAGAIN;
    }
    return 0;
}

void plat_thread_join(plat_thread *t) {
    WaitForSingleObject(t->handle, INFINITE);
    CloseHandle(t->handle);
    t->handle = NULL;
}

void plat_lock_take(plat_lock *l) { AcquireSRWLockExclusive((PSRWLOCK)&l->srw); }

void plat_lock_give(plat_lock *l) { ReleaseSRWLockExclusive((PSRWLOCK)&l->srw); }

int plat_stat(const char *path, plat_info *info, int follow) {
    (void)follow;
    memset(info, 0, sizeof *info);
    info->uid = info->gid = -1;
    wchar_t *w = wide(path);
    if (!w) return errno;
    WIN32_FILE_ATTRIBUTE_DATA a;
    BOOL ok = GetFileAttributesExW(w, GetFileExInfoStandard, &a);
    free(w);
    if (!ok) return win_errno(GetLastError());
    info->kind = a.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY ? PLAT_DIR
                 : a.dwFileAttributes & FILE_ATTRIBUTE_DEVICE  ? PLAT_OTHER
                                                               : PLAT_FILE;
    info->size = (uint64_t)a.nFileSizeHigh << 32 | a.nFileSizeLow;
    uint64_t t = (uint64_t)a.ftLastWriteTime.dwHighDateTime << 32 | a.ftLastWriteTime.dwLowDateTime;
    info->mtime = (int64_t)((t - 116444736000000000ull) / 10000000ull);
    info->mode = a.dwFileAttributes & FILE_ATTRIBUTE_READONLY ? 0444 : 0666;
    return 0;
}

char *plat_readlink(const char *path, int *e) {
    (void)path;
    *e = EINVAL;
    return NULL;
}

int plat_access(const char *path, int w) {
    plat_info info;
    int e = plat_stat(path, &info, 1);
    if (e) return e;
    /* The read-only attribute is what Windows has of a file's write bit;
     * a folder's is ignored by Windows (ACLs decide, and a failed
     * create says so later). */
    return w && info.kind == PLAT_FILE && !(info.mode & 0200) ? EACCES : 0;
}

FILE *plat_fopen(const char *path, const char *mode) {
    wchar_t *w = wide(path), wm[8];
    if (!w) return NULL;
    size_t i = 0;
    for (; mode[i] && i < 7; i++) wm[i] = (wchar_t)mode[i];
    wm[i] = 0;
    FILE *f = _wfopen(w, wm);
    free(w);
    return f;
}

int plat_create_new(const char *path, const plat_info *like, FILE **out) {
    *out = NULL;
    wchar_t *w = wide(path);
    if (!w) return errno;
    int fd = _wopen(w, _O_WRONLY | _O_CREAT | _O_EXCL | _O_BINARY | _O_NOINHERIT,
                    like && !(like->mode & 0200) ? _S_IREAD : _S_IREAD | _S_IWRITE);
    int e = fd < 0 ? errno : 0;
    if (!e && !(*out = _fdopen(fd, "wb"))) {
        e = errno;
        _close(fd);
        _wunlink(w);
    }
    free(w);
    return e;
}

int plat_sync(FILE *f) { return _commit(_fileno(f)) == 0 ? 0 : errno; }

void plat_start_writeback(FILE *f) { (void)f; }

void plat_sync_dir(const char *dir) { (void)dir; /* MoveFileEx's MOVEFILE_WRITE_THROUGH did it */ }

int plat_replace(const char *from, const char *to) {
    wchar_t *a = wide(from), *b = a ? wide(to) : NULL;
    int e = 0;
    if (!a || !b) e = errno;
    else if (!MoveFileExW(a, b, MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) e = win_errno(GetLastError());
    free(a);
    free(b);
    return e;
}

int plat_remove(const char *path) {
    wchar_t *w = wide(path);
    if (!w) return errno;
    int e = _wunlink(w) == 0 ? 0 : errno;
    free(w);
    return e;
}

int plat_mkdir(const char *path) {
    wchar_t *w = wide(path);
    if (!w) return errno;
    int e = _wmkdir(w) == 0 ? 0 : errno;
    free(w);
    return e;
}

void plat_touch(const char *path) {
    wchar_t *w = wide(path);
    if (!w) return;
    HANDLE h = CreateFileW(w, FILE_WRITE_ATTRIBUTES, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, NULL,
                           OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, NULL);
    free(w);
    if (h == INVALID_HANDLE_VALUE) return;
    FILETIME now;
    GetSystemTimeAsFileTime(&now);
    SetFileTime(h, NULL, NULL, &now);
    CloseHandle(h);
}

long plat_name_max(const char *dir) {
    (void)dir;
    return 255; /* NTFS, FAT32 long names, ReFS: 255 UTF-16 units */
}

int plat_is_sep(char c) { return c == '/' || c == '\\'; }

int plat_is_absolute(const char *path) {
    return plat_is_sep(path[0]) || (((path[0] | 32) >= 'a' && (path[0] | 32) <= 'z') && path[1] == ':');
}

struct plat_dir {
    HANDLE h;
    int first;
    WIN32_FIND_DATAW fd;
    char name[MAX_PATH * 3 + 1];
};

plat_dir *plat_dir_open(const char *path) {
    size_t n = strlen(path);
    char *pattern = malloc(n + 3);
    if (!pattern) return NULL;
    memcpy(pattern, path, n);
    memcpy(pattern + n, n && plat_is_sep(path[n - 1]) ? "*" : "\\*", 3);
    wchar_t *w = wide(pattern);
    free(pattern);
    if (!w) return NULL;
    plat_dir *d = malloc(sizeof *d);
    if (d) {
        d->h = FindFirstFileW(w, &d->fd);
        d->first = 1;
        if (d->h == INVALID_HANDLE_VALUE) {
            free(d);
            d = NULL;
        }
    }
    free(w);
    return d;
}

const char *plat_dir_next(plat_dir *d) {
    for (;;) {
        if (!d->first && !FindNextFileW(d->h, &d->fd)) return NULL;
        d->first = 0;
        const wchar_t *n = d->fd.cFileName;
        if (!wcscmp(n, L".") || !wcscmp(n, L"..")) continue;
        if (WideCharToMultiByte(CP_UTF8, 0, n, -1, d->name, (int)sizeof d->name, NULL, NULL) > 0) return d->name;
    }
}

void plat_dir_close(plat_dir *d) {
    FindClose(d->h);
    free(d);
}

int plat_user_cache(char *out, size_t cap, const char *sub) {
    const char *local = getenv("LOCALAPPDATA");
    if (!local || !local[0]) return 0;
    int n = snprintf(out, cap, "%s\\%s", local, sub);
    return n > 0 && (size_t)n < cap;
}

void *plat_module_open_beside(const void *here, const char *name) {
    HMODULE self;
    if (!GetModuleHandleExW(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                            (LPCWSTR)here, &self))
        return NULL;
    wchar_t path[32768];
    DWORD n = GetModuleFileNameW(self, path, 32768);
    if (n == 0 || n >= 32768) return NULL;
    DWORD dir = n;
    while (dir > 0 && path[dir - 1] != L'\\' && path[dir - 1] != L'/') dir--;
    wchar_t *w = wide(name);
    if (!w) return NULL;
    size_t len = wcslen(w) + 1;
    HMODULE h = NULL;
    if (dir + len <= 32768) {
        memcpy(path + dir, w, len * sizeof *w);
        /* The module's own imports (OpenVDB, TBB) from its folder too. */
        h = LoadLibraryExW(path, NULL, LOAD_LIBRARY_SEARCH_DLL_LOAD_DIR | LOAD_LIBRARY_SEARCH_DEFAULT_DIRS);
    }
    free(w);
    return (void *)h;
}

void (*plat_module_fn(void *module, const char *name))(void) {
    FARPROC p = GetProcAddress((HMODULE)module, name);
    void (*fn)(void);
    memcpy(&fn, &p, sizeof fn);
    return fn;
}

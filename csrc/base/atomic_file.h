/* atomic_file.h - every file banyan writes (glTF, PNG) goes through here:
 * the bytes go to a temporary file next to the target,
 * ".<name>.XXXXXX.tmp" in the same folder, which is flushed, synced
 * (unless the caller clears af->sync) and renamed over the target only
 * when all of it is written. A failed write
 * (full disk, file size limit, unwritable folder) removes the temporary
 * file and leaves the old target as it was; a process killed mid-write
 * (SIGKILL, SIGXFSZ) may leave the temporary file, never a cut target.
 *
 * A symbolic link is followed: its final target is replaced whole and the
 * link stays. The old file's permission bits (and, where allowed, owner
 * and group) are kept; a new file gets 0666 less the umask, as fopen
 * would. A target that exists but is not a regular file (a FIFO, a
 * device) is written in place, as there is nothing to rename over.
 * A hard-linked target is replaced for this name only.
 *
 * Functions return 0 or an errno value. They keep no global state; the
 * CLI compiles this file too (the library's symbols are hidden). */
#ifndef BANYAN_ATOMIC_FILE_H
#define BANYAN_ATOMIC_FILE_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" { /* the glTF writer (C++) writes through it too */
#endif

typedef struct atomic_file {
    FILE *f;     /* write here */
    char *path;  /* the file replaced at commit (symlinks followed) */
    char *temp;  /* the temporary file; NULL when writing in place */
    int sync;    /* 1 (atomic_open's default): fsync file and folder at commit */
} atomic_file;

/* Creates the temporary file for path. On failure *af is cleared and
 * there is nothing to abort. */
int atomic_open(atomic_file *af, const char *path);
/* Starts the disk writing back what af holds so far, without waiting
 * (Linux; elsewhere nothing), so a later sync waits less. Best effort. */
void atomic_start_writeback(atomic_file *af);
/* Flushes, syncs (af->sync), closes and renames the temporary file over the target.
 * On failure the temporary file is removed and the target is untouched.
 * Either way *af is released. */
int atomic_commit(atomic_file *af);
/* Closes and removes the temporary file; the target is untouched. Safe on
 * a cleared or released *af. */
void atomic_abort(atomic_file *af);
/* len bytes as the whole new contents of path. */
int atomic_write(const char *path, const void *data, size_t len);
/* Whether path could be written, checked before any work is done: its
 * folder exists and is writable, path is not a folder and, if it exists,
 * is writable. On failure why (cap bytes) says what is wrong. */
int atomic_check(const char *path, char *why, size_t cap);

#ifdef __cplusplus
}
#endif

#endif

/* test_atomic_write.c - a write never destroys the file it replaces
 * (base/atomic_file.h): a full disk, a killed run and an
 * unwritable folder leave the old .glb byte for byte, a symlink stays a
 * link with its target replaced whole, no temporary file is left behind
 * by a failed write. The full disk and the kill are RLIMIT_FSIZE in a
 * child process: with SIGXFSZ ignored write() fails with EFBIG, with it
 * at its default the child dies mid-write.
 *
 *   test_atomic_write OUTDIR
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "banyan.h"
#include "check.h"
#include "base/atomic_file.h"
#include "test_files.h"

enum { LIMIT = 64 * 1024 }; /* the "disk" of the children, in bytes */

/* A tube of n points and the given sides: n = 400, sides = 32 writes
 * about 600 KB, well past LIMIT; n = 20, sides = 6 about 10 KB. */
static banyan_mesh *tube(uint32_t n, int32_t sides) {
    double *pts = calloc(3 * (size_t)n, sizeof *pts), *rad = calloc(n, sizeof *rad);
    for (uint32_t i = 0; i < n; i++) {
        pts[3 * i + 0] = 0.1 * sin(0.2 * i);
        pts[3 * i + 2] = 0.05 * i;
        rad[i] = 0.05;
    }
    banyan_mesh *m = NULL;
    banyan_error err;
    if (banyan_tube_generate(pts, rad, n, sides, 1, &m, &err) != BANYAN_OK) fprintf(stderr, "tube: %s\n", err.message);
    free(pts);
    free(rad);
    return m;
}

static banyan_status write_glb(const char *path, const banyan_mesh *m, banyan_error *err) {
    return banyan_gltf_write(path, &m, NULL, 1, err);
}

static int same_bytes(const char *path, const char *bytes, size_t len) {
    size_t n = 0;
    char *b = test_read_file(path, &n);
    int same = b && n == len && memcmp(b, bytes, len) == 0;
    free(b);
    return same;
}

/* Temporary files (".*.tmp") in dir; removes them when clean is set. */
static int temps(const char *dir, int clean) {
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (e->d_name[0] == '.' && len > 4 && !strcmp(e->d_name + len - 4, ".tmp")) {
            n++;
            if (clean) {
                char p[4400];
                snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
                unlink(p);
            }
        }
    }
    if (d) closedir(d);
    return n;
}

/* Writes m to path in a child limited to LIMIT bytes per file, with
 * SIGXFSZ ignored (write fails: a full disk) or not (the child is
 * killed), as uid when it is not -1. Returns the child's wait status. */
static int child_write(const char *path, const banyan_mesh *m, int ignore_xfsz, int uid) {
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        if (uid >= 0 && (setgid((gid_t)uid) != 0 || setuid((uid_t)uid) != 0)) _exit(100);
        struct rlimit rl = {LIMIT, LIMIT};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(101);
        signal(SIGXFSZ, ignore_xfsz ? SIG_IGN : SIG_DFL);
        banyan_error err;
        banyan_status s = write_glb(path, m, &err);
        if (s) printf("  child: %s\n", err.message);
        fflush(stdout);
        _exit(s);
    }
    int st = -1;
    if (pid > 0) waitpid(pid, &st, 0);
    return st;
}

static int is_link_to(const char *link, const char *target) {
    struct stat st;
    char buf[4096];
    if (lstat(link, &st) != 0 || !S_ISLNK(st.st_mode)) return 0;
    ssize_t n = readlink(link, buf, sizeof buf - 1);
    if (n < 0) return 0;
    buf[n] = '\0';
    return !strcmp(buf, target);
}

static void check_helper(const char *dir) {
    char p[4200], q[4400], why[512];
    const char data[] = "banyan";
    umask(022);
    snprintf(p, sizeof p, "%s/helper.bin", dir);
    unlink(p);
    CHECK(atomic_write(p, data, 6) == 0 && same_bytes(p, data, 6), "atomic_write of a new file");
    struct stat st;
    CHECK(stat(p, &st) == 0 && (st.st_mode & 07777) == 0644, "a new file is 0666 less the umask: %o",
          (unsigned)(st.st_mode & 07777));
    chmod(p, 0600);
    CHECK(atomic_write(p, "x", 1) == 0 && same_bytes(p, "x", 1), "atomic_write over a file");
    CHECK(stat(p, &st) == 0 && (st.st_mode & 07777) == 0600, "the old mode kept: %o", (unsigned)(st.st_mode & 07777));
    CHECK(atomic_write(dir, "x", 1) == EISDIR, "a folder is not replaced");
    /* A dangling link: its target is created, the link stays. */
    snprintf(q, sizeof q, "%s/dangling.bin", dir);
    unlink(q);
    unlink(p);
    CHECK(symlink("helper.bin", q) == 0, "symlink: %s", strerror(errno));
    CHECK(atomic_write(q, data, 6) == 0 && same_bytes(p, data, 6) && is_link_to(q, "helper.bin"),
          "a dangling link is written through");
    unlink(q);
    CHECK(temps(dir, 0) == 0, "the helper left temporary files");

    /* atomic_check: what the CLI tells about -o before it generates. */
    CHECK(atomic_check(p, why, sizeof why) == 0, "an existing file: %s", why);
    snprintf(q, sizeof q, "%s/nope/x.glb", dir);
    CHECK(atomic_check(q, why, sizeof why) == ENOENT && strstr(why, "does not exist"), "missing folder: %s", why);
    snprintf(q, sizeof q, "%s/x.glb", p);
    CHECK(atomic_check(q, why, sizeof why) == ENOTDIR, "a file as the folder: %s", why);
    CHECK(atomic_check(dir, why, sizeof why) == EISDIR && strstr(why, "folder"), "a folder as the file: %s", why);
    unlink(p);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    char dir[4096], path[4400], link[4400], direct[4400];
    snprintf(dir, sizeof dir, "%s/atomic_write", argv[1]);
    mkdir(dir, 0755);
    temps(dir, 1);
    check_helper(dir);

    banyan_mesh *small = tube(20, 6), *big = tube(400, 32);
    CHECK(small && big, "tubes");
    if (!small || !big) return check_done("test_atomic_write");
    banyan_error err;
    snprintf(direct, sizeof direct, "%s/direct.glb", dir);
    CHECK(write_glb(direct, big, &err) == BANYAN_OK, "big: %s", err.message);
    size_t big_len = 0, old_len = 0;
    char *big_bytes = test_read_file(direct, &big_len);
    CHECK(big_bytes && big_len > 4 * LIMIT, "the big file (%zu bytes) is far past the limit", big_len);
    snprintf(path, sizeof path, "%s/old.glb", dir);
    CHECK(write_glb(path, small, &err) == BANYAN_OK, "small: %s", err.message);
    char *old = test_read_file(path, &old_len);
    CHECK(old && old_len < LIMIT, "the old file (%zu bytes) fits the limit", old_len);
    if (!old || !big_bytes) return check_done("test_atomic_write");

    /* A full disk: the write fails, the old file is untouched. */
    int st = child_write(path, big, 1, -1);
    CHECK(WIFEXITED(st) && WEXITSTATUS(st) == BANYAN_E_IO, "full disk: wait status %#x, expected exit %d", st,
          BANYAN_E_IO);
    CHECK(same_bytes(path, old, old_len), "full disk: the old .glb changed");
    CHECK(temps(dir, 0) == 0, "full disk: a temporary file was left");

    /* Killed mid-write: the old file is untouched; the temporary file may
     * stay (nothing runs after SIGXFSZ), named after the target. */
    st = child_write(path, big, 0, -1);
    CHECK(WIFSIGNALED(st) && WTERMSIG(st) == SIGXFSZ, "killed: wait status %#x", st);
    CHECK(same_bytes(path, old, old_len), "killed: the old .glb is cut or gone");
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));)
        if (e->d_name[0] == '.' && strstr(e->d_name, ".tmp"))
            CHECK(!strncmp(e->d_name, ".old.glb.", 9) && strlen(e->d_name) == 9 + 6 + 4,
                  "killed: temporary file '%s' is not .old.glb.XXXXXX.tmp", e->d_name);
    if (d) closedir(d);
    temps(dir, 1);

    /* Through a symlink: the link stays, its target is replaced whole;
     * a failed write keeps both. The mode of the old file is kept. */
    snprintf(link, sizeof link, "%s/link.glb", dir);
    unlink(link);
    CHECK(symlink("old.glb", link) == 0, "symlink: %s", strerror(errno));
    st = child_write(link, big, 1, -1);
    CHECK(WIFEXITED(st) && WEXITSTATUS(st) == BANYAN_E_IO, "full disk via link: wait status %#x", st);
    CHECK(is_link_to(link, "old.glb"), "full disk via link: the link is gone or changed");
    CHECK(same_bytes(path, old, old_len), "full disk via link: the target changed");
    CHECK(temps(dir, 0) == 0, "full disk via link: a temporary file was left");
    chmod(path, 0640);
    CHECK(write_glb(link, big, &err) == BANYAN_OK, "write via link: %s", err.message);
    CHECK(is_link_to(link, "old.glb"), "write via link: the link is gone or changed");
    CHECK(same_bytes(path, big_bytes, big_len), "write via link: the target is not the whole new file");
    struct stat sb;
    CHECK(stat(path, &sb) == 0 && (sb.st_mode & 07777) == 0640, "write via link: mode %o, expected 640",
          (unsigned)(sb.st_mode & 07777));
    CHECK(temps(dir, 0) == 0, "write via link: a temporary file was left");

    /* opt->sync = 1 (the CLI's --fsync): synced before the rename, the
     * same bytes; off by default. Over an old file and to a new one. */
    banyan_gltf_options so;
    banyan_gltf_options_init(&so);
    CHECK(so.sync == 0, "opt->sync is %d by default, expected 0", so.sync);
    so.sync = 1;
    const banyan_mesh *bigs[1] = {big};
    char synced[4400];
    snprintf(synced, sizeof synced, "%s/synced.glb", dir);
    unlink(synced);
    for (int k = 0; k < 2; k++)
        CHECK(banyan_gltf_write_ex(synced, bigs, NULL, 1, &so, &err) == BANYAN_OK &&
                  same_bytes(synced, big_bytes, big_len),
              "synced write %d: %s", k, err.message);
    CHECK(temps(dir, 0) == 0, "synced write: a temporary file was left");

    /* An unwritable folder (as nobody when the test runs as root): the
     * write fails even though the old file itself is writable, as there
     * is no room for the temporary file; the old file is untouched. */
    char ro[] = "/tmp/banyan_atomic_XXXXXX", in_ro[64];
    if (mkdtemp(ro)) {
        snprintf(in_ro, sizeof in_ro, "%s/plant.glb", ro);
        CHECK(write_glb(in_ro, small, &err) == BANYAN_OK, "in %s: %s", ro, err.message);
        chmod(in_ro, 0666);
        chmod(ro, 0555);
        st = child_write(in_ro, big, 1, geteuid() == 0 ? 65534 : -1);
        CHECK(WIFEXITED(st) && WEXITSTATUS(st) == BANYAN_E_IO, "unwritable folder: wait status %#x", st);
        CHECK(same_bytes(in_ro, old, old_len), "unwritable folder: the old .glb changed");
        CHECK(temps(ro, 0) == 0, "unwritable folder: a temporary file was left");
        chmod(ro, 0755);
        unlink(in_ro);
        rmdir(ro);
    }

    /* One file for the validator, written over an older one. */
    snprintf(path, sizeof path, "%s/test_atomic_write.glb", argv[1]);
    CHECK(write_glb(path, small, &err) == BANYAN_OK && write_glb(path, big, &err) == BANYAN_OK &&
              same_bytes(path, big_bytes, big_len),
          "rewrite: %s", err.message);
    free(old);
    free(big_bytes);
    banyan_mesh_free(small);
    banyan_mesh_free(big);
    return check_done("test_atomic_write");
}

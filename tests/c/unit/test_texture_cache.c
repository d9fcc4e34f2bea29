/* test_texture_cache: the texture cache (textures/tex_cache.c) in a folder
 * of its own under the test output, never the user's cache.
 *   - tex_cache_dir: the option's folder, BANYAN_TEXTURE_CACHE (off or a
 *     folder), XDG_CACHE_HOME, HOME, in that order; off wins;
 *   - cold and warm calls give the bytes drawing and encoding give, and a
 *     warm call reads the file (a file with other valid PNGs is served);
 *   - a cut, corrupt, foreign (other key or build) or odd file is passed
 *     over and rewritten whole;
 *   - four threads filling the same empty entry at once all get the right
 *     bytes and leave a whole file;
 *   - past the size bound the least recently used files go, with
 *     leftover temporary files over an hour old;
 *   - a .glb written with the cache off, cold and warm is the same bytes. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include "banyan.h"
#include "check.h"
#include "base/atomic_file.h"
#include "test_files.h"
#include "textures/tex_budget.h"
#include "textures/tex_cache.h"

static char g_cache[1100];

typedef struct pngs {
    uint8_t *b, *n;
    size_t bl, nl;
} pngs;

static void pngs_free(pngs *p) {
    banyan_png_free(p->b);
    banyan_png_free(p->n);
    memset(p, 0, sizeof *p);
}

static int pngs_same(const pngs *a, const pngs *b) {
    return a->b && b->b && a->bl == b->bl && a->nl == b->nl && !memcmp(a->b, b->b, a->bl) && !memcmp(a->n, b->n, a->nl);
}

static banyan_texture_params params(int kind, int size, uint64_t seed) {
    banyan_texture_params p;
    banyan_texture_params_init(&p);
    p.kind = kind;
    p.size = size;
    p.seed = seed;
    return p;
}

static pngs get(const banyan_texture_params *p, const char *cache) {
    pngs r = {0};
    banyan_error e;
    CHECK(tex_cached_pngs(p, cache, NULL, 0.0, &r.b, &r.bl, &r.n, &r.nl, &e) == BANYAN_OK, "tex_cached_pngs: %s",
          e.message);
    return r;
}

/* The one .btc file of the folder's entries whose name starts with prefix. */
static int entry_path(const char *prefix, char *out, size_t cap) {
    DIR *d = opendir(g_cache);
    int found = 0;
    struct dirent *de;
    while (d && (de = readdir(d)) != NULL) {
        size_t n = strlen(de->d_name);
        if (!strncmp(de->d_name, prefix, strlen(prefix)) && n > 4 && !strcmp(de->d_name + n - 4, ".btc")) {
            snprintf(out, cap, "%s/%s", g_cache, de->d_name);
            found++;
        }
    }
    if (d) closedir(d);
    return found == 1;
}

static long file_size(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static void test_dir(void) {
    char out[4096];
    unsetenv("BANYAN_TEXTURE_CACHE");
    setenv("XDG_CACHE_HOME", "/x/cache", 1);
    setenv("HOME", "/h", 1);
    CHECK(tex_cache_dir(1, "/opt/dir", out, sizeof out) && !strcmp(out, "/opt/dir"), "option folder: %s", out);
    CHECK(tex_cache_dir(1, NULL, out, sizeof out) && !strcmp(out, "/x/cache/banyan/textures"), "XDG: %s", out);
    setenv("XDG_CACHE_HOME", "relative", 1);
    CHECK(tex_cache_dir(1, "", out, sizeof out) && !strcmp(out, "/h/.cache/banyan/textures"), "HOME: %s", out);
    unsetenv("XDG_CACHE_HOME");
    CHECK(tex_cache_dir(1, NULL, out, sizeof out) && !strcmp(out, "/h/.cache/banyan/textures"), "HOME: %s", out);
    unsetenv("HOME");
    CHECK(!tex_cache_dir(1, NULL, out, sizeof out), "no HOME, no XDG: no cache");
    setenv("BANYAN_TEXTURE_CACHE", "/env/dir", 1);
    CHECK(tex_cache_dir(1, NULL, out, sizeof out) && !strcmp(out, "/env/dir"), "environment folder: %s", out);
    CHECK(tex_cache_dir(1, "/opt/dir", out, sizeof out) && !strcmp(out, "/opt/dir"), "option over environment");
    CHECK(!tex_cache_dir(0, "/opt/dir", out, sizeof out), "option off");
    const char *offs[] = {"off", "0", "no", "false"};
    for (int i = 0; i < 4; i++) {
        setenv("BANYAN_TEXTURE_CACHE", offs[i], 1);
        CHECK(!tex_cache_dir(1, "/opt/dir", out, sizeof out), "BANYAN_TEXTURE_CACHE=%s turns it off", offs[i]);
    }
    char tiny[8];
    CHECK(!tex_cache_dir(1, "/a/folder/too/long", tiny, sizeof tiny), "a folder over cap: no cache");
    setenv("BANYAN_TEXTURE_CACHE", g_cache, 1);
}

static void test_hits_and_damage(void) {
    const banyan_texture_params p = params(BANYAN_TEX_KEYAKI_BARK, 128, 7);
    pngs ref = get(&p, NULL), cold = get(&p, g_cache);
    CHECK(pngs_same(&ref, &cold), "cold: the drawn bytes");
    char path[4200];
    CHECK(entry_path("3-0-128-7-", path, sizeof path), "one cache file for the key");
    const long whole = file_size(path);
    CHECK(whole == 64 + (long)(ref.bl + ref.nl), "file of %ld bytes, head and PNGs %zu", whole, 64 + ref.bl + ref.nl);
    pngs warm = get(&p, g_cache);
    CHECK(pngs_same(&ref, &warm), "warm: the drawn bytes");
    pngs_free(&warm);

    /* A warm call reads the file: another key's valid file renamed to this
     * key's name is refused (its head names its key), but this key's file
     * from another seed's PNGs with a fixed-up head is served. */
    const banyan_texture_params q = params(BANYAN_TEX_KEYAKI_BARK, 128, 8);
    pngs other = get(&q, g_cache);
    char qpath[4200];
    CHECK(entry_path("3-0-128-8-", qpath, sizeof qpath), "second key's file");
    size_t qlen = 0, plen = 0;
    char *qbytes = test_read_file(qpath, &qlen), *pbytes = test_read_file(path, &plen);
    CHECK(qbytes && pbytes, "read the files");
    if (qbytes && pbytes) {
        CHECK(atomic_write(path, qbytes, qlen) == 0, "plant");
        pngs served = get(&p, g_cache);
        CHECK(pngs_same(&served, &ref), "another key's file under this name is not served");
        pngs_free(&served);
        CHECK(file_size(path) == whole, "and is rewritten whole");
        /* this key's head over the other seed's PNGs (CRC recomputed by the
         * writer's own code path: tex_cached_pngs stores what it is given) */
        char *fake = malloc(qlen);
        memcpy(fake, pbytes, 64);
        memcpy(fake + 64, qbytes + 64, qlen - 64);
        /* lengths and CRC from the other file: same size fields at 40 .. 63 */
        memcpy(fake + 40, qbytes + 40, 16);
        memcpy(fake + 60, qbytes + 60, 4);
        /* the head's own CRC (at 56) now disagrees: refused */
        CHECK(atomic_write(path, fake, qlen) == 0, "plant");
        served = get(&p, g_cache);
        CHECK(pngs_same(&served, &ref), "a head whose CRC disagrees is not served");
        pngs_free(&served);
        free(fake);
    }
    free(qbytes);

    /* Cut at every few bytes of the head and through the PNGs; a flipped
     * byte in the head and in each PNG; empty; trailing bytes; a folder. */
    if (pbytes) {
        const size_t cuts[] = {0, 1, 8, 40, 63, 64, 65, plen / 2, plen - 1};
        for (size_t i = 0; i < sizeof cuts / sizeof *cuts; i++) {
            CHECK(atomic_write(path, pbytes, cuts[i]) == 0, "plant cut");
            pngs r = get(&p, g_cache);
            CHECK(pngs_same(&r, &ref), "cut at %zu: the drawn bytes", cuts[i]);
            CHECK(file_size(path) == whole, "cut at %zu: rewritten whole", cuts[i]);
            pngs_free(&r);
        }
        const size_t flips[] = {3, 12, 24, 33, 45, 58, 61, 64 + 30, 64 + ref.bl + 30, plen - 1};
        for (size_t i = 0; i < sizeof flips / sizeof *flips; i++) {
            pbytes[flips[i]] ^= 0x20;
            CHECK(atomic_write(path, pbytes, plen) == 0, "plant flip");
            pbytes[flips[i]] ^= 0x20;
            pngs r = get(&p, g_cache);
            CHECK(pngs_same(&r, &ref), "byte %zu flipped: the drawn bytes", flips[i]);
            pngs_free(&r);
            size_t len = 0;
            char *now = test_read_file(path, &len);
            CHECK(now && len == plen && !memcmp(now, pbytes, plen), "byte %zu flipped: rewritten", flips[i]);
            free(now);
        }
        char *longer = malloc(plen + 5);
        memcpy(longer, pbytes, plen);
        memset(longer + plen, 0, 5);
        CHECK(atomic_write(path, longer, plen + 5) == 0, "plant long");
        pngs r = get(&p, g_cache);
        CHECK(pngs_same(&r, &ref) && file_size(path) == whole, "trailing bytes: refused and rewritten");
        pngs_free(&r);
        free(longer);
        unlink(path);
        CHECK(mkdir(path, 0700) == 0, "a folder where the file goes");
        r = get(&p, g_cache);
        CHECK(pngs_same(&r, &ref), "a folder in the way: the drawn bytes");
        pngs_free(&r);
        rmdir(path);
    }
    free(pbytes);
    /* An unwritable cache folder: the drawn bytes, no failure. */
    pngs r = get(&p, "/proc/banyan-no-such-cache");
    CHECK(pngs_same(&r, &ref), "unwritable cache folder");
    pngs_free(&r);
    pngs_free(&ref);
    pngs_free(&cold);
    pngs_free(&other);
}

typedef struct racer {
    banyan_texture_params p;
    pngs got;
} racer;

static void *race(void *arg) {
    racer *r = arg;
    r->got = get(&r->p, g_cache);
    return NULL;
}

static void test_race(void) {
    const banyan_texture_params p = params(BANYAN_TEX_IVY_LEAF, 256, 3);
    pngs ref = get(&p, NULL);
    racer r[4];
    pthread_t t[4];
    for (int i = 0; i < 4; i++) {
        r[i].p = p;
        memset(&r[i].got, 0, sizeof r[i].got);
        CHECK(pthread_create(&t[i], NULL, race, &r[i]) == 0, "thread");
    }
    for (int i = 0; i < 4; i++) pthread_join(t[i], NULL);
    for (int i = 0; i < 4; i++) {
        CHECK(pngs_same(&r[i].got, &ref), "racer %d: the drawn bytes", i);
        pngs_free(&r[i].got);
    }
    char path[4200];
    CHECK(entry_path("2-0-256-3-", path, sizeof path) && file_size(path) == (long)(64 + ref.bl + ref.nl),
          "one whole file after the race");
    pngs warm = get(&p, g_cache);
    CHECK(pngs_same(&warm, &ref), "warm after the race");
    pngs_free(&warm);
    pngs_free(&ref);
}

static void set_age(const char *path, long seconds_ago) {
    struct timeval tv[2];
    gettimeofday(&tv[0], NULL);
    tv[0].tv_sec -= seconds_ago;
    tv[1] = tv[0];
    utimes(path, tv);
}

/* Sparse files of 200 MB stand for big entries (no disk used). */
static void test_bound(void) {
    char a[1200], b[1200], c[1200], t_old[1200], t_new[1200];
    snprintf(a, sizeof a, "%s/1-0-8192-1-aaaaaaaaaaaaaaaa.btc", g_cache);
    snprintf(b, sizeof b, "%s/1-0-8192-2-aaaaaaaaaaaaaaaa.btc", g_cache);
    snprintf(c, sizeof c, "%s/1-0-8192-3-aaaaaaaaaaaaaaaa.btc", g_cache);
    snprintf(t_old, sizeof t_old, "%s/.1-0-64-1-aaaaaaaaaaaaaaaa.btc.abcdef.tmp", g_cache);
    snprintf(t_new, sizeof t_new, "%s/.1-0-64-2-aaaaaaaaaaaaaaaa.btc.abcdef.tmp", g_cache);
    const char *big[3] = {a, b, c};
    for (int i = 0; i < 3; i++) {
        int fd = open(big[i], O_WRONLY | O_CREAT | O_TRUNC, 0600);
        CHECK(fd >= 0 && ftruncate(fd, 200 << 20) == 0, "sparse file");
        if (fd >= 0) close(fd);
        set_age(big[i], 300 - 100 * i); /* a oldest */
    }
    for (int i = 0; i < 2; i++) {
        FILE *f = fopen(i ? t_new : t_old, "wb");
        if (f) fclose(f);
    }
    set_age(t_old, 7200);
    const banyan_texture_params p = params(BANYAN_TEX_FIG_BARK, 64, 5);
    pngs r = get(&p, g_cache); /* a miss: written, then the folder trimmed */
    pngs_free(&r);
    char path[4200];
    CHECK(entry_path("4-0-64-5-", path, sizeof path), "the new file stays");
    CHECK(file_size(a) < 0, "the least recently used file went");
    CHECK(file_size(b) > 0 && file_size(c) > 0, "the others stay (600 MB less 200 under 512 MB)");
    CHECK(file_size(t_old) < 0, "a temporary file over an hour old went");
    CHECK(file_size(t_new) == 0, "a fresh temporary file stays (another run's)");
    unlink(b);
    unlink(c);
    unlink(t_new);
}

/* The .glb: the same bytes with the cache off, cold and warm. */
static void test_glb(const char *dir) {
    banyan_keyaki_params kp;
    banyan_keyaki_params_init(&kp);
    kp.levels = 7;
    banyan_mesh *m = NULL;
    banyan_error e;
    CHECK(banyan_keyaki_generate(&kp, &m, NULL, NULL, &e) == BANYAN_OK, "keyaki: %s", e.message);
    if (!m) return;
    char gcache[1200];
    snprintf(gcache, sizeof gcache, "%s/glb_cache", g_cache);
    const banyan_mesh *one[1] = {m};
    const char *names[3] = {"cache_off.glb", "cache_cold.glb", "cache_warm.glb"};
    char *bytes[3] = {0};
    size_t len[3] = {0};
    for (int k = 0; k < 3; k++) {
        banyan_gltf_options o;
        banyan_gltf_options_init(&o);
        o.texture_size = 256;
        o.texture_cache = k > 0;
        o.texture_cache_dir = gcache;
        const char *path = test_join(dir, names[k]);
        CHECK(banyan_gltf_write_ex(path, one, NULL, 1, &o, &e) == BANYAN_OK, "%s: %s", names[k], e.message);
        bytes[k] = test_read_file(path, &len[k]);
        if (k == 1) {
            DIR *d = opendir(gcache);
            int files = 0;
            struct dirent *de;
            while (d && (de = readdir(d)) != NULL) files += de->d_name[0] != '.';
            if (d) closedir(d);
            CHECK(files == 2, "cold: %d cache files for the leaf and bark textures", files);
        }
    }
    CHECK(bytes[0] && len[0] > 1000, "written");
    for (int k = 1; k < 3; k++)
        CHECK(bytes[k] && len[k] == len[0] && !memcmp(bytes[k], bytes[0], len[0]), "%s: not the uncached bytes",
              names[k]);
    for (int k = 0; k < 3; k++) free(bytes[k]);
    /* texture_cache must be 0 or 1 */
    banyan_gltf_options o;
    banyan_gltf_options_init(&o);
    o.texture_cache = 2;
    CHECK(banyan_gltf_write_ex(test_join(dir, "bad.glb"), one, NULL, 1, &o, &e) == BANYAN_E_RANGE &&
              strstr(e.message, "texture_cache"),
          "texture_cache = 2 refused: %s", e.message);
    banyan_mesh_free(m);
}

static void rm_tree(const char *dir) {
    DIR *d = opendir(dir);
    struct dirent *de;
    char p[1400];
    while (d && (de = readdir(d)) != NULL) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
        struct stat st;
        if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode)) rm_tree(p);
        else unlink(p);
    }
    if (d) closedir(d);
    rmdir(dir);
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : ".";
    snprintf(g_cache, sizeof g_cache, "%s/texture_cache_%ld", dir, (long)getpid());
    rm_tree(g_cache);
    test_dir(); /* leaves BANYAN_TEXTURE_CACHE = g_cache */
    test_hits_and_damage();
    test_race();
    test_bound();
    test_glb(dir);
    rm_tree(g_cache);
    return check_done("test_texture_cache");
}

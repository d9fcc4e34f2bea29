/* tex_cache.c - the on-disk cache of the library textures' PNGs
 * (tex_cache.h).
 *
 * A file "<kind>-<season>-<size>-<seed>-<code hash>.btc" in the cache
 * folder: a 64-byte head (magic, format, the key again, the two PNGs'
 * lengths, the CRC-32 of the head before it and of both PNGs), then the
 * base colour's PNG and the normal map's. The code hash (code_hash.cmake)
 * changes with the texture code, the library's version, the compiler and
 * its flags, so a build never reads images another build drew. A file is
 * used only when its size, head and CRC all agree; anything else is a
 * miss, and the fresh images are stored over it. Files are written whole
 * through base/atomic_file.h (a private temporary file renamed over the
 * name), so runs that share the folder read either a whole old file or a
 * whole new one. A hit touches the file's time; past TEX_CACHE_MAX_BYTES
 * the files used longest ago are removed (with temporary files a killed
 * run left over an hour ago). */
#include "textures/tex_cache.h"

#include <errno.h>
#include <libdeflate.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/platform.h"
#include "tex_code_hash.h"
#include "textures/tex_budget.h"

#define HEAD 64
#define FORMAT 1u
static const char kMagic[8] = {'b', 'a', 'n', 'y', 'a', 'n', 'T', 'C'};

static int is_off(const char *v) {
    return !strcmp(v, "off") || !strcmp(v, "0") || !strcmp(v, "no") || !strcmp(v, "false");
}

int tex_cache_dir(int32_t enabled, const char *dir, char *out, size_t cap) {
    if (!enabled || cap == 0) return 0;
    const char *env = getenv("BANYAN_TEXTURE_CACHE");
    if (env && is_off(env)) return 0;
    int n;
    if (dir && dir[0]) n = snprintf(out, cap, "%s", dir);
    else if (env && env[0]) n = snprintf(out, cap, "%s", env);
    else return plat_user_cache(out, cap, "banyan/textures");
    return n > 0 && (size_t)n < cap;
}

static void put32(uint8_t *p, uint32_t v) { memcpy(p, &v, 4); } /* the host's order: the hash differs elsewhere */
static void put64(uint8_t *p, uint64_t v) { memcpy(p, &v, 8); }
static uint32_t get32(const uint8_t *p) {
    uint32_t v;
    memcpy(&v, p, 4);
    return v;
}
static uint64_t get64(const uint8_t *p) {
    uint64_t v;
    memcpy(&v, p, 8);
    return v;
}

/* The head for a key and two lengths, with the CRC of the head so far and
 * of the PNGs at byte 56 and 60. */
static void make_head(uint8_t h[HEAD], const banyan_texture_params *p, uint64_t bl, uint64_t nl, uint32_t crc) {
    memset(h, 0, HEAD);
    memcpy(h, kMagic, 8);
    put32(h + 8, FORMAT);
    put32(h + 12, (uint32_t)p->kind);
    put32(h + 16, (uint32_t)p->season);
    put32(h + 20, (uint32_t)p->size);
    put64(h + 24, p->seed);
    put64(h + 32, TEX_CODE_HASH);
    put64(h + 40, bl);
    put64(h + 48, nl);
    put32(h + 56, libdeflate_crc32(0, h, 56));
    put32(h + 60, crc);
}

static int path_of(char *out, size_t cap, const char *dir, const banyan_texture_params *p) {
    int n = snprintf(out, cap, "%s/%d-%d-%d-%llu-%016llx.btc", dir, (int)p->kind, (int)p->season, (int)p->size,
                     (unsigned long long)p->seed, (unsigned long long)TEX_CODE_HASH);
    return n > 0 && (size_t)n < cap;
}

/* The most bytes one PNG of the size can take (4 channels stored, the
 * chunks): a head claiming more is corrupt. */
static uint64_t png_most(int32_t size) {
    const uint64_t raw = (uint64_t)size * (4 * (uint64_t)size + 1);
    return raw + raw / 1000 + 4096;
}

/* 1 and the two PNGs when the file is whole and is this key's. */
static int cache_read(const char *path, const banyan_texture_params *p, uint8_t **base, size_t *bl, uint8_t **normal,
                      size_t *nl) {
    plat_info st;
    if (plat_stat(path, &st, 1) != 0 || st.kind != PLAT_FILE || st.size < HEAD) return 0;
    FILE *f = plat_fopen(path, "rb");
    if (!f) return 0;
    int ok = 0;
    uint8_t h[HEAD], want[HEAD];
    uint8_t *b = NULL, *n = NULL;
    if (fread(h, 1, HEAD, f) != HEAD) goto done;
    const uint64_t L0 = get64(h + 40), L1 = get64(h + 48), most = png_most(p->size);
    if (L0 == 0 || L1 == 0 || L0 > most || L1 > most || st.size != HEAD + L0 + L1) goto done;
    make_head(want, p, L0, L1, get32(h + 60));
    if (memcmp(h, want, HEAD) != 0) goto done; /* another key, build or format, or a damaged head */
    b = malloc(L0);
    n = malloc(L1);
    if (!b || !n) goto done;
    if (fread(b, 1, L0, f) != L0 || fread(n, 1, L1, f) != L1) goto done;
    if (libdeflate_crc32(libdeflate_crc32(0, b, L0), n, L1) != get32(h + 60)) goto done;
    plat_touch(path); /* used now: the last to go */
    *base = b, *bl = L0, *normal = n, *nl = L1;
    b = n = NULL;
    ok = 1;
done:
    free(b);
    free(n);
    fclose(f);
    return ok;
}

typedef struct entry {
    char *name;
    uint64_t size;
    int64_t used;
} entry;

static int by_use(const void *a, const void *b) {
    const entry *x = a, *y = b;
    return x->used < y->used ? -1 : x->used > y->used ? 1 : strcmp(x->name, y->name);
}

static int ends_with(const char *s, const char *tail) {
    size_t a = strlen(s), b = strlen(tail);
    return a >= b && !strcmp(s + a - b, tail);
}

/* The folder back under TEX_CACHE_MAX_BYTES, the files used longest ago
 * removed first; leftover temporary files over an hour old removed. Other
 * runs may remove the same files: a failed unlink is passed over. */
static void trim(const char *dir) {
    plat_dir *d = plat_dir_open(dir);
    if (!d) return;
    entry *e = NULL;
    size_t count = 0, cap = 0;
    unsigned long long total = 0;
    const int64_t now = (int64_t)time(NULL);
    char path[4200];
    const char *nm;
    while ((nm = plat_dir_next(d)) != NULL) {
        int temp = nm[0] == '.' && ends_with(nm, ".tmp") && strstr(nm, ".btc.");
        if (!temp && (nm[0] == '.' || !ends_with(nm, ".btc"))) continue;
        if (snprintf(path, sizeof path, "%s/%s", dir, nm) >= (int)sizeof path) continue;
        plat_info st;
        if (plat_stat(path, &st, 0) != 0 || st.kind != PLAT_FILE) continue;
        if (temp) {
            if (now - st.mtime > 3600) plat_remove(path);
            continue;
        }
        if (count == cap) {
            size_t nc = cap ? 2 * cap : 64;
            entry *ne = realloc(e, nc * sizeof *e);
            if (!ne) break;
            e = ne, cap = nc;
        }
        size_t len = strlen(nm) + 1;
        if (!(e[count].name = malloc(len))) break;
        memcpy(e[count].name, nm, len);
        e[count].size = st.size;
        e[count].used = st.mtime;
        total += (unsigned long long)st.size;
        count++;
    }
    plat_dir_close(d);
    if (total > TEX_CACHE_MAX_BYTES) {
        qsort(e, count, sizeof *e, by_use);
        for (size_t i = 0; i < count && total > TEX_CACHE_MAX_BYTES; i++) {
            if (snprintf(path, sizeof path, "%s/%s", dir, e[i].name) < (int)sizeof path) plat_remove(path);
            total -= (unsigned long long)e[i].size;
        }
    }
    for (size_t i = 0; i < count; i++) free(e[i].name);
    free(e);
}

/* dir and its parents, created where missing (0700: a user's cache). */
static int make_dirs(const char *dir) {
    char buf[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (!plat_is_sep(buf[i]) && buf[i] != '\0') continue;
        if (i == 2 && buf[1] == ':' && plat_is_absolute(dir)) continue; /* "C:" of "C:\\...": a drive */
        char c = buf[i];
        buf[i] = '\0';
        int e = plat_mkdir(buf);
        if (e != 0 && e != EEXIST) return -1;
        buf[i] = c;
    }
    plat_info st;
    return plat_stat(dir, &st, 1) == 0 && st.kind == PLAT_DIR ? 0 : -1;
}

static void cache_write(const char *dir, const char *path, const banyan_texture_params *p, const uint8_t *b, size_t bl,
                        const uint8_t *n, size_t nl) {
    if ((unsigned long long)bl + nl > TEX_CACHE_MAX_BYTES / 4 || make_dirs(dir) != 0) return;
    uint8_t h[HEAD];
    make_head(h, p, bl, nl, libdeflate_crc32(libdeflate_crc32(0, b, bl), n, nl));
    atomic_file af;
    if (atomic_open(&af, path) != 0) return;
    af.sync = 0; /* a file lost in a power cut is drawn again */
    if (fwrite(h, 1, HEAD, af.f) != HEAD || fwrite(b, 1, bl, af.f) != bl || fwrite(n, 1, nl, af.f) != nl) {
        atomic_abort(&af);
        return;
    }
    if (atomic_commit(&af) == 0) trim(dir);
}

banyan_status tex_cached_pngs(const banyan_texture_params *p, const char *cache, const prog_deadline *stop,
                              double seconds, uint8_t **base, size_t *base_len, uint8_t **normal, size_t *normal_len,
                              banyan_error *err) {
    banyan_error_clear(err);
    *base = *normal = NULL;
    *base_len = *normal_len = 0;
    char path[4200];
    const int cached = cache && path_of(path, sizeof path, cache, p);
    if (cached && cache_read(path, p, base, base_len, normal, normal_len)) return BANYAN_OK;
    banyan_image *bc = NULL, *nm = NULL;
    banyan_status s = tex_generate(p, stop, seconds, &bc, &nm, err);
    if (s == BANYAN_OK) s = tex_png(bc, stop, seconds, base, base_len, err);
    if (s == BANYAN_OK) s = tex_png(nm, stop, seconds, normal, normal_len, err);
    banyan_image_free(bc);
    banyan_image_free(nm);
    if (s != BANYAN_OK) {
        banyan_png_free(*base);
        banyan_png_free(*normal);
        *base = *normal = NULL;
        *base_len = *normal_len = 0;
        return s;
    }
    if (cached) cache_write(cache, path, p, *base, *base_len, *normal, *normal_len);
    return BANYAN_OK;
}

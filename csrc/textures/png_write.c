/* png_write.c - PNG bytes through libdeflate (png_write.h).
 *
 * Filter and level, measured on the library's 1024-pixel textures (base
 * colour and normal map each) by tests/bench/bench_png_filters.c: one
 * filter for every row spends no time choosing one; Up gives the smallest
 * files of the five (Paeth within 0.5 % of it, at more CPU time), smaller
 * than zlib with stb's per-row choice; libdeflate's level 1 is its fastest,
 * its higher levels cost far more time for a few per cent. Deflating is one call on the whole filtered image (libdeflate
 * has no streaming), so a deadline is checked while filtering and before
 * deflating. */
#include "textures/png_write.h"

#include <libdeflate.h>
#include <stdlib.h>
#include <string.h>

static void put32(uint8_t *p, uint32_t v) {
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* A chunk's length, type and CRC around the len data bytes already at
 * p + 8; returns the byte after it. */
static uint8_t *chunk(uint8_t *p, const char type[4], size_t len) {
    put32(p, (uint32_t)len);
    memcpy(p + 4, type, 4);
    put32(p + 8 + len, libdeflate_crc32(0, p + 4, len + 4));
    return p + 12 + len;
}

static inline uint8_t paeth(int a, int b, int c) {
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return (uint8_t)(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

/* One row filtered into out (its filter byte first); prev NULL on the first row. */
static void filter_row(const uint8_t *cur, const uint8_t *prev, size_t n, int bpp, int filter, uint8_t *out) {
    *out++ = (uint8_t)filter;
    size_t i = 0;
    switch (filter) {
    case 0: memcpy(out, cur, n); break;
    case 1:
        for (; i < (size_t)bpp; i++) out[i] = cur[i];
        for (; i < n; i++) out[i] = (uint8_t)(cur[i] - cur[i - bpp]);
        break;
    case 2:
        if (!prev) memcpy(out, cur, n);
        else
            for (; i < n; i++) out[i] = (uint8_t)(cur[i] - prev[i]);
        break;
    case 3:
        for (; i < (size_t)bpp; i++) out[i] = (uint8_t)(cur[i] - (prev ? prev[i] >> 1 : 0));
        for (; i < n; i++) out[i] = (uint8_t)(cur[i] - ((cur[i - bpp] + (prev ? prev[i] : 0)) >> 1));
        break;
    default: /* Paeth; on the first row it is Sub */
        if (!prev) {
            for (; i < (size_t)bpp; i++) out[i] = cur[i];
            for (; i < n; i++) out[i] = (uint8_t)(cur[i] - cur[i - bpp]);
            break;
        }
        for (; i < (size_t)bpp; i++) out[i] = (uint8_t)(cur[i] - prev[i]);
        for (; i < n; i++) out[i] = (uint8_t)(cur[i] - paeth(cur[i - bpp], prev[i], prev[i - bpp]));
        break;
    }
}

int png_write(const uint8_t *pixels, int w, int h, int channels, int filter, int level, const prog_deadline *stop,
              uint8_t **out, size_t *len) {
    static const uint8_t sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    static const uint8_t ctype[5] = {0, 0, 4, 2, 6};
    *out = NULL;
    *len = 0;
    const size_t n = (size_t)w * (size_t)channels, row = n + 1, raw = row * (size_t)h;
    uint8_t *filt = malloc(raw);
    if (!filt) return -1;
    for (int j = 0; j < h; j++) {
        if ((j & 63) == 0 && prog_deadline_passed(stop)) {
            free(filt);
            return 1;
        }
        const uint8_t *cur = pixels + (size_t)j * n;
        filter_row(cur, j ? cur - n : NULL, n, channels, filter, filt + (size_t)j * row);
    }
    if (prog_deadline_passed(stop)) {
        free(filt);
        return 1;
    }
    struct libdeflate_compressor *c = libdeflate_alloc_compressor(level);
    const size_t bound = c ? libdeflate_zlib_compress_bound(c, raw) : 0;
    /* signature, IHDR (13), IDAT (the zlib stream), IEND: 12 bytes of chunk around each */
    uint8_t *png = c ? malloc(8 + 25 + 12 + bound + 12) : NULL;
    if (!png) {
        libdeflate_free_compressor(c);
        free(filt);
        return -1;
    }
    uint8_t *p = png;
    memcpy(p, sig, 8);
    p += 8;
    put32(p + 8, (uint32_t)w);
    put32(p + 12, (uint32_t)h);
    p[16] = 8; /* bits a channel */
    p[17] = ctype[channels];
    p[18] = p[19] = p[20] = 0; /* deflate, adaptive filters, no interlace */
    p = chunk(p, "IHDR", 13);
    const size_t z = libdeflate_zlib_compress(c, filt, raw, p + 8, bound);
    libdeflate_free_compressor(c);
    free(filt);
    if (z == 0) { /* the bound was too small: cannot happen */
        free(png);
        return -1;
    }
    p = chunk(p, "IDAT", z);
    p = chunk(p, "IEND", 0);
    *out = png;
    *len = (size_t)(p - png);
    return 0;
}

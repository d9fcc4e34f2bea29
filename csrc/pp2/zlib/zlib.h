/* zlib.h - the three zlib calls tinyexr makes (compressBound, compress,
 * uncompress), over libdeflate's zlib streams, for csrc/pp2/exr_half.cpp
 * only: tinyexr includes <zlib.h> and asks for "a zlib-compatible API"
 * there, and libdeflate is the deflate banyan already links (the PNG
 * encoder's), on Linux and in the Windows build alike. The streams are
 * standard zlib streams; the same bytes in give the same bytes out on
 * every run and CPU. */
#ifndef BANYAN_PP2_ZLIB_H
#define BANYAN_PP2_ZLIB_H

#include <libdeflate.h>
#include <stddef.h>

typedef unsigned char Bytef;
typedef unsigned long uLong;
typedef uLong uLongf;

#define Z_OK 0
#define Z_DATA_ERROR (-3)
#define Z_MEM_ERROR (-4)
#define Z_BUF_ERROR (-5)

/* The deflate level of the EXR blocks. */
#define BANYAN_EXR_ZLIB_LEVEL 6

static inline uLong compressBound(uLong n) {
    struct libdeflate_compressor *c = libdeflate_alloc_compressor(BANYAN_EXR_ZLIB_LEVEL);
    if (!c) return n + (n >> 8) + 64; /* compress() then fails and tinyexr stores the block raw */
    size_t b = libdeflate_zlib_compress_bound(c, n);
    libdeflate_free_compressor(c);
    return static_cast<uLong>(b < n ? n : b);
}

/* On failure *destLen is sourceLen: tinyexr then stores the block raw. */
static inline int compress(Bytef *dest, uLongf *destLen, const Bytef *source, uLong sourceLen) {
    struct libdeflate_compressor *c = libdeflate_alloc_compressor(BANYAN_EXR_ZLIB_LEVEL);
    size_t n = c ? libdeflate_zlib_compress(c, source, sourceLen, dest, *destLen) : 0;
    if (c) libdeflate_free_compressor(c);
    if (n == 0) {
        *destLen = sourceLen;
        return c ? Z_BUF_ERROR : Z_MEM_ERROR;
    }
    *destLen = static_cast<uLongf>(n);
    return Z_OK;
}

static inline int uncompress(Bytef *dest, uLongf *destLen, const Bytef *source, uLong sourceLen) {
    struct libdeflate_decompressor *d = libdeflate_alloc_decompressor();
    if (!d) return Z_MEM_ERROR;
    size_t got = 0;
    enum libdeflate_result r = libdeflate_zlib_decompress(d, source, sourceLen, dest, *destLen, &got);
    libdeflate_free_decompressor(d);
    if (r != LIBDEFLATE_SUCCESS) return r == LIBDEFLATE_INSUFFICIENT_SPACE ? Z_BUF_ERROR : Z_DATA_ERROR;
    *destLen = static_cast<uLongf>(got);
    return Z_OK;
}

#endif

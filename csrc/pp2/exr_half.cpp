/* exr_half.cpp - the extern "C" shim over tinyexr (exr_half.h). tinyexr
 * is header-only: its implementation is compiled here, with its zlib calls
 * going to libdeflate (csrc/pp2/zlib/zlib.h), so no tinyexr library is
 * linked or shipped. */
#include "pp2/exr_half.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#define TINYEXR_IMPLEMENTATION
#define TINYEXR_USE_MINIZ 0
#define TINYEXR_USE_THREAD 0
#define TINYEXR_USE_OPENMP 0
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wclass-memaccess"
#endif
#include <zlib.h> /* csrc/pp2/zlib/zlib.h: on this file's include path only */
#include <tinyexr.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace {

void say(char *why, size_t cap, const char *what, const char *tinyexr_err) {
    if (why && cap) std::snprintf(why, cap, "%s%s%s", what, tinyexr_err ? ": " : "", tinyexr_err ? tinyexr_err : "");
    if (tinyexr_err) FreeEXRErrorMessage(tinyexr_err);
}

/* Where channel c (R, G, B, A = 0 .. 3) sits in rgba, by the channel's name. */
int rgba_slot(const char *name) {
    if (!std::strcmp(name, "R")) return 0;
    if (!std::strcmp(name, "G")) return 1;
    if (!std::strcmp(name, "B")) return 2;
    if (!std::strcmp(name, "A")) return 3;
    return -1;
}

} // namespace

extern "C" int exr_half_encode(const uint16_t *rgba, uint32_t w, uint32_t h, uint8_t **out, size_t *len, char *why,
                               size_t cap) {
    *out = nullptr;
    *len = 0;
    const size_t n = static_cast<size_t>(w) * h;
    /* OpenEXR keeps channels sorted by name: A, B, G, R. */
    static const char kNames[4] = {'A', 'B', 'G', 'R'};
    static const int kSlot[4] = {3, 2, 1, 0};
    uint16_t *planes = static_cast<uint16_t *>(std::malloc(4 * n * sizeof(uint16_t)));
    if (!planes) {
        say(why, cap, "out of memory", nullptr);
        return -1;
    }
    unsigned char *ptr[4];
    for (int c = 0; c < 4; ++c) {
        uint16_t *p = planes + c * n;
        for (size_t i = 0; i < n; ++i) p[i] = rgba[4 * i + kSlot[c]];
        ptr[c] = reinterpret_cast<unsigned char *>(p);
    }
    EXRHeader header;
    InitEXRHeader(&header);
    EXRImage image;
    InitEXRImage(&image);
    EXRChannelInfo channels[4];
    std::memset(channels, 0, sizeof channels);
    int types[4], requested[4];
    for (int c = 0; c < 4; ++c) {
        channels[c].name[0] = kNames[c];
        types[c] = TINYEXR_PIXELTYPE_HALF;
        requested[c] = TINYEXR_PIXELTYPE_HALF;
    }
    image.num_channels = 4;
    image.images = ptr;
    image.width = static_cast<int>(w);
    image.height = static_cast<int>(h);
    header.num_channels = 4;
    header.channels = channels;
    header.pixel_types = types;
    header.requested_pixel_types = requested;
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    unsigned char *mem = nullptr;
    const char *err = nullptr;
    size_t got = SaveEXRImageToMemory(&image, &header, &mem, &err);
    std::free(planes);
    if (got == 0 || !mem) {
        say(why, cap, "tinyexr could not encode the image", err);
        std::free(mem);
        return -1;
    }
    if (err) FreeEXRErrorMessage(err);
    *out = mem;
    *len = got;
    return 0;
}

extern "C" int exr_half_decode(const uint8_t *bytes, size_t len, uint32_t *w, uint32_t *h, uint16_t **rgba, char *why,
                               size_t cap) {
    *rgba = nullptr;
    *w = *h = 0;
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, bytes, len) != TINYEXR_SUCCESS) {
        say(why, cap, "not an OpenEXR file", nullptr);
        return -1;
    }
    if (version.multipart || version.tiled) {
        say(why, cap, "a multipart or tiled EXR", nullptr);
        return -1;
    }
    EXRHeader header;
    InitEXRHeader(&header);
    const char *err = nullptr;
    if (ParseEXRHeaderFromMemory(&header, &version, bytes, len, &err) != TINYEXR_SUCCESS) {
        say(why, cap, "bad EXR header", err);
        return -1;
    }
    int slot[4] = {-1, -1, -1, -1};
    for (int c = 0; c < header.num_channels; ++c) {
        int s = rgba_slot(header.channels[c].name);
        if (s >= 0 && header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) slot[s] = c;
        header.requested_pixel_types[c] = header.pixel_types[c];
    }
    if (slot[0] < 0 || slot[1] < 0 || slot[2] < 0 || slot[3] < 0) {
        FreeEXRHeader(&header);
        say(why, cap, "the EXR lacks a half R, G, B or A channel", nullptr);
        return -1;
    }
    EXRImage image;
    InitEXRImage(&image);
    if (LoadEXRImageFromMemory(&image, &header, bytes, len, &err) != TINYEXR_SUCCESS) {
        FreeEXRHeader(&header);
        say(why, cap, "bad EXR pixels", err);
        return -1;
    }
    const size_t n = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    uint16_t *o = static_cast<uint16_t *>(std::malloc(4 * n * sizeof(uint16_t) + 1));
    if (o) {
        for (int s = 0; s < 4; ++s) {
            const uint16_t *p = reinterpret_cast<const uint16_t *>(image.images[slot[s]]);
            for (size_t i = 0; i < n; ++i) o[4 * i + s] = p[i];
        }
        *w = static_cast<uint32_t>(image.width);
        *h = static_cast<uint32_t>(image.height);
    }
    FreeEXRImage(&image);
    FreeEXRHeader(&header);
    if (!o) {
        say(why, cap, "out of memory", nullptr);
        return -1;
    }
    *rgba = o;
    return 0;
}

extern "C" uint16_t exr_half_from_float(float f) {
    uint32_t x;
    std::memcpy(&x, &f, 4);
    const uint32_t sign = (x >> 16) & 0x8000u;
    const uint32_t ax = x & 0x7fffffffu;
    if (ax >= 0x7f800000u) return static_cast<uint16_t>(sign | 0x7c00u | (ax > 0x7f800000u ? 0x200u : 0u));
    if (ax >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u); /* rounds past 65504 */
    if (ax < 0x38800000u) { /* a subnormal half (or zero) */
        if (ax < 0x33000000u) return static_cast<uint16_t>(sign); /* below half the smallest: zero */
        /* value = m * 2^(e - 150); a subnormal half counts 2^-24: m * 2^(e - 126) of them */
        const uint32_t e = ax >> 23, m = (ax & 0x7fffffu) | 0x800000u;
        const uint32_t sh = 126u - e; /* 14 .. 24 */
        uint32_t hm = m >> sh;
        const uint32_t rest = m & ((1u << sh) - 1u), halfway = 1u << (sh - 1u);
        if (rest > halfway || (rest == halfway && (hm & 1u))) hm++;
        return static_cast<uint16_t>(sign | hm);
    }
    uint32_t hb = ((ax >> 13) - (112u << 10)); /* rebias 127 -> 15 */
    const uint32_t rest = ax & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (hb & 1u))) hb++;
    return static_cast<uint16_t>(sign | hb);
}

extern "C" float exr_half_to_float(uint16_t h) {
    const uint32_t sign = static_cast<uint32_t>(h & 0x8000u) << 16;
    const uint32_t e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
    uint32_t x;
    if (e == 0) {
        if (m == 0) {
            x = sign;
        } else { /* subnormal: m * 2^-24, exact in float */
            float f = static_cast<float>(m) * 5.9604644775390625e-8f;
            std::memcpy(&x, &f, 4);
            x |= sign;
        }
    } else if (e == 31) {
        x = sign | 0x7f800000u | (m << 13);
    } else {
        x = sign | ((e + 112u) << 23) | (m << 13);
    }
    float f;
    std::memcpy(&f, &x, 4);
    return f;
}

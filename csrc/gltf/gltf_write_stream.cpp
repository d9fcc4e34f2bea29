/*
 * gltf_write_stream.cpp - the BIN chunk's bytes (gltf_write.h): the planned
 * segments converted on a second thread into a few small blocks while the
 * caller writes them, and the document around them split from tinygltf's.
 */
#include "gltf/gltf_write.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <mutex>
#include <system_error>

namespace gltfw {

Sink::Sink(std::FILE *f, bool base64) : f_(f), base64_(base64) {
    if (base64_) out_.resize(4 * (kBlock / 3) + 8);
}

void Sink::put(const void *data, size_t n) {
    const unsigned char *p = static_cast<const unsigned char *>(data);
    count_ += n;
    if (!base64_) {
        raw(p, n);
        return;
    }
    while (n > 0) {
        if (held_ > 0 || n < 3) { /* finish the held triple first */
            while (held_ < 3 && n > 0) {
                hold_[held_++] = *p++;
                --n;
            }
            if (held_ == 3) {
                encode(hold_, 3, &out_[0]);
                raw(reinterpret_cast<const unsigned char *>(&out_[0]), 4);
                held_ = 0;
            }
            continue;
        }
        size_t take = std::min(n - n % 3, static_cast<size_t>(kBlock / 3 * 3));
        char *o = &out_[0];
        for (size_t i = 0; i < take; i += 3, o += 4) encode(p + i, 3, o);
        raw(reinterpret_cast<const unsigned char *>(&out_[0]), static_cast<size_t>(o - &out_[0]));
        p += take;
        n -= take;
    }
}

void Sink::finish() {
    if (base64_ && held_ > 0) {
        encode(hold_, held_, &out_[0]);
        raw(reinterpret_cast<const unsigned char *>(&out_[0]), 4);
        held_ = 0;
    }
}

void Sink::raw(const unsigned char *p, size_t n) {
    if (error_ != 0 || n == 0) return;
    errno = 0;
    if (std::fwrite(p, 1, n, f_) != n) error_ = errno ? errno : EIO;
}

void Sink::encode(const unsigned char *in, int n, char *o) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    uint32_t v = static_cast<uint32_t>(in[0]) << 16 | (n > 1 ? static_cast<uint32_t>(in[1]) << 8 : 0u) |
                 (n > 2 ? static_cast<uint32_t>(in[2]) : 0u);
    o[0] = kAlphabet[v >> 18 & 63];
    o[1] = kAlphabet[v >> 12 & 63];
    o[2] = n > 1 ? kAlphabet[v >> 6 & 63] : '=';
    o[3] = n > 2 ? kAlphabet[v & 63] : '=';
}

namespace {

/* The BIN chunk's bytes on their way from the converting thread to the
 * writing one (the caller), in order: converted or small pieces gathered in
 * a few small fixed blocks (kBlockBytes each, reused), large raw arrays
 * handed over as they are in the mesh. Converting block k + 1 while block k
 * is written overlaps the CPU work with write(); the bytes do not depend on
 * the split. Without a thread (none could be started) each piece is
 * written as soon as it is ready. */
class Pipe {
  public:
    /* Small blocks, so the one just converted is still in the cache when
     * write() copies it: 4 MiB blocks made write() 2.5x slower here. */
    static constexpr int kBlocks = 8;
    static constexpr size_t kBlockBytes = size_t(512) << 10;
    static constexpr size_t kByReference = size_t(256) << 10; /* raw pieces at least this long are not copied */
    static constexpr uint64_t kWriteback = uint64_t(64) << 20; /* with sync: start the disk every this many bytes */

    Pipe(Sink &sink, OutFile &file) : sink_(sink), file_(file) {
        for (int k = 0; k < kBlocks; ++k) {
            blocks_[k].resize(kBlockBytes);
            if (k > 0) free_.push_back(k);
        }
    }

    /* Producer side. Room for at least min bytes (4-aligned) in the current block. */
    unsigned char *space(size_t min, size_t &cap) {
        if (kBlockBytes - fill_ < min || fill_ % 4 != 0) hand_block();
        cap = kBlockBytes - fill_;
        return blocks_[cur_].data() + fill_;
    }
    void used(size_t n) { fill_ += n; }
    void put(const void *data, size_t n) {
        if (n >= kByReference) {
            hand_block();
            push(Piece{data, n, -1});
            return;
        }
        const unsigned char *p = static_cast<const unsigned char *>(data);
        while (n > 0) {
            if (fill_ == kBlockBytes) hand_block();
            size_t take = std::min(n, kBlockBytes - fill_);
            std::memcpy(blocks_[cur_].data() + fill_, p, take);
            fill_ += take;
            p += take;
            n -= take;
        }
    }
    void zeros(uint64_t n) {
        while (n > 0) {
            if (fill_ == kBlockBytes) hand_block();
            size_t take = static_cast<size_t>(std::min<uint64_t>(n, kBlockBytes - fill_));
            std::memset(blocks_[cur_].data() + fill_, 0, take);
            fill_ += take;
            n -= take;
        }
    }
    /* Whether the writing side failed: the producer may stop early. */
    bool failed() {
        std::lock_guard<std::mutex> lk(mu_);
        return stop_;
    }
    /* The last block, then the end mark. */
    void finish() {
        hand_block();
        push(Piece{nullptr, 0, -2});
    }

    /* Runs produce(*this) on a new thread while the caller writes; inline
     * when no thread can be started. Rethrows the producer's exception. */
    template <class F> void run(F produce) {
        auto body = [this, &produce] {
            try {
                produce(*this);
            } catch (...) {
                std::lock_guard<std::mutex> lk(mu_);
                thrown_ = std::current_exception();
            }
            finish();
        };
        std::thread t;
        threaded_ = true; /* before the thread starts: it reads it */
        try {
            t = std::thread(body);
        } catch (const std::system_error &) {
            threaded_ = false;
        }
        if (!threaded_) {
            body();
        } else {
            for (;;) {
                Piece pc;
                {
                    std::unique_lock<std::mutex> lk(mu_);
                    cv_.wait(lk, [this] { return !queue_.empty(); });
                    pc = queue_.front();
                    queue_.pop_front();
                }
                if (pc.block == -2) break;
                write(pc);
                std::lock_guard<std::mutex> lk(mu_);
                if (pc.block >= 0) free_.push_back(pc.block);
                if (sink_.error()) stop_ = true;
                cv_.notify_all();
            }
            t.join();
        }
        if (thrown_) std::rethrow_exception(thrown_);
    }

  private:
    struct Piece {
        const void *p;
        size_t n;
        int block; /* -1: mesh memory; -2: the end */
    };

    void write(const Piece &pc) {
        sink_.put(pc.p, pc.n);
        written_ += pc.n;
        if (written_ - synced_ >= kWriteback) {
            file_.start_writeback();
            synced_ = written_;
        }
    }
    void push(const Piece &pc) {
        if (!threaded_) {
            if (pc.block != -2) write(pc);
            if (sink_.error()) stop_ = true;
            return;
        }
        std::lock_guard<std::mutex> lk(mu_);
        queue_.push_back(pc);
        cv_.notify_all();
    }
    /* The current block to the writer (when it holds anything), then a free one. */
    void hand_block() {
        if (fill_ == 0) return;
        if (!threaded_) {
            write(Piece{blocks_[cur_].data(), fill_, cur_});
            if (sink_.error()) stop_ = true;
            fill_ = 0;
            return;
        }
        std::unique_lock<std::mutex> lk(mu_);
        queue_.push_back(Piece{blocks_[cur_].data(), fill_, cur_});
        cv_.notify_all();
        cv_.wait(lk, [this] { return !free_.empty(); });
        cur_ = free_.front();
        free_.pop_front();
        fill_ = 0;
    }

    Sink &sink_;
    OutFile &file_;
    std::vector<unsigned char> blocks_[kBlocks];
    int cur_ = 0;
    size_t fill_ = 0;
    bool threaded_ = false;
    std::mutex mu_;
    std::condition_variable cv_;
    std::deque<Piece> queue_;
    std::deque<int> free_;
    bool stop_ = false;
    std::exception_ptr thrown_;
    uint64_t written_ = 0, synced_ = 0;
};

/* n normals from nv, turned to Y up ((x, y, z) -> (x, z, -y)) and
 * renormalised in double into o; a zero normal becomes +Y. Two at a time
 * in SSE2 (the same correctly rounded operations, so the same bits). */
inline void put_normals(const float *nv, uint32_t n, float *o) {
    uint32_t i = 0;
#if defined(__SSE2__)
    for (; i + 2 <= n; i += 2, nv += 6, o += 6) {
        const __m128d x = _mm_set_pd(nv[3], nv[0]), y = _mm_set_pd(nv[5], nv[2]);
        const __m128d z = _mm_xor_pd(_mm_set_pd(nv[4], nv[1]), _mm_set1_pd(-0.0)); /* -y, signed zeros too */
        const __m128d len = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)), _mm_mul_pd(z, z)));
        double l[2], qx[2], qy[2], qz[2];
        _mm_storeu_pd(l, len);
        _mm_storeu_pd(qx, _mm_div_pd(x, len));
        _mm_storeu_pd(qy, _mm_div_pd(y, len));
        _mm_storeu_pd(qz, _mm_div_pd(z, len));
        for (int k = 0; k < 2; ++k) {
            float *ok = o + 3 * k;
            if (l[k] > 0.0) {
                ok[0] = static_cast<float>(qx[k]);
                ok[1] = static_cast<float>(qy[k]);
                ok[2] = static_cast<float>(qz[k]);
            } else {
                ok[0] = 0.0f;
                ok[1] = 1.0f;
                ok[2] = 0.0f;
            }
        }
    }
#endif
    for (; i < n; ++i, nv += 3, o += 3) {
        double q[3] = {nv[0], nv[2], -static_cast<double>(nv[1])};
        double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (len > 0.0) {
            for (int k = 0; k < 3; ++k) o[k] = static_cast<float>(q[k] / len);
        } else {
            o[0] = 0.0f;
            o[1] = 1.0f;
            o[2] = 0.0f;
        }
    }
}

/* n colour components from c, clamped to [0, 1] (NaN to 0) and rounded
 * to the nearest of 0..255, into u; four at a time in SSE2 (max and min
 * take their second operand on a NaN, as the scalar compares do). */
inline void put_colors(const float *c, uint32_t n, uint8_t *u) {
    uint32_t i = 0;
#if defined(__SSE2__)
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), k255 = _mm_set1_ps(255.0f),
                 half = _mm_set1_ps(0.5f);
    for (; i + 4 <= n; i += 4) {
        __m128 x = _mm_loadu_ps(c + i);
        x = _mm_max_ps(x, zero); /* x > 0 ? x : 0 */
        x = _mm_min_ps(x, one);  /* x < 1 ? x : 1 */
        const __m128i v = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(x, k255), half));
        const __m128i b8 = _mm_packus_epi16(_mm_packs_epi32(v, v), _mm_setzero_si128());
        const int32_t w = _mm_cvtsi128_si32(b8);
        std::memcpy(u + i, &w, 4);
    }
#endif
    for (; i < n; ++i) {
        float x = c[i];
        x = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
        u[i] = static_cast<uint8_t>(x * 255.0f + 0.5f);
    }
}

/* Streams the planned segments into a Pipe, converting straight into its
 * blocks. */
class BinWriter {
  public:
    BinWriter(Pipe &out, TangentAhead *ahead) : out_(out), ahead_(ahead) {}

    void write(const Segment &s) {
        switch (s.kind) {
        case kRaw:
            out_.put(s.src, static_cast<size_t>(s.bytes));
            return;
        case kZero:
            out_.zeros(s.bytes);
            return;
        case kIndices:
            if (s.aux == 0) { /* already right: straight from the mesh */
                out_.put(s.m->indices + s.base, static_cast<size_t>(s.count) * sizeof(uint32_t));
                return;
            }
            break;
        case kTangent:
            tangents_for(s);
            break;
        default:
            break;
        }
        /* 4-byte words per element (kColor: its four bytes are one) */
        const uint32_t width = s.kind == kIndices ? 1 : static_cast<uint32_t>(s.bytes / 4 / (s.count ? s.count : 1));
        const size_t elem = static_cast<size_t>(width) * sizeof(float);
        for (uint32_t i0 = 0; i0 < s.count;) {
            size_t cap = 0;
            float *o = reinterpret_cast<float *>(out_.space(elem, cap));
            uint32_t n = static_cast<uint32_t>(std::min<uint64_t>(cap / elem, s.count - i0));
            fill(s, i0, n, o);
            out_.used(n * elem);
            i0 += n;
        }
    }

  private:
    /* Elements [i0, i0 + n) of segment s into o. */
    void fill(const Segment &s, uint32_t i0, uint32_t n, float *o) {
        const banyan_mesh *m = s.m;
        const size_t b = static_cast<size_t>(s.base) + i0;
        switch (s.kind) {
        case kPosition: /* (x, y, z) -> (x, z, -y) */
            for (uint32_t i = 0; i < n; ++i, o += 3) {
                const float *p = m->positions + 3 * (b + i);
                o[0] = p[0];
                o[1] = p[2];
                o[2] = -p[1];
            }
            break;
        case kNormal: /* converted, renormalised in double; a zero normal becomes +Y */
            put_normals(m->normals + 3 * b, n, o);
            break;
        case kUv: /* glTF's v runs down the image, banyan's (like Blender's) up */
            for (uint32_t i = 0; i < n; ++i, o += 2) {
                const float *t = m->uvs + 2 * (b + i);
                o[0] = t[0];
                o[1] = 1.0f - t[1];
            }
            break;
        case kTangent: { /* converted like the normals (a rotation: w keeps its sign) */
            const float *t = tan_->data() + 4 * (b - tan_base_);
            for (uint32_t i = 0; i < n; ++i, o += 4, t += 4) {
                o[0] = t[0];
                o[1] = t[2];
                o[2] = -t[1];
                o[3] = t[3];
            }
            break;
        }
        case kWindPivot: { /* one axis of a point like POSITION: x, z, -y */
            const Layout &L = *s.L;
            const float *src = L.wind[s.aux == 0 ? 0 : s.aux == 1 ? 2 : 1];
            const float sign = s.aux == 2 ? -1.0f : 1.0f;
            for (uint32_t i = 0; i < n; ++i) o[i] = sign * src[b + i];
            break;
        }
        case kEngineUv: {
            /* TEXCOORD_1 arm (x, y), 2 (arm z, level), 3 (stiffness,
             * phase), 4 (flutter, birth). The arm is pivot - position, Y up
             * as POSITION: bounded by the plant's size, so an engine that
             * keeps a UV set at half precision still has it to 2^-11 of its
             * length (a leaf's pivot to micrometres, where the pivot itself
             * would lose millimetres). */
            const Layout &L = *s.L;
            const float *P = s.m->positions;
            for (uint32_t i = 0; i < n; ++i, o += 2) {
                size_t j = b + i;
                float a = 0.0f, c = 0.0f;
                switch (s.aux) {
                case 1: a = L.wind[0][j] - P[3 * j]; c = L.wind[2][j] - P[3 * j + 2]; break;
                case 2: a = -(L.wind[1][j] - P[3 * j + 1]); c = L.wind[3][j]; break;
                case 3: a = L.wind[4][j]; c = L.wind[5][j]; break;
                default: a = L.wind[6][j]; c = L.birth ? L.birth[j] : 0.0f; break;
                }
                o[0] = a;
                o[1] = c;
            }
            break;
        }
        case kPivotPainterUv: /* already in glTF's uv (v down), as Unreal reads it */
            std::memcpy(o, s.L->pp2 + 2 * b, static_cast<size_t>(n) * 2 * sizeof(float));
            break;
        case kColor: /* clamped to [0, 1], rounded to the nearest of 0..255 */
            put_colors(m->colors + 4 * b, 4 * n, reinterpret_cast<uint8_t *>(o));
            break;
        case kIndices: { /* rebased to the primitive's first vertex */
            uint32_t *u = reinterpret_cast<uint32_t *>(o);
            for (uint32_t i = 0; i < n; ++i) u[i] = m->indices[b + i] - s.aux;
            break;
        }
        default:
            break;
        }
    }

    /* The tangents a kTangent segment reads: its own range's, or the whole
     * mesh's, kept while the same mesh's ranges follow. */
    void tangents_for(const Segment &s) {
        if (s.whole && tan_mesh_ == s.m && tan_whole_) return;
        const TangentKey key = tangent_key(s);
        tan_ = ahead_ ? ahead_->take(key, scratch_) : std::make_shared<const std::vector<float>>(tangents_of(key, scratch_));
        tan_mesh_ = s.m;
        tan_whole_ = s.whole;
        tan_base_ = key.base;
    }

    Pipe &out_;
    TangentAhead *ahead_; /* NULL: every range computed here */
    std::shared_ptr<const std::vector<float>> tan_;
    std::vector<double> scratch_; /* the tangents' sums, reused from range to range */
    const banyan_mesh *tan_mesh_ = nullptr;
    bool tan_whole_ = false;
    size_t tan_base_ = 0;
};

} // namespace

void stream_segments(Sink &bin, OutFile &out, const std::vector<Segment> &segs, size_t from,
                     const prog_deadline &deadline, bool &late, TangentAhead *ahead) {
    Pipe pipe(bin, out);
    pipe.run([&segs, from, &deadline, &late, ahead](Pipe &p) {
        BinWriter bw(p, ahead);
        for (size_t k = from, n = segs.size(); k < n; ++k) {
            if (p.failed()) break;
            if (prog_deadline_passed(&deadline)) {
                late = true;
                break;
            }
            bw.write(segs[k]);
        }
    });
}

namespace {

void put_u32(std::string &s, uint32_t v) {
    for (int k = 0; k < 4; ++k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
}

uint32_t get_u32(const std::string &s, size_t at) {
    uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(s[at + static_cast<size_t>(k)]);
    return v;
}

/* Sets buffer 0's "byteLength": 0 after `key` to n; false if not found
 * where expected. `at` gets where the digit was. */
bool patch_byte_length(std::string &json, const std::string &key, const std::string &field, uint64_t n,
                       size_t &at) {
    size_t k = json.find(key);
    if (k == std::string::npos || json.find(key, k + 1) != std::string::npos) return false;
    size_t f = json.find(field, k + key.size());
    if (f == std::string::npos || f != json.find_first_of('"', k + key.size())) return false;
    at = f + field.size();
    if (json.compare(at, 1, "0") != 0 || (at + 1 < json.size() && json[at + 1] >= '0' && json[at + 1] <= '9'))
        return false;
    json.replace(at, 1, std::to_string(n));
    return true;
}

} // namespace

/* tinygltf's document for an empty buffer 0 into what goes before and after
 * the buffer's `total` bytes: a .glb's header, JSON chunk and BIN chunk
 * header, then the BIN padding; a .gltf's JSON up to the base64 of the data
 * URI, then the rest. The same bytes tinygltf writes with the buffer held,
 * but for json_chunk (a .glb): the JSON chunk padded with spaces to that
 * length, the head's size fixed before the JSON is known. */
bool split_document(const std::string &doc, bool binary, uint64_t total, std::string &head, std::string &tail,
                    size_t json_chunk) {
    if (binary) {
        if (doc.size() < 20 || doc.compare(0, 4, "glTF") != 0 || get_u32(doc, 16) != 0x4E4F534Au) return false;
        uint32_t chunk = get_u32(doc, 12);
        if (20 + static_cast<uint64_t>(chunk) != doc.size()) return false; /* no BIN chunk: the buffer was empty */
        std::string json = doc.substr(20, chunk);
        while (!json.empty() && json.back() == ' ') json.pop_back(); /* tinygltf's padding */
        size_t at = 0;
        if (!patch_byte_length(json, "\"buffers\":[{", "\"byteLength\":", total, at)) return false;
        if (json_chunk) { /* a JSON chunk of this many bytes (a multiple of 4): spaces after the JSON */
            if (json.size() > json_chunk || json_chunk % 4) return false;
            json.append(json_chunk - json.size(), ' ');
        }
        const uint64_t jpad = (4 - json.size() % 4) % 4, bpad = (4 - total % 4) % 4;
        const uint64_t length = 12 + 8 + json.size() + jpad + 8 + total + bpad;
        if (length > 0xFFFFFFFFu) return false;
        head.assign("glTF");
        put_u32(head, 2);
        put_u32(head, static_cast<uint32_t>(length));
        put_u32(head, static_cast<uint32_t>(json.size() + jpad));
        put_u32(head, 0x4E4F534Au); /* JSON */
        head += json;
        head.append(static_cast<size_t>(jpad), ' ');
        put_u32(head, static_cast<uint32_t>(total + bpad));
        put_u32(head, 0x004E4942u); /* BIN */
        tail.assign(static_cast<size_t>(bpad), '\0');
        return true;
    }
    std::string json = doc;
    size_t at = 0;
    if (!patch_byte_length(json, "\"buffers\": [", "\"byteLength\": ", total, at)) return false;
    const std::string uri = "\"uri\": \"data:application/octet-stream;base64,\"";
    size_t u = json.find(uri, at);
    if (u == std::string::npos || json.find_first_of("{}", at) < u) return false;
    size_t split = u + uri.size() - 1; /* before the closing quote */
    head = json.substr(0, split);
    tail = json.substr(split);
    return true;
}

} // namespace gltfw

/*
 * gltf_write_tangents.cpp - per-vertex tangents for the normal maps
 * (gltf_write.h), and their computation ahead of the stream: a thread
 * started before the meshes are checked computes each range's tangents in
 * the order the stream asks for them, so the work overlaps the checks,
 * the planning and the streaming instead of adding to them. Each range's
 * tangents are the same bits whichever thread computes them.
 */
#include "gltf/gltf_write.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <system_error>

namespace gltfw {

/* Per-vertex tangents (x, y, z, w) in the mesh's own Z-up frame, for
 * normal maps: xyz the direction of increasing u, made perpendicular to
 * the normal; w = +1 when (normal x tangent) points up the image
 * (increasing banyan v, glTF's bitangent), -1 where the uvs are mirrored.
 * Triangles add their uv gradients to their corners (Lengyel's method);
 * a vertex without a usable gradient gets any unit vector perpendicular
 * to its normal. Needs normals and uvs. Computed for vertices
 * [vbase, vbase + vc) from the triangles of indices [ioff, ioff + icount),
 * which must reference only those vertices; out[4 (v - vbase) ..]. When no
 * other triangle touches the range, this is the whole mesh's result, bit
 * for bit: each vertex sums the same terms in the same order. */
namespace {

/* Vertices per chunk: a chunk's sums (48 bytes a vertex) stay in the
 * cache while its triangles add to them. */
constexpr uint32_t kChunkShift = 14;

/* One triangle's uv gradients (s, t per axis, interleaved as the sums
 * are): false when its uvs are degenerate (it adds nothing). */
inline bool tri_gradient(const banyan_mesh *m, const uint32_t i[3], double st[6]) {
    const float *p0 = m->positions + 3 * static_cast<size_t>(i[0]);
    const float *p1 = m->positions + 3 * static_cast<size_t>(i[1]);
    const float *p2 = m->positions + 3 * static_cast<size_t>(i[2]);
    const float *t0 = m->uvs + 2 * static_cast<size_t>(i[0]);
    const float *t1 = m->uvs + 2 * static_cast<size_t>(i[1]);
    const float *t2 = m->uvs + 2 * static_cast<size_t>(i[2]);
    double e1[3], e2[3];
    for (int c = 0; c < 3; ++c) {
        e1[c] = static_cast<double>(p1[c]) - p0[c];
        e2[c] = static_cast<double>(p2[c]) - p0[c];
    }
    double du1 = static_cast<double>(t1[0]) - t0[0], dv1 = static_cast<double>(t1[1]) - t0[1];
    double du2 = static_cast<double>(t2[0]) - t0[0], dv2 = static_cast<double>(t2[1]) - t0[1];
    double det = du1 * dv2 - du2 * dv1;
    if (!(std::fabs(det) > 1e-20)) return false;
    const double r = 1.0 / det;
#if defined(__SSE2__)
    /* (sd[c], td[c]) in one register: the same products, differences and
     * scaling as the scalar lines below, two lanes at a time. */
    const __m128d a = _mm_set_pd(du1, dv2), bq = _mm_set_pd(du2, dv1), rr = _mm_set1_pd(r);
    for (int c = 0; c < 3; ++c) {
        const __m128d e = _mm_set_pd(e2[c], e1[c]); /* (e1, e2) */
        const __m128d es = _mm_shuffle_pd(e, e, 1); /* (e2, e1) */
        _mm_storeu_pd(st + 2 * c, _mm_mul_pd(_mm_sub_pd(_mm_mul_pd(e, a), _mm_mul_pd(es, bq)), rr));
    }
#else
    for (int c = 0; c < 3; ++c) {
        st[2 * c] = (e1[c] * dv2 - e2[c] * dv1) * r;
        st[2 * c + 1] = (e2[c] * du1 - e1[c] * du2) * r;
    }
#endif
    return true;
}

/* A vertex's tangent from its normal nv and its sums s2 ((t, b) per axis). */
inline void finish_tangent(const float *nv, const double *s2, float *out) {
    double n[3] = {nv[0], nv[1], nv[2]};
    double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nl > 0.0) {
        for (double &c : n) c /= nl;
    } else { /* the writer's zero normal becomes +Y up, i.e. +Z here */
        n[0] = n[1] = 0.0;
        n[2] = 1.0;
    }
    const double t[3] = {s2[0], s2[2], s2[4]}, bt[3] = {s2[1], s2[3], s2[5]};
    double d = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    double q[3] = {t[0] - d * n[0], t[1] - d * n[1], t[2] - d * n[2]};
    double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (!(ql > 1e-12 * (1.0 + std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2])))) {
        /* any perpendicular: n x (the axis least along n) */
        double a[3] = {0.0, 0.0, 0.0};
        int least = std::fabs(n[0]) <= std::fabs(n[1]) ? (std::fabs(n[0]) <= std::fabs(n[2]) ? 0 : 2)
                                                        : (std::fabs(n[1]) <= std::fabs(n[2]) ? 1 : 2);
        a[least] = 1.0;
        q[0] = n[1] * a[2] - n[2] * a[1];
        q[1] = n[2] * a[0] - n[0] * a[2];
        q[2] = n[0] * a[1] - n[1] * a[0];
        ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    }
    for (double &c : q) c /= ql;
    double cx[3] = {n[1] * q[2] - n[2] * q[1], n[2] * q[0] - n[0] * q[2], n[0] * q[1] - n[1] * q[0]};
    double w = cx[0] * bt[0] + cx[1] * bt[1] + cx[2] * bt[2] < 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(q[c]);
    out[3] = static_cast<float>(w);
}

#if defined(__SSE2__)
/* finish_tangent for two vertices at once (normals nv, nv + 3; sums s2,
 * s2 + 6; out, out + 4): the same correctly rounded operations lane by
 * lane, so the same bits. False, with nothing written, when either takes
 * a rare branch (a zero normal, no usable gradient): finish_tangent then
 * does both. */
inline bool finish_tangent2(const float *nv, const double *s2, float *out) {
    const __m128d nx0 = _mm_set_pd(nv[3], nv[0]), ny0 = _mm_set_pd(nv[4], nv[1]), nz0 = _mm_set_pd(nv[5], nv[2]);
    const __m128d nl = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(nx0, nx0), _mm_mul_pd(ny0, ny0)),
                                              _mm_mul_pd(nz0, nz0)));
    const __m128d zero = _mm_setzero_pd();
    if (_mm_movemask_pd(_mm_cmpgt_pd(nl, zero)) != 3) return false;
    const __m128d nx = _mm_div_pd(nx0, nl), ny = _mm_div_pd(ny0, nl), nz = _mm_div_pd(nz0, nl);
    const __m128d tx = _mm_set_pd(s2[6], s2[0]), ty = _mm_set_pd(s2[8], s2[2]), tz = _mm_set_pd(s2[10], s2[4]);
    const __m128d bx = _mm_set_pd(s2[7], s2[1]), by = _mm_set_pd(s2[9], s2[3]), bz = _mm_set_pd(s2[11], s2[5]);
    const __m128d d = _mm_add_pd(_mm_add_pd(_mm_mul_pd(tx, nx), _mm_mul_pd(ty, ny)), _mm_mul_pd(tz, nz));
    __m128d qx = _mm_sub_pd(tx, _mm_mul_pd(d, nx)), qy = _mm_sub_pd(ty, _mm_mul_pd(d, ny)),
            qz = _mm_sub_pd(tz, _mm_mul_pd(d, nz));
    const __m128d ql = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(qx, qx), _mm_mul_pd(qy, qy)), _mm_mul_pd(qz, qz)));
    const __m128d tl = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(tx, tx), _mm_mul_pd(ty, ty)), _mm_mul_pd(tz, tz)));
    const __m128d bound = _mm_mul_pd(_mm_set1_pd(1e-12), _mm_add_pd(_mm_set1_pd(1.0), tl));
    if (_mm_movemask_pd(_mm_cmpgt_pd(ql, bound)) != 3) return false;
    qx = _mm_div_pd(qx, ql), qy = _mm_div_pd(qy, ql), qz = _mm_div_pd(qz, ql);
    const __m128d cx = _mm_sub_pd(_mm_mul_pd(ny, qz), _mm_mul_pd(nz, qy));
    const __m128d cy = _mm_sub_pd(_mm_mul_pd(nz, qx), _mm_mul_pd(nx, qz));
    const __m128d cz = _mm_sub_pd(_mm_mul_pd(nx, qy), _mm_mul_pd(ny, qx));
    const __m128d dot = _mm_add_pd(_mm_add_pd(_mm_mul_pd(cx, bx), _mm_mul_pd(cy, by)), _mm_mul_pd(cz, bz));
    const int neg = _mm_movemask_pd(_mm_cmplt_pd(dot, zero));
    double X[2], Y[2], Z[2];
    _mm_storeu_pd(X, qx);
    _mm_storeu_pd(Y, qy);
    _mm_storeu_pd(Z, qz);
    for (int k = 0; k < 2; ++k) {
        out[4 * k] = static_cast<float>(X[k]);
        out[4 * k + 1] = static_cast<float>(Y[k]);
        out[4 * k + 2] = static_cast<float>(Z[k]);
        out[4 * k + 3] = (neg >> k) & 1 ? -1.0f : 1.0f;
    }
    return true;
}
#endif

} // namespace

/* The vertices go in chunks of 2^kChunkShift: each chunk's triangles (any
 * corner in it, in index order, listed once up front) add to its sums,
 * which stay in the cache, then its tangents are finished. A vertex sums
 * the same terms in the same order as one pass over every triangle would. */
std::vector<float> vertex_tangents(const banyan_mesh *m, uint32_t vbase, uint32_t vcount, uint32_t ioff,
                                   uint32_t icount, std::vector<double> &acc) {
    const size_t vc = vcount;
    const uint32_t chunk = 1u << kChunkShift;
    const size_t nchunks = (vc + chunk - 1) >> kChunkShift;
    /* rel[j] >> kChunkShift for a corner of the range, nchunks for one
     * outside it (it adds to nothing). */
    auto chunk_of = [&](uint32_t idx) -> size_t {
        uint32_t rel = idx - vbase;
        return rel < vc ? rel >> kChunkShift : nchunks;
    };
    std::vector<uint32_t> start(nchunks + 2, 0), list;
    for (uint32_t k = ioff; k + 2 < ioff + icount; k += 3) {
        size_t c0 = chunk_of(m->indices[k]), c1 = chunk_of(m->indices[k + 1]), c2 = chunk_of(m->indices[k + 2]);
        start[c0 + 1]++;
        if (c1 != c0) start[c1 + 1]++;
        if (c2 != c0 && c2 != c1) start[c2 + 1]++;
    }
    for (size_t c = 0; c <= nchunks; ++c) start[c + 1] += start[c];
    list.resize(start[nchunks]);
    {
        std::vector<uint32_t> fill(start.begin(), start.begin() + static_cast<long>(nchunks));
        for (uint32_t k = ioff; k + 2 < ioff + icount; k += 3) {
            size_t c0 = chunk_of(m->indices[k]), c1 = chunk_of(m->indices[k + 1]), c2 = chunk_of(m->indices[k + 2]);
            if (c0 < nchunks) list[fill[c0]++] = k;
            if (c1 != c0 && c1 < nchunks) list[fill[c1]++] = k;
            if (c2 != c0 && c2 != c1 && c2 < nchunks) list[fill[c2]++] = k;
        }
    }
    acc.resize(6 * std::min<size_t>(vc, chunk)); /* per vertex and axis (t, b); the caller's memory, reused */
    std::vector<float> out(4 * vc);
    for (size_t c = 0; c < nchunks; ++c) {
        const uint32_t lo = static_cast<uint32_t>(c << kChunkShift);
        const uint32_t n = static_cast<uint32_t>(std::min<size_t>(chunk, vc - lo));
        std::memset(acc.data(), 0, sizeof(double) * 6 * n);
        for (uint32_t e = start[c]; e < start[c + 1]; ++e) {
            const uint32_t k = list[e];
            const uint32_t i[3] = {m->indices[k], m->indices[k + 1], m->indices[k + 2]};
            double st[6];
            if (!tri_gradient(m, i, st)) continue;
            for (int j = 0; j < 3; ++j) {
                const uint32_t rel = i[j] - vbase - lo;
                if (rel >= n) continue; /* another chunk's corner */
                double *a = &acc[6 * static_cast<size_t>(rel)];
#if defined(__SSE2__)
                for (int q = 0; q < 3; ++q)
                    _mm_storeu_pd(a + 2 * q, _mm_add_pd(_mm_loadu_pd(a + 2 * q), _mm_loadu_pd(st + 2 * q)));
#else
                for (int q = 0; q < 6; ++q) a[q] += st[q];
#endif
            }
        }
        uint32_t v = 0;
#if defined(__SSE2__)
        for (; v + 2 <= n; v += 2) {
            const float *nv = m->normals + 3 * (static_cast<size_t>(vbase) + lo + v);
            const double *s2 = &acc[6 * static_cast<size_t>(v)];
            float *o = &out[4 * (static_cast<size_t>(lo) + v)];
            if (!finish_tangent2(nv, s2, o)) {
                finish_tangent(nv, s2, o);
                finish_tangent(nv + 3, s2 + 6, o + 4);
            }
        }
#endif
        for (; v < n; ++v)
            finish_tangent(m->normals + 3 * (static_cast<size_t>(vbase) + lo + v), &acc[6 * static_cast<size_t>(v)],
                           &out[4 * (static_cast<size_t>(lo) + v)]);
    }
    return out;
}

namespace {

/* Whether the worker may read mesh m: what check_mesh guarantees of the
 * fields tangents and plan_prims read (a mesh that fails here fails the
 * check, and the worker leaves it alone). */
bool tangents_safe(const banyan_mesh *m) {
    if (m == nullptr || m->vertex_count == 0 || m->index_count == 0 || m->index_count % 3 != 0) return false;
    if (!m->positions || !m->indices) return false;
    if ((m->material_count > 0 && !m->materials) || (m->part_count > 0 && !m->parts) ||
        (m->instance_count > 0 && !m->instances))
        return false;
    for (uint32_t p = 0; p < m->part_count; ++p) {
        const banyan_part *pt = &m->parts[p];
        if (static_cast<uint64_t>(pt->vertex_offset) + pt->vertex_count > m->vertex_count ||
            static_cast<uint64_t>(pt->index_offset) + pt->index_count > m->index_count || pt->index_count % 3 != 0)
            return false;
    }
    uint32_t top = 0;
    for (uint32_t i = 0; i < m->index_count; ++i) top = std::max(top, m->indices[i]);
    return top < m->vertex_count;
}

/* Whether the writer gives mesh m tangents (Write::plan_buffer's rule). */
bool wants_tangents(const banyan_mesh *m, const banyan_gltf_options &o) {
    if (!o.textures) return false;
    for (uint32_t k = 0; k < m->material_count; ++k) {
        const banyan_material *bm = &m->materials[k];
        if (bm->image > 0) continue;
        if (texture_key(m, bm) >= 0) return true;
    }
    return false;
}

} // namespace

bool TangentKey::operator==(const TangentKey &k) const {
    return m == k.m && whole == k.whole && (whole || (base == k.base && count == k.count && ioff == k.ioff &&
                                                      icount == k.icount));
}

TangentKey tangent_key(const Segment &s) {
    TangentKey k;
    k.m = s.m;
    k.whole = s.whole;
    k.base = s.whole ? 0 : s.base;
    k.count = s.whole ? s.m->vertex_count : s.count;
    k.ioff = s.whole ? 0 : s.ioff;
    k.icount = s.whole ? s.m->index_count : s.icount;
    return k;
}

std::vector<float> tangents_of(const TangentKey &k, std::vector<double> &scratch) {
    return vertex_tangents(k.m, k.base, k.count, k.ioff, k.icount, scratch);
}

/* The ranges mesh m's tangents are streamed in, in emit_job's order: the
 * whole mesh once, or each primitive's own (tangent_ranges_exact), the
 * variants of an instanced mesh in turn. */
void tangent_keys(const banyan_mesh *m, std::vector<TangentKey> &out) {
    std::vector<Prim> prims;
    bool local = false;
    plan_prims(m, 0, prims, local);
    if (!tangent_ranges_exact(m, prims, local)) {
        TangentKey k;
        k.m = m;
        k.whole = true;
        k.count = m->vertex_count;
        k.icount = m->index_count;
        out.push_back(k);
        return;
    }
    auto add = [&](const Prim &pr) {
        TangentKey k;
        k.m = m;
        k.base = pr.vbase;
        k.count = pr.vcount;
        k.ioff = pr.ioff;
        k.icount = pr.icount;
        out.push_back(k);
    };
    if (m->instance_count == 0) {
        for (const Prim &pr : prims) add(pr);
        return;
    }
    for (uint32_t g : drawn_groups(m)) {
        bool shown = false;
        for (uint32_t k = 0; k < m->instance_count && !shown; ++k) shown = m->instances[k].variant == g;
        if (!shown) continue;
        for (const Prim &pr : prims)
            if (pr.group == g) add(pr);
    }
}

TangentAhead::TangentAhead(const banyan_gltf_node *nodes, uint32_t count, const banyan_gltf_options &o)
    : nodes_(nodes), count_(count), o_(o) {
    try {
        th_ = std::thread([this] { run(); });
    } catch (const std::system_error &) {
        /* no thread: the stream computes every range itself */
    }
}

TangentAhead::~TangentAhead() {
    {
        std::lock_guard<std::mutex> lk(mu_);
        stop_ = true;
    }
    cv_.notify_all();
    if (th_.joinable()) th_.join();
}

void TangentAhead::run() {
    try {
        for (uint32_t i = 0; i < count_; ++i) {
            const banyan_gltf_node &n = nodes_[i];
            if (n.lod_count > kMaxLods || (n.lod_count > 0 && n.lods == nullptr)) break;
            for (uint32_t k = 0; k <= n.lod_count; ++k) {
                const banyan_mesh *m = k == 0 ? n.mesh : n.lods[k - 1];
                if (!tangents_safe(m)) return; /* the check refuses it: nothing more will be streamed */
                if (!wants_tangents(m, o_)) continue;
                std::vector<TangentKey> keys;
                tangent_keys(m, keys);
                size_t most = 0; /* the sums' memory once, for the mesh's largest range */
                for (const TangentKey &key : keys) most = std::max<size_t>(most, key.count);
                if (scratch_.capacity() < 6 * most) {
                    scratch_ = std::vector<double>();
                    scratch_.reserve(6 * most);
                }
                for (const TangentKey &key : keys)
                    if (!compute(key)) return;
            }
        }
    } catch (...) {
        /* out of memory here: the stream computes what is missing */
    }
}

bool TangentAhead::compute(const TangentKey &key) {
    size_t at;
    {
        std::unique_lock<std::mutex> lk(mu_);
        cv_.wait(lk, [this] { return stop_ || held_ < kAheadBytes; });
        if (stop_) return false;
        for (const Entry &e : entries_)
            if (e.key == key) return true; /* claimed already (the stream, or a repeated range) */
        entries_.push_back(Entry{key, kComputing, nullptr});
        at = entries_.size() - 1;
    }
    auto t = std::make_shared<const std::vector<float>>(tangents_of(key, scratch_));
    std::lock_guard<std::mutex> lk(mu_);
    entries_[at].state = kDone;
    entries_[at].data = t;
    held_ += t->size() * sizeof(float);
    cv_.notify_all();
    return true;
}

std::shared_ptr<const std::vector<float>> TangentAhead::take(const TangentKey &key, std::vector<double> &scratch) {
    {
        std::unique_lock<std::mutex> lk(mu_);
        for (;;) {
            Entry *found = nullptr;
            for (Entry &e : entries_)
                if (e.key == key) found = &e;
            if (found == nullptr) { /* not reached yet: claimed and computed here */
                entries_.push_back(Entry{key, kTaken, nullptr});
                break;
            }
            if (found->state == kDone) {
                std::shared_ptr<const std::vector<float>> t = std::move(found->data);
                found->data.reset();
                found->state = kTaken;
                held_ -= t->size() * sizeof(float);
                cv_.notify_all();
                return t;
            }
            if (found->state == kTaken) break; /* taken already (a range asked for twice): computed again */
            cv_.wait(lk); /* kComputing: the worker finishes it */
        }
    }
    return std::make_shared<const std::vector<float>>(tangents_of(key, scratch));
}

} // namespace gltfw

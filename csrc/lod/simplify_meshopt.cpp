/* simplify_meshopt.cpp - wood simplification for levels of detail: the
 * one C++ shim around meshoptimizer 0.18 (Kapoulkine's edge-collapse
 * simplifier with quadric error metrics, Garland & Heckbert 1997).
 *
 * meshoptimizer 0.18 knows positions only, so a tube's seam (two vertices
 * per point, u = 0 and u = 1) and its caps (own normals) would read as
 * cracks. The part is welded by position first (a shadow index buffer),
 * simplified with its open border locked (tube ends that meet their
 * parent stay put), and every kept corner is mapped back to the member of
 * its weld whose uv lies nearest the triangle's other corners and whose
 * normal faces the triangle's way: the seam keeps its u = 0 / u = 1 pair,
 * no triangle wraps the texture. When the collapses stop short of the
 * target (a twig of two rings has nothing but border), the grid
 * simplifier (meshopt_simplifySloppy) finishes the job. */
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <new>
#include <vector>

#include <meshoptimizer.h>

#include "lod_internal.h"

namespace {

/* Relative error bounds (of the part's extent): the careful pass may move
 * the surface by 0.05 % (a centimetre on a 20 m tree: a limb of 2 cm or
 * more keeps its round section, the collapses take rings along its
 * length), the loose one by 5 %, the fallback by what it takes. */
const float CAREFUL_ERROR = 0.0005f;
const float LOOSE_ERROR = 0.05f;
const float SLOPPY_ERROR = 1.0f;

float uv_d2(const float *uv, uint32_t a, uint32_t b) {
    if (!uv) return 0;
    float du = uv[2 * (size_t)a] - uv[2 * (size_t)b], dv = uv[2 * (size_t)a + 1] - uv[2 * (size_t)b + 1];
    return du * du + dv * dv;
}

float nrm_miss(const float *nrm, uint32_t v, const float fn[3]) {
    if (!nrm) return 0;
    const float *n = nrm + 3 * (size_t)v;
    return 1.0f - (n[0] * fn[0] + n[1] * fn[1] + n[2] * fn[2]);
}

uint32_t uf_root(std::vector<uint32_t> &parent, uint32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

/* Drops the smallest connected pieces of tri[0 .. n) (by area; ties by
 * their first vertex) while what stays is at least target indices.
 * Returns the new count; triangles keep their order. */
size_t cull_small(std::vector<uint32_t> &tri, size_t n, const float *pos, uint32_t nv, size_t target) {
    std::vector<uint32_t> parent(nv);
    for (uint32_t v = 0; v < nv; v++) parent[v] = v;
    for (size_t t = 0; t + 2 < n; t += 3)
        for (int j = 1; j < 3; j++) {
            uint32_t a = uf_root(parent, tri[t]), b = uf_root(parent, tri[t + j]);
            if (a != b) parent[a < b ? b : a] = a < b ? a : b;
        }
    std::vector<double> area(nv, 0.0);
    std::vector<uint32_t> count(nv, 0);
    for (size_t t = 0; t + 2 < n; t += 3) {
        const float *a = pos + 3 * (size_t)tri[t], *b = pos + 3 * (size_t)tri[t + 1], *c = pos + 3 * (size_t)tri[t + 2];
        double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
        double e2[3] = {(double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2]};
        double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
        uint32_t r = uf_root(parent, tri[t]);
        area[r] += 0.5 * std::sqrt(x * x + y * y + z * z);
        count[r] += 3;
    }
    std::vector<uint32_t> roots;
    for (uint32_t v = 0; v < nv; v++)
        if (count[v]) roots.push_back(v);
    std::sort(roots.begin(), roots.end(), [&](uint32_t a, uint32_t b) {
        return area[a] < area[b] || (area[a] == area[b] && a < b);
    });
    /* Pieces that hold the part's bounds stay: the silhouette keeps its
     * size. */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < n; t++)
        for (int j = 0; j < 3; j++) {
            float x = pos[3 * (size_t)tri[t] + j];
            lo[j] = x < lo[j] ? x : lo[j];
            hi[j] = x > hi[j] ? x : hi[j];
        }
    std::vector<unsigned char> drop(nv, 0), rim(nv, 0);
    for (size_t t = 0; t < n; t++)
        for (int j = 0; j < 3; j++) {
            float x = pos[3 * (size_t)tri[t] + j], tol = 0.01f * (hi[j] - lo[j]);
            if (x <= lo[j] + tol || x >= hi[j] - tol) rim[uf_root(parent, tri[t])] = 1;
        }
    size_t left = n;
    for (uint32_t r : roots) {
        if (rim[r]) continue;
        if (left - count[r] < target) break;
        drop[r] = 1;
        left -= count[r];
    }
    size_t w = 0;
    for (size_t t = 0; t + 2 < n; t += 3)
        if (!drop[uf_root(parent, tri[t])])
            for (int j = 0; j < 3; j++) tri[w++] = tri[t + j];
    return w;
}

void simplify(const float *pos, const float *nrm, const float *uv, uint32_t nv, const uint32_t *idx, uint32_t ni,
              uint32_t target_tris, std::vector<uint32_t> &out, int *used_sloppy) {
    std::vector<uint32_t> shadow(ni);
    meshopt_generateShadowIndexBuffer(shadow.data(), idx, ni, pos, nv, 3 * sizeof(float), 3 * sizeof(float));
    /* Each vertex's weld (the first vertex at its position) and the welds'
     * members, CSR. */
    std::vector<uint32_t> canon(nv);
    for (uint32_t v = 0; v < nv; v++) canon[v] = v;
    for (uint32_t k = 0; k < ni; k++) canon[idx[k]] = shadow[k];
    std::vector<uint32_t> start(nv + 1, 0), members(nv);
    for (uint32_t v = 0; v < nv; v++) start[canon[v] + 1]++;
    for (uint32_t v = 0; v < nv; v++) start[v + 1] += start[v];
    {
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (uint32_t v = 0; v < nv; v++) members[fill[canon[v]]++] = v;
    }

    size_t target = (size_t)target_tris * 3;
    std::vector<uint32_t> simp(ni);
    size_t n = meshopt_simplify(simp.data(), shadow.data(), ni, pos, nv, 3 * sizeof(float), target, CAREFUL_ERROR,
                                meshopt_SimplifyLockBorder, NULL);
    *used_sloppy = 0;
    if (n > target + target / 20) {
        /* Still over: what is left is many small separate pieces (twigs of
         * two rings the collapses cannot touch, all border) and tubes whose
         * next collapse would flatten their section. Drop whole pieces, the
         * smallest by area first, down to the target: from afar a twig
         * disappears rather than turning into a blob, and the limbs keep
         * their round section. */
        n = cull_small(simp, n, pos, nv, target);
    }
    if (n > target + target / 20) {
        /* Thin tubes of two rings are all border: let the ends go too
         * (a twig's tip may shorten a little, 5 % of the part at most). */
        std::vector<uint32_t> loose(n);
        size_t m = meshopt_simplify(loose.data(), simp.data(), n, pos, nv, 3 * sizeof(float), target, LOOSE_ERROR, 0,
                                    NULL);
        if (m >= 3 && m < n) {
            std::memcpy(simp.data(), loose.data(), m * sizeof(uint32_t));
            n = m;
        }
    }
    if (n > target + target / 20) {
        /* The grid's cell size moves the count in steps, and the search
         * inside simplifySloppy lands at or below what it is asked: ask
         * again, scaled by the miss, and keep the closest of a few. */
        std::vector<uint32_t> rough(n), best;
        size_t ask = target, best_n = 0;
        for (int tries = 0; tries < 6; tries++) {
            size_t m = meshopt_simplifySloppy(rough.data(), simp.data(), n, pos, nv, 3 * sizeof(float), ask,
                                              SLOPPY_ERROR, NULL);
            if (m > 0 && m < n &&
                (best.empty() || (m > target ? m - target : target - m) < (best_n > target ? best_n - target : target - best_n))) {
                best.assign(rough.begin(), rough.begin() + (long)m);
                best_n = m;
            }
            if (m == 0 || (m > target ? m - target : target - m) <= target / 40) break;
            double scale = (double)target / (double)m;
            size_t next = (size_t)((double)ask * scale);
            if (next == ask) next = m < target ? ask + 3 : ask - 3;
            ask = next > n ? n : next < 3 ? 3 : next;
        }
        size_t miss_now = n > target ? n - target : target - n;
        size_t miss_best = best_n > target ? best_n - target : target - best_n;
        if (!best.empty() && miss_best < miss_now) {
            std::memcpy(simp.data(), best.data(), best_n * sizeof(uint32_t));
            n = best_n;
            *used_sloppy = 1;
        }
    }

    out.clear();
    out.reserve(n);
    for (size_t t = 0; t + 2 < n; t += 3) {
        const uint32_t c[3] = {simp[t], simp[t + 1], simp[t + 2]};
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
        const float *a = pos + 3 * (size_t)c[0], *b = pos + 3 * (size_t)c[1], *d = pos + 3 * (size_t)c[2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        float fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float len = std::sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
        float ext = std::fabs(e1[0]) + std::fabs(e1[1]) + std::fabs(e1[2]) + std::fabs(e2[0]) + std::fabs(e2[1]) +
                    std::fabs(e2[2]);
        if (!(len > 1e-7f * ext * ext) || !(len > 0)) continue; /* a sliver the collapses left flat */
        for (int k = 0; k < 3; k++) fn[k] /= len;
        /* Choose the weld members: each candidate of corner 0 as anchor,
         * the others' members nearest it in uv; the least uv spread and
         * normal mismatch wins (ties: the lowest vertex, deterministic). */
        uint32_t best[3] = {c[0], c[1], c[2]};
        uint32_t s0 = start[c[0]], e0 = start[c[0] + 1], s1 = start[c[1]], e1m = start[c[1] + 1],
                 s2 = start[c[2]], e2m = start[c[2] + 1];
        if (e0 - s0 > 1 || e1m - s1 > 1 || e2m - s2 > 1) {
            float best_score = 1e30f;
            for (uint32_t i = s0; i < e0 && i < s0 + 8; i++) {
                uint32_t A = members[i], pick[3] = {A, members[s1], members[s2]};
                float sc1 = 1e30f, sc2 = 1e30f;
                for (uint32_t j = s1; j < e1m && j < s1 + 8; j++) {
                    float s = uv_d2(uv, A, members[j]) + nrm_miss(nrm, members[j], fn);
                    if (s < sc1) sc1 = s, pick[1] = members[j];
                }
                for (uint32_t j = s2; j < e2m && j < s2 + 8; j++) {
                    float s = uv_d2(uv, A, members[j]) + uv_d2(uv, pick[1], members[j]) + nrm_miss(nrm, members[j], fn);
                    if (s < sc2) sc2 = s, pick[2] = members[j];
                }
                float score = sc1 + sc2 + nrm_miss(nrm, A, fn);
                if (score < best_score) {
                    best_score = score;
                    std::memcpy(best, pick, sizeof best);
                }
            }
        }
        out.push_back(best[0]);
        out.push_back(best[1]);
        out.push_back(best[2]);
    }
}

} // namespace

extern "C" int lod_simplify_part(const float *pos, const float *nrm, const float *uv, uint32_t nv,
                                 const uint32_t *idx, uint32_t ni, uint32_t target_tris, uint32_t **out_idx,
                                 uint32_t *out_ni, int *used_sloppy) {
    *out_idx = NULL;
    *out_ni = 0;
    *used_sloppy = 0;
    try {
        std::vector<uint32_t> out;
        if (ni >= 3 && nv > 0) simplify(pos, nrm, uv, nv, idx, ni, target_tris, out, used_sloppy);
        uint32_t *r = static_cast<uint32_t *>(std::malloc(sizeof(uint32_t) * (out.size() ? out.size() : 1)));
        if (!r) return -1;
        if (!out.empty()) std::memcpy(r, out.data(), out.size() * sizeof(uint32_t));
        *out_idx = r;
        *out_ni = static_cast<uint32_t>(out.size());
        return 0;
    } catch (const std::bad_alloc &) {
        return -1;
    }
}

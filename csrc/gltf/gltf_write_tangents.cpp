/*
 * gltf_write_tangents.cpp - per-vertex tangents for the normal maps
 * (gltf_write.h).
 */
#include "gltf/gltf_write.h"

#include <cmath>

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
std::vector<float> vertex_tangents(const banyan_mesh *m, uint32_t vbase, uint32_t vcount, uint32_t ioff,
                                   uint32_t icount) {
    const size_t vc = vcount;
    std::vector<double> acc(6 * vc, 0.0); /* t then b, per vertex */
    for (uint32_t k = ioff; k + 2 < ioff + icount; k += 3) {
        const uint32_t i[3] = {m->indices[k], m->indices[k + 1], m->indices[k + 2]};
        const uint32_t rel[3] = {i[0] - vbase, i[1] - vbase, i[2] - vbase};
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
        if (!(std::fabs(det) > 1e-20)) continue;
        double r = 1.0 / det, sd[3], td[3];
        for (int c = 0; c < 3; ++c) {
            sd[c] = (e1[c] * dv2 - e2[c] * dv1) * r;
            td[c] = (e2[c] * du1 - e1[c] * du2) * r;
        }
        for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) {
                acc[6 * static_cast<size_t>(rel[j]) + c] += sd[c];
                acc[6 * static_cast<size_t>(rel[j]) + 3 + c] += td[c];
            }
    }
    std::vector<float> out(4 * vc);
    for (size_t v = 0; v < vc; ++v) {
        const float *nv = m->normals + 3 * (vbase + v);
        double n[3] = {nv[0], nv[1], nv[2]};
        double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (nl > 0.0) {
            for (double &c : n) c /= nl;
        } else { /* the writer's zero normal becomes +Y up, i.e. +Z here */
            n[0] = n[1] = 0.0;
            n[2] = 1.0;
        }
        const double *t = &acc[6 * v], *bt = &acc[6 * v + 3];
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
        for (int c = 0; c < 3; ++c) out[4 * v + c] = static_cast<float>(q[c]);
        out[4 * v + 3] = static_cast<float>(w);
    }
    return out;
}

} // namespace gltfw

/* Host sets (spec README, "Hosts"; docs/hosts.md): oriented boxes kept as
 * exact obbs, triangle meshes held in an Embree BVH.
 *
 * A mesh is welded by exact position (glTF splits vertices at seams),
 * stripped of zero-area triangles and given the angle-weighted
 * pseudonormals of Baerentzen and Aanaes (2005): for a closed,
 * consistently wound mesh the sign of (p - q) . N at the closest feature q
 * (face, edge or vertex) is exactly the inside test. Where that cannot be
 * trusted (holes, several shells that may overlap as Suzanne's do,
 * inconsistent winding) the inside test casts three rays and takes the
 * majority: the winding number (exits minus entries) for a consistently
 * wound mesh, whose nonzero value is the union of overlapping shells, with
 * holes capped and the caps' own winding taken off (host_caps.c), else the
 * parity of the crossings. This file builds the set and answers
 * the public queries; the mesh queries are in host_queries.c. */
#include "hosts.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/frame.h"

#define MAX_VERTICES 33554432u /* 2^25 over the whole set */

/* --------------------------------------------------------- building */

static void mesh_free(host_mesh *m) {
    if (m->scene) rtcReleaseScene((RTCScene)m->scene);
    free(m->pos);
    free(m->tri);
    free(m->fnrm);
    free(m->twin);
    free(m->vnrm);
    free(m->capv);
    memset(m, 0, sizeof *m);
}

void banyan_hosts_free(banyan_hosts *H) {
    if (!H) return;
    for (uint32_t i = 0; i < H->n_meshes; i++) mesh_free(&H->meshes[i]);
    if (H->device) rtcReleaseDevice((RTCDevice)H->device);
    free(H->boxes);
    free(H->meshes);
    free(H->lo);
    free(H->hi);
    free(H);
}

static uint32_t uf_find(uint32_t *up, uint32_t i) {
    while (up[i] != i) {
        up[i] = up[up[i]];
        i = up[i];
    }
    return i;
}

/* Welds vertices of equal position: remap[i] = the first vertex there. */
static int weld(const float *pos, uint32_t nv, uint32_t *remap) {
    uint32_t cap = 16;
    while (cap < 2u * nv && cap < (1u << 31)) cap <<= 1;
    /* Each slot keeps its position's bits beside its vertex: one cache
     * line per probe. Equal bits are equal floats (no NaN here; -0 is
     * made +0). */
    typedef struct { uint32_t b[3], v; } slot_t;
    slot_t *slot = malloc(sizeof *slot * cap);
    if (!slot) return 0;
    for (uint32_t j = 0; j < cap; j++) slot[j].v = UINT32_MAX;
    for (uint32_t i = 0; i < nv; i++) {
        uint32_t b[3];
        memcpy(b, pos + 4 * (size_t)i, sizeof b);
        for (int k = 0; k < 3; k++)
            if (b[k] == 0x80000000u) b[k] = 0;
        uint32_t h = (b[0] * 73856093u) ^ (b[1] * 19349663u) ^ (b[2] * 83492791u);
        h ^= h >> 15;
        for (uint32_t j = h & (cap - 1);; j = (j + 1) & (cap - 1)) {
            slot_t *e = &slot[j];
            if (e->v == UINT32_MAX) {
                memcpy(e->b, b, sizeof b);
                e->v = remap[i] = i;
                break;
            }
            if (e->b[0] == b[0] && e->b[1] == b[1] && e->b[2] == b[2]) {
                remap[i] = e->v;
                break;
            }
        }
    }
    free(slot);
    return 1;
}

static float angle_at(v3 a, v3 b, v3 c) { /* angle at a of triangle abc; float is plenty for a weight */
    v3 u = v3_sub(b, a), v = v3_sub(c, a);
    float cosine = (float)(v3_dot(u, v) / sqrt(v3_len2(u) * v3_len2(v)));
    return dm_acosf(cosine < -1 ? -1 : cosine > 1 ? 1 : cosine);
}

static void store3(float *f, v3 v) {
    f[0] = (float)v.x;
    f[1] = (float)v.y;
    f[2] = (float)v.z;
}

/* The input's triangles as the host keeps them: indices checked,
 * zero-area ones dropped, winding flipped under a mirroring transform. */
typedef struct tri_input {
    const uint32_t *indices;
    uint32_t nt, nv;
    int flip;
    double area_eps;
} tri_input;

/* Fills m->tri, m->fnrm and m->nt, through remap (NULL: as given), and
 * *area. Returns UINT32_MAX, or the position in indices of an index out of
 * range. */
static uint32_t collect_triangles(host_mesh *m, const tri_input *ti, const uint32_t *remap, double *area) {
    uint32_t nt = 0;
    double twice = 0;
    for (uint32_t t = 0; t < ti->nt; t++) {
        const uint32_t *ix = ti->indices + 3 * (size_t)t;
        for (int k = 0; k < 3; k++)
            if (ix[k] >= ti->nv) return 3 * t + (uint32_t)k;
        uint32_t a = ix[0], b = ix[ti->flip ? 2 : 1], c = ix[ti->flip ? 1 : 2];
        if (remap) a = remap[a], b = remap[b], c = remap[c];
        v3 n = v3_cross(v3_sub(vtx(m, b), vtx(m, a)), v3_sub(vtx(m, c), vtx(m, a)));
        double len = v3_len(n);
        if (a == b || b == c || a == c || !(len > ti->area_eps)) continue;
        uint32_t *o = m->tri + 3 * (size_t)nt;
        o[0] = a, o[1] = b, o[2] = c;
        store3(m->fnrm + 3 * (size_t)nt, v3_scale(n, 1.0 / len));
        twice += len;
        nt++;
    }
    m->nt = nt;
    *area = 0.5 * twice;
    return UINT32_MAX;
}

typedef struct edge_stats {
    uint32_t boundary, nonmanifold;
    int consistent;
    double boundary_len;
} edge_stats;

/* Matches the 3 nt sides of m's triangles: twin[side] (UINT32_MAX on a
 * hole or a non-manifold edge), up[] the union-find of the shells. The
 * sides are bucketed by their lower vertex (a counting sort) and matched
 * by their upper vertex inside each small bucket. 0 when out of memory. */
static int match_edges(const host_mesh *m, uint32_t *twin, uint32_t *up, edge_stats *st) {
    const size_t ne = 3 * (size_t)m->nt;
    const uint32_t nv = m->nv;
    uint32_t *start = calloc((size_t)nv + 1, sizeof *start), *val = malloc(sizeof *val * ne),
             *bh = malloc(sizeof *bh * ne);
    if (!start || !val || !bh) {
        free(start), free(val), free(bh);
        return 0;
    }
#define SIDE_B(e) (m->tri[(e) % 3 == 2 ? (e) - 2 : (e) + 1])
#define SIDE_LO(e) (m->tri[e] < SIDE_B(e) ? m->tri[e] : SIDE_B(e))
#define SIDE_HI(e) (m->tri[e] < SIDE_B(e) ? SIDE_B(e) : m->tri[e])
    for (size_t e = 0; e < ne; e++) start[SIDE_LO(e) + 1]++, twin[e] = UINT32_MAX;
    for (uint32_t v = 0; v < nv; v++) start[v + 1] += start[v];
    for (size_t e = 0; e < ne; e++) { /* each side with its upper vertex beside it, read in order below */
        uint32_t at = start[SIDE_LO(e)]++;
        val[at] = (uint32_t)e;
        bh[at] = SIDE_HI(e);
    }
    for (uint32_t v = nv; v > 0; v--) start[v] = start[v - 1]; /* back to bucket starts */
    start[0] = 0;
    for (uint32_t t = 0; t < m->nt; t++) up[t] = t;
    memset(st, 0, sizeof *st);
    st->consistent = 1;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t *b = val + start[v], *bhi = bh + start[v], k = start[v + 1] - start[v];
        for (uint32_t i = 0; i < k; i++) {
            if (b[i] == UINT32_MAX) continue; /* taken by an earlier side */
            uint32_t e0 = b[i], h = bhi[i], same = 1, e1 = UINT32_MAX;
            for (uint32_t j = i + 1; j < k; j++) {
                if (b[j] == UINT32_MAX || bhi[j] != h) continue;
                uint32_t ra = uf_find(up, e0 / 3), rb = uf_find(up, b[j] / 3); /* round one edge: one shell */
                if (ra != rb) up[ra > rb ? ra : rb] = ra < rb ? ra : rb;
                e1 = b[j];
                b[j] = UINT32_MAX;
                same++;
            }
            if (same == 1) {
                st->boundary++;
                st->boundary_len += v3_dist(vtx(m, m->tri[e0]), vtx(m, SIDE_B(e0)));
            } else if (same == 2) {
                twin[e0] = e1, twin[e1] = e0;
                if (m->tri[e0] == m->tri[e1]) st->consistent = 0; /* both sides run the same way */
            } else {
                st->nonmanifold++;
            }
        }
    }
#undef SIDE_B
#undef SIDE_LO
#undef SIDE_HI
    free(start), free(val), free(bh);
    return 1;
}

#define MESH_FAIL(code, ...)                                                       \
    do {                                                                           \
        free(remap), free(up), free(twin), free(vol);                    \
        return banyan_fail(err, code, __VA_ARGS__);                                \
    } while (0)

/* Checks host `hi` (mesh number `mi`): not empty, its arrays given, closed
 * in range and its transform finite and not singular (*det_out: the
 * transform's determinant). */
static banyan_status mesh_check(const banyan_host_mesh *in, uint32_t hi, uint32_t mi, double *det_out,
                                banyan_error *err) {
    const uint32_t nv = in->vertex_count, nt_in = in->triangle_count;
    if (nv < 3 || nt_in < 1)
        return banyan_fail(err, BANYAN_E_BAD_HOST,
                           "hosts[%u] (mesh %u) is empty: vertex_count = %u, triangle_count = %u (a mesh "
                           "host needs at least 3 vertices and 1 triangle)",
                           hi, mi, nv, nt_in);
    if (!in->positions || !in->indices)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts[%u] (mesh %u): positions or indices is NULL", hi, mi);
    if (in->closed < -1 || in->closed > 1)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "hosts[%u] (mesh %u): closed = %d must be -1 (auto), 0 (open) or 1 (closed)", hi, mi,
                           in->closed);
    const double *T = in->transform;
    for (int i = 0; i < 12; i++)
        if (!isfinite(T[i]))
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): transform[%d] = %g must be finite", hi,
                               mi, i, T[i]);
    const double det = T[0] * (T[5] * T[10] - T[6] * T[9]) - T[1] * (T[4] * T[10] - T[6] * T[8]) +
                       T[2] * (T[4] * T[9] - T[5] * T[8]);
    double mx = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) mx = fmax(mx, fabs(T[4 * r + c]));
    if (!(fabs(det) > 1e-12 * mx * mx * mx) || mx == 0)
        return banyan_fail(err, BANYAN_E_BAD_HOST,
                           "hosts[%u] (mesh %u): transform is singular (determinant %g); a host needs "
                           "extent on every axis (scale != 0)",
                           hi, mi, det);
    *det_out = det;
    return BANYAN_OK;
}

/* World positions checked and bounded, then stored relative to the
 * centre of the bounds (m->origin) with the bounds; refused when a vertex
 * is not finite or beyond 1e6 m, or the mesh spans under 1e-6 m
 * (*diag_out: the bounds' diagonal). */
static banyan_status mesh_positions(const banyan_host_mesh *in, uint32_t hi, uint32_t mi, host_mesh *m,
                                    double *diag_out, banyan_error *err) {
    const uint32_t nv = in->vertex_count;
    const double *T = in->transform;
    m->pos = malloc(sizeof(float) * 4 * (size_t)nv);
    if (!m->pos) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for hosts[%u] (%u vertices)", hi, nv);
    v3 lo = v3_make(HUGE_VAL, HUGE_VAL, HUGE_VAL), hiw = v3_neg(lo);
    for (uint32_t i = 0; i < nv; i++) {
        const float *p = in->positions + 3 * (size_t)i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): vertex %u = (%g, %g, %g) is not finite",
                               hi, mi, i, p[0], p[1], p[2]);
        v3 w = v3_make(T[0] * p[0] + T[1] * p[1] + T[2] * p[2] + T[3], T[4] * p[0] + T[5] * p[1] + T[6] * p[2] + T[7],
                       T[8] * p[0] + T[9] * p[1] + T[10] * p[2] + T[11]);
        if (!(fabs(w.x) <= 1e6 && fabs(w.y) <= 1e6 && fabs(w.z) <= 1e6))
            return banyan_fail(err, BANYAN_E_BAD_HOST,
                               "hosts[%u] (mesh %u): vertex %u lies at (%g, %g, %g) m in the world; "
                               "coordinates must be within [-1e6, 1e6] m",
                               hi, mi, i, w.x, w.y, w.z);
        lo = v3_make(fmin(lo.x, w.x), fmin(lo.y, w.y), fmin(lo.z, w.z));
        hiw = v3_make(fmax(hiw.x, w.x), fmax(hiw.y, w.y), fmax(hiw.z, w.z));
    }
    m->origin = v3_scale(v3_add(lo, hiw), 0.5);
    for (uint32_t i = 0; i < nv; i++) {
        float *f = m->pos + 4 * (size_t)i;
        const float *p = in->positions + 3 * (size_t)i;
        /* Again, relative to the origin: floats keep their precision near
         * the mesh however far it is from the world's origin. */
        v3 w = v3_make(T[0] * p[0] + T[1] * p[1] + T[2] * p[2] + T[3], T[4] * p[0] + T[5] * p[1] + T[6] * p[2] + T[7],
                       T[8] * p[0] + T[9] * p[1] + T[10] * p[2] + T[11]);
        f[0] = (float)(w.x - m->origin.x), f[1] = (float)(w.y - m->origin.y), f[2] = (float)(w.z - m->origin.z);
        f[3] = 0;
    }
    m->nv = nv;
    m->lo = lo;
    m->hi = hiw;
    const double diag = v3_dist(lo, hiw);
    if (!(diag >= 1e-6)) /* as a box's half extent: nothing grows on a speck */
        return banyan_fail(err, BANYAN_E_BAD_HOST,
                           "hosts[%u] (mesh %u) spans %g m in the world; a host must span at least 1e-6 m "
                           "(is the object scaled to nearly 0?)",
                           hi, mi, diag);
    *diag_out = diag;
    return BANYAN_OK;
}

/* Pseudonormals of the vertices: the normals of the triangles around each,
 * weighted by their angles there, summed in m->vnrm (zeroed) and
 * normalised; +z for a vertex no triangle uses. */
static void vertex_normals(host_mesh *m, uint32_t nv, uint32_t nt) {
    for (uint32_t t = 0; t < nt; t++) { /* sums in vnrm itself, normalised after */
        const uint32_t *ix = m->tri + 3 * (size_t)t;
        const float *n = m->fnrm + 3 * (size_t)t;
        v3 a = vtx(m, ix[0]), b = vtx(m, ix[1]), c = vtx(m, ix[2]);
        float w[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
        for (int k = 0; k < 3; k++) {
            float *s = m->vnrm + 3 * (size_t)ix[k];
            s[0] += w[k] * n[0], s[1] += w[k] * n[1], s[2] += w[k] * n[2];
        }
    }
    for (uint32_t i = 0; i < nv; i++) {
        float *s = m->vnrm + 3 * (size_t)i;
        float l = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (l > 0) s[0] /= l, s[1] /= l, s[2] /= l;
        else s[2] = 1; /* a vertex no triangle uses */
    }
}

/* The BVH of host `hi`: an Embree scene over a user geometry whose
 * triangle tests are banyan's own (hmesh_user_geometry), padded by 1e-6 of
 * the diagonal. */
static banyan_status mesh_bvh(RTCDevice dev, host_mesh *m, uint32_t hi, double diag, banyan_error *err) {
    const uint32_t nt = m->nt;
    RTCScene sc = rtcNewScene(dev);
    if (!sc) return banyan_fail(err, BANYAN_E_NOMEM, "Embree could not make a scene for hosts[%u]", hi);
    m->scene = sc;
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    /* Embree's Morton builder (LOW) for big sculpts, twice as fast to build;
     * the SAH tree (MEDIUM), a little faster to query, below 200k. */
    rtcSetSceneBuildQuality(sc, nt > 200000 ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    /* A user geometry, not Embree's triangles: its triangle kernels round
     * differently on each CPU (SSE, AVX2 with FMA, AVX-512, approximate
     * reciprocals), so only its traversal is used (hmesh_user_geometry). */
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
    if (!g) return banyan_fail(err, BANYAN_E_NOMEM, "Embree could not make a geometry for hosts[%u]", hi);
    rtcSetGeometryBuildQuality(g, nt > 200000 ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM); /* both are read */
    m->bpad = (float)(1e-6 * diag);
    m->slack = 1e-12 * diag;
    hmesh_user_geometry(g, m);
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    enum RTCError e = rtcGetDeviceError(dev);
    if (e != RTC_ERROR_NONE)
        return banyan_fail(err, e == RTC_ERROR_OUT_OF_MEMORY ? BANYAN_E_NOMEM : BANYAN_E_INTERNAL,
                           "Embree failed to build hosts[%u] (error %d)", hi, (int)e);
    return BANYAN_OK;
}

/* Builds host `hi` (mesh number `mi`) into m. */
static banyan_status mesh_build(RTCDevice dev, const banyan_host_mesh *in, uint32_t hi, uint32_t mi, host_mesh *m,
                                banyan_error *err) {
    uint32_t *remap = NULL, *up = NULL, *twin = NULL;
    double *vol = NULL;
    const uint32_t nv = in->vertex_count, nt_in = in->triangle_count;
    double det = 0, diag = 0;
    banyan_status s = mesh_check(in, hi, mi, &det, err);
    if (s) return s;
    if ((s = mesh_positions(in, hi, mi, m, &diag, err))) return s;

    /* Triangles by the input's indices first: a mesh watertight by index
     * (Blender's) needs no weld. Holes then may be seams (glTF splits
     * vertices there): weld by position and match again. */
    m->tri = malloc(sizeof(uint32_t) * 3 * (size_t)nt_in);
    m->fnrm = malloc(sizeof(float) * 3 * (size_t)nt_in);
    twin = malloc(sizeof *twin * 3 * (size_t)nt_in);
    up = malloc(sizeof *up * (size_t)nt_in);
    if (!m->tri || !m->fnrm || !twin || !up)
        MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] (%u triangles)", hi, nt_in);
    const tri_input ti = {in->indices, nt_in, nv, det < 0, 1e-14 * diag * diag};
    double area;
    uint32_t bad = collect_triangles(m, &ti, NULL, &area);
    if (bad != UINT32_MAX)
        MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): triangle %u index %u is out of range [0, %u]", hi, mi,
                  bad / 3, in->indices[bad], nv - 1);
    edge_stats es = {0, 0, 1, 0};
    if (m->nt && !match_edges(m, twin, up, &es))
        MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] edges", hi);
    if (!m->nt || es.boundary || es.nonmanifold) {
        remap = malloc(sizeof *remap * (size_t)nv);
        if (!remap || !weld(m->pos, nv, remap))
            MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] (%u vertices)", hi, nv);
        collect_triangles(m, &ti, remap, &area);
        if (m->nt && !match_edges(m, twin, up, &es))
            MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] edges", hi);
        free(remap), remap = NULL;
    }
    const uint32_t nt = m->nt;
    m->dropped = nt_in - nt;
    if (nt == 0)
        MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): all %u triangles have zero area", hi, mi, nt_in);
    const size_t ne = 3 * (size_t)nt;
    const uint32_t boundary = es.boundary, nonmanifold = es.nonmanifold;
    const int consistent = es.consistent;
    const double boundary_len = es.boundary_len;
    uint32_t shells = 0;
    for (uint32_t t = 0; t < nt; t++) shells += uf_find(up, t) == t;
    m->boundary_edges = boundary;
    m->shells = shells;

    /* Closed? Auto: no non-manifold edges to speak of and holes small
     * beside the surface: a boundary shorter than 1.7 times the square root
     * of the area. Suzanne (1.59: open eye sockets plugged by the eyes), a
     * sculpt with pin holes, a column without its top cap (0.9) are solid;
     * a wall (4), a terrain, a bowl (2.5), a short open tube (1.8) are not.
     * banyan_host_mesh.closed overrides it. */
    if (in->closed == BANYAN_HOST_CLOSED_AUTO)
        m->closed = nonmanifold * 100 <= ne / 3 && boundary_len <= 1.7 * sqrt(area);
    else
        m->closed = in->closed;

    /* Shells wound inside out (negative volume) are turned round, per
     * shell, when the winding is consistent and there are no holes (the
     * volume of an open shell says nothing of its winding). */
    if (m->closed && consistent && boundary == 0) {
        vol = calloc(nt, sizeof *vol);
        if (!vol) MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u]", hi);
        for (uint32_t t = 0; t < nt; t++) {
            const uint32_t *ix = m->tri + 3 * (size_t)t;
            vol[uf_find(up, t)] += v3_dot(vtx(m, ix[0]), v3_cross(vtx(m, ix[1]), vtx(m, ix[2])));
        }
        for (uint32_t t = 0; t < nt; t++)
            if (vol[uf_find(up, t)] < 0) {
                float *f = m->fnrm + 3 * (size_t)t;
                f[0] = -f[0], f[1] = -f[1], f[2] = -f[2];
            }
    }
    m->sign_by_rays = !m->closed ? 0 : !consistent ? 2 : (boundary || nonmanifold || shells > 1) ? 1 : 0;

    m->twin = twin, twin = NULL; /* edge pseudonormals are summed when asked (host_queries.c) */
    /* Holes of a consistently wound solid are capped for the inside test
     * (host_caps.c): its inside is then the winding number's. */
    if (m->sign_by_rays == 1 && boundary && !nonmanifold && !hmesh_build_caps(m))
        MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] hole caps", hi);

    /* Pseudonormals: vertices by angle (edges from their two faces). */
    m->vnrm = calloc(3 * (size_t)nv, sizeof(float));
    if (!m->vnrm) MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] normals", hi);
    vertex_normals(m, nv, nt);
    free(up), up = NULL;
    free(twin), twin = NULL;
    free(vol), vol = NULL;

    return mesh_bvh(dev, m, hi, diag, err);
}

/* Moves the set into its frame (frame.h), picked from all the hosts'
 * bounds; each subtraction is of nearby doubles, so exact or nearly. */
static void set_frame(banyan_hosts *H) {
    uint32_t n = H->n_boxes + H->n_meshes;
    v3 lo, hi;
    frame_empty(&lo, &hi);
    for (uint32_t i = 0; i < n; i++) frame_add(&lo, &hi, H->lo[i]), frame_add(&lo, &hi, H->hi[i]);
    v3 o = H->origin = frame_pick(lo, hi);
    if (o.x == 0 && o.y == 0 && o.z == 0) return;
    for (uint32_t i = 0; i < n; i++) H->lo[i] = v3_sub(H->lo[i], o), H->hi[i] = v3_sub(H->hi[i], o);
    for (uint32_t i = 0; i < H->n_boxes; i++) H->boxes[i].c = v3_sub(H->boxes[i].c, o);
    for (uint32_t i = 0; i < H->n_meshes; i++) {
        host_mesh *m = &H->meshes[i];
        m->origin = v3_sub(m->origin, o), m->lo = v3_sub(m->lo, o), m->hi = v3_sub(m->hi, o);
    }
}

banyan_status banyan_hosts_create(const banyan_box *boxes, uint32_t n_boxes, const banyan_host_mesh *meshes,
                                  uint32_t n_meshes, banyan_hosts **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    uint64_t n = (uint64_t)n_boxes + n_meshes;
    if (n == 0)
        return banyan_fail(err, BANYAN_E_NO_HOSTS, "n_boxes + n_meshes = 0: a host set needs at least one host");
    if (n > BANYAN_MAX_HOSTS)
        return banyan_fail(err, BANYAN_E_RANGE, "n_boxes + n_meshes = %llu must be within [1, %d]",
                           (unsigned long long)n, BANYAN_MAX_HOSTS);
    if (n_boxes && !boxes) return banyan_fail(err, BANYAN_E_INVALID_ARG, "boxes is NULL but n_boxes = %u", n_boxes);
    if (n_meshes && !meshes)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "meshes is NULL but n_meshes = %u", n_meshes);
    uint64_t tris = 0, verts = 0;
    for (uint32_t i = 0; i < n_meshes; i++) {
        if (meshes[i].triangle_count > BANYAN_HOSTS_MAX_TRIANGLES || meshes[i].vertex_count > MAX_VERTICES)
            return banyan_fail(err, BANYAN_E_LIMIT, "hosts[%u] (mesh %u) has %u triangles and %u vertices; a host set "
                               "takes at most %u triangles and %u vertices (decimate it, or use its bounding box)",
                               n_boxes + i, i, meshes[i].triangle_count, meshes[i].vertex_count,
                               BANYAN_HOSTS_MAX_TRIANGLES, MAX_VERTICES);
        tris += meshes[i].triangle_count, verts += meshes[i].vertex_count;
    }
    if (tris > BANYAN_HOSTS_MAX_TRIANGLES)
        return banyan_fail(err, BANYAN_E_LIMIT, "the mesh hosts hold %llu triangles; a host set takes at most %u "
                           "(decimate the host, or use its bounding box)",
                           (unsigned long long)tris, BANYAN_HOSTS_MAX_TRIANGLES);
    if (verts > MAX_VERTICES)
        return banyan_fail(err, BANYAN_E_LIMIT, "the mesh hosts hold %llu vertices; a host set takes at most %u",
                           (unsigned long long)verts, MAX_VERTICES);
    banyan_hosts *H = calloc(1, sizeof *H);
    if (!H) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
    H->boxes = malloc(sizeof(obb) * (n_boxes ? n_boxes : 1));
    H->meshes = calloc(n_meshes ? n_meshes : 1, sizeof(host_mesh));
    H->lo = malloc(sizeof(v3) * n);
    H->hi = malloc(sizeof(v3) * n);
    banyan_status s = BANYAN_OK;
    if (!H->boxes || !H->meshes || !H->lo || !H->hi) {
        s = banyan_fail(err, BANYAN_E_NOMEM, "out of memory");
        goto fail;
    }
    for (uint32_t i = 0; i < n_boxes; i++) {
        if ((s = obb_from_box(&boxes[i], i, &H->boxes[i], err))) goto fail;
        obb_bounds(&H->boxes[i], &H->lo[i], &H->hi[i]);
        H->n_boxes = i + 1;
    }
    if (n_meshes) {
        /* One build thread: the same BVH, so the same answers, every run. */
        RTCDevice dev = rtcNewDevice("threads=1,verbose=0");
        if (!dev) {
            s = banyan_fail(err, BANYAN_E_UNSUPPORTED, "Embree could not start (rtcNewDevice failed)");
            goto fail;
        }
        H->device = dev;
        for (uint32_t i = 0; i < n_meshes; i++) {
            H->n_meshes = i + 1;
            if ((s = mesh_build(dev, &meshes[i], n_boxes + i, i, &H->meshes[i], err))) goto fail;
            H->lo[n_boxes + i] = H->meshes[i].lo;
            H->hi[n_boxes + i] = H->meshes[i].hi;
        }
    }
    set_frame(H);
    *out = H;
    banyan_error_clear(err);
    return BANYAN_OK;
fail:
    banyan_hosts_free(H);
    return s;
}

/* ------------------------------------------------------- public queries */

uint32_t banyan_hosts_count(const banyan_hosts *H) { return H ? H->n_boxes + H->n_meshes : 0; }

banyan_status banyan_hosts_info(const banyan_hosts *H, uint32_t index, banyan_host_info *out, banyan_error *err) {
    if (!H || !out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts or out is NULL");
    uint32_t n = H->n_boxes + H->n_meshes;
    if (index >= n) return banyan_fail(err, BANYAN_E_RANGE, "index = %u must be within [0, %u]", index, n - 1);
    memset(out, 0, sizeof *out);
    out->closed = 1;
    out->shells = 1;
    if (index >= H->n_boxes) {
        const host_mesh *m = &H->meshes[index - H->n_boxes];
        out->kind = 1;
        out->closed = m->closed;
        out->triangle_count = m->nt;
        out->dropped_triangles = m->dropped;
        out->boundary_edges = m->boundary_edges;
        out->shells = m->shells;
    }
    v3 wl = v3_add(H->lo[index], H->origin), wh = v3_add(H->hi[index], H->origin);
    const double lo[3] = {wl.x, wl.y, wl.z};
    const double hi[3] = {wh.x, wh.y, wh.z};
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
    banyan_error_clear(err);
    return BANYAN_OK;
}

static banyan_status check_point(const char *name, const double *p, banyan_error *err) {
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "%s is NULL", name);
    for (int i = 0; i < 3; i++)
        if (!isfinite(p[i]) || fabs(p[i]) > 1e6)
            return banyan_fail(err, BANYAN_E_RANGE, "%s[%d] = %g must be finite, within [-1e6, 1e6] m", name, i, p[i]);
    return BANYAN_OK;
}

static void hit_clear(banyan_host_hit *hit) {
    memset(hit, 0, sizeof *hit);
    hit->host = -1;
}

static void hit_store(banyan_host_hit *hit, int32_t host, uint32_t prim, double dist, v3 point, v3 normal) {
    hit->host = host;
    hit->primitive = prim;
    hit->distance = dist;
    hit->point[0] = point.x, hit->point[1] = point.y, hit->point[2] = point.z;
    hit->normal[0] = normal.x, hit->normal[1] = normal.y, hit->normal[2] = normal.z;
}

/* A hit found in the set's frame, back in the world's. */
static void hit_world(const banyan_hosts *H, banyan_host_hit *hit) {
    if (hit->host < 0) return;
    for (int k = 0; k < 3; k++) hit->point[k] += (&H->origin.x)[k];
}

/* The box face whose plane p lies farthest outside of (or least inside). */
static uint32_t box_face(const obb *o, v3 p) {
    v3 l = obb_to_local(o, p);
    double c[3] = {l.x, l.y, l.z};
    int best = 0;
    double q = fabs(c[0]) - o->h[0];
    for (int k = 1; k < 3; k++)
        if (fabs(c[k]) - o->h[k] > q) q = fabs(c[k]) - o->h[k], best = k;
    return (uint32_t)(2 * best + (c[best] >= 0));
}

/* Nearest over the whole set (least signed distance: the union's). */
static int set_nearest(const banyan_hosts *H, v3 p, double cap, banyan_host_hit *hit) {
    double best = cap;
    int found = 0;
    for (uint32_t i = 0; i < H->n_boxes; i++) {
        const obb *o = &H->boxes[i];
        double d = obb_signed_distance(o, p);
        if (d < best || (!found && d <= cap)) {
            v3 n, s = obb_closest_surface(o, p, &n);
            hit_store(hit, (int32_t)i, box_face(o, p), d, s, n);
            best = d;
            found = 1;
        }
    }
    for (uint32_t i = 0; i < H->n_meshes; i++) {
        const host_mesh *m = &H->meshes[i];
        mesh_near nr;
        double c = found ? fabs(best) : cap;
        if (!found && hosts_far_from(H, H->n_boxes + i, p, c)) continue;
        if (!hmesh_nearest(m, p, c > 0 ? c : 1e-12, &nr)) {
            if (nr.dist < 0 && (!found || nr.dist < best)) { /* deep inside, surface beyond the cap */
                hit_store(hit, (int32_t)(H->n_boxes + i), UINT32_MAX, nr.dist, p, nr.normal);
                best = nr.dist;
                found = 1;
            }
            continue;
        }
        if (nr.dist < best || !found) {
            hit_store(hit, (int32_t)(H->n_boxes + i), nr.prim, nr.dist, nr.point, nr.normal);
            best = nr.dist;
            found = 1;
        }
    }
    return found;
}

banyan_status banyan_hosts_closest(const banyan_hosts *H, const double p[3], double max_distance,
                                   banyan_host_hit *hit, banyan_error *err) {
    if (!H || !hit) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts or hit is NULL");
    hit_clear(hit);
    banyan_status s = check_point("p", p, err);
    if (s) return s;
    if (isnan(max_distance) || !(max_distance > 0))
        return banyan_fail(err, BANYAN_E_RANGE, "max_distance = %g must be > 0 (HUGE_VAL for any)", max_distance);
    set_nearest(H, v3_sub(v3_load(p), H->origin), max_distance, hit);
    hit_world(H, hit);
    banyan_error_clear(err);
    return BANYAN_OK;
}

/* First boundary crossing of o along a + t d, t in (0, tmax]: the entry, or
 * the exit for a start inside. */
static int box_ray(const obb *o, v3 a, v3 d, double tmax, double *t_out, v3 *n_out) {
    v3 la = obb_to_local(o, a), ld = v3_make(v3_dot(d, o->ax[0]), v3_dot(d, o->ax[1]), v3_dot(d, o->ax[2]));
    double A[3] = {la.x, la.y, la.z}, D[3] = {ld.x, ld.y, ld.z};
    double t0 = -HUGE_VAL, t1 = HUGE_VAL;
    int k0 = 0, k1 = 0;
    for (int k = 0; k < 3; k++) {
        if (D[k] == 0) {
            if (fabs(A[k]) > o->h[k]) return 0;
            continue;
        }
        double ta = (-o->h[k] - A[k]) / D[k], tb = (o->h[k] - A[k]) / D[k];
        if (ta > tb) { double x = ta; ta = tb; tb = x; }
        if (ta > t0) t0 = ta, k0 = k;
        if (tb < t1) t1 = tb, k1 = k;
    }
    if (t0 > t1) return 0;
    double t = t0 > 0 ? t0 : t1;
    int k = t0 > 0 ? k0 : k1;
    if (!(t >= 0 && t <= tmax)) return 0;
    *t_out = t;
    double sgn = A[k] + t * D[k] >= 0 ? 1.0 : -1.0;
    *n_out = v3_scale(o->ax[k], sgn);
    return 1;
}

banyan_status banyan_hosts_raycast(const banyan_hosts *H, const double origin[3], const double dir[3], double max_t,
                                   banyan_host_hit *hit, banyan_error *err) {
    if (!H || !hit) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts or hit is NULL");
    hit_clear(hit);
    banyan_status s = check_point("origin", origin, err);
    if (s) return s;
    if (!dir) return banyan_fail(err, BANYAN_E_INVALID_ARG, "dir is NULL");
    v3 a = v3_sub(v3_load(origin), H->origin), d = v3_load(dir);
    if (!v3_finite(d) || !(v3_len(d) > 0))
        return banyan_fail(err, BANYAN_E_RANGE, "dir = (%g, %g, %g) must be finite and not zero", d.x, d.y, d.z);
    if (isnan(max_t) || !(max_t > 0))
        return banyan_fail(err, BANYAN_E_RANGE, "max_t = %g must be > 0", max_t);
    double tmax = fmin(max_t, 4e6 / v3_len(d)); /* nothing lies farther than the world's extent */
    double best = HUGE_VAL;
    for (uint32_t i = 0; i < H->n_boxes; i++) {
        double t;
        v3 n;
        if (box_ray(&H->boxes[i], a, d, tmax, &t, &n) && t < best) {
            best = t;
            hit_store(hit, (int32_t)i, box_face(&H->boxes[i], v3_madd(a, d, t)), t, v3_madd(a, d, t), n);
        }
    }
    for (uint32_t i = 0; i < H->n_meshes; i++) {
        double span = fmin(best, tmax), t;
        v3 n;
        if (hmesh_segment_hit(&H->meshes[i], a, v3_madd(a, d, span), &t, &n) && t * span < best) {
            best = t * span;
            v3 q = v3_madd(a, d, best);
            hit_store(hit, (int32_t)(H->n_boxes + i), 0, best, q, n);
        }
    }
    hit_world(H, hit);
    banyan_error_clear(err);
    return BANYAN_OK;
}

banyan_status banyan_hosts_sweep_sphere(const banyan_hosts *H, const double from[3], const double to[3],
                                        double radius, banyan_host_hit *hit, banyan_error *err) {
    if (!H || !hit) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts or hit is NULL");
    hit_clear(hit);
    banyan_status s = check_point("from", from, err);
    if (!s) s = check_point("to", to, err);
    if (s) return s;
    if (!isfinite(radius) || !(radius > 0) || radius > 1e6)
        return banyan_fail(err, BANYAN_E_RANGE, "radius = %g must be within (0, 1e6] m", radius);
    v3 p = v3_sub(v3_load(from), H->origin), d = v3_sub(v3_sub(v3_load(to), H->origin), p);
    double L = v3_len(d), tol = 1e-9 * (radius + L), best = 1.0;
    int which = -1;
    for (uint32_t i = 0; i < H->n_boxes; i++) { /* sphere tracing on the exact box distance */
        double t = 0;
        for (int it = 0; it < 1000 && t < best; it++) {
            double f = obb_signed_distance(&H->boxes[i], v3_madd(p, d, t)) - radius;
            if (f < tol) {
                if (t < best || which < 0) best = t, which = (int)i;
                break;
            }
            if (!(L > 0)) break;
            t += f / L;
        }
    }
    for (uint32_t i = 0; i < H->n_meshes; i++) {
        /* Touching at the start is a contact at 0 (the generators' sweep
         * lets a sphere pressed against a face slide away). */
        double t = hmesh_distance(&H->meshes[i], p, radius + tol) - radius < tol
                       ? 0.0
                       : hmesh_sweep(&H->meshes[i], p, v3_scale(d, best), radius, tol, NULL) * best;
        if (t < best || (which < 0 && t < 1.0)) best = t, which = (int)(H->n_boxes + i);
    }
    if (which >= 0) {
        banyan_host_hit near;
        hit_clear(&near);
        v3 at = v3_madd(p, d, best);
        set_nearest(H, at, HUGE_VAL, &near);
        hit_store(hit, which, near.primitive, best, v3_load(near.point), v3_load(near.normal));
        hit_world(H, hit);
    }
    banyan_error_clear(err);
    return BANYAN_OK;
}

int32_t banyan_hosts_inside(const banyan_hosts *H, const double p[3]) {
    if (!H || !p) return 0;
    v3 q = v3_sub(v3_load(p), H->origin);
    if (!v3_finite(q)) return 0;
    for (uint32_t i = 0; i < H->n_boxes; i++)
        if (obb_signed_distance(&H->boxes[i], q) < 0) return 1;
    for (uint32_t i = 0; i < H->n_meshes; i++)
        if (hmesh_inside(&H->meshes[i], q)) return 1;
    return 0;
}

size_t banyan_sizeof_host_mesh(void) { return sizeof(banyan_host_mesh); }
size_t banyan_sizeof_host_hit(void) { return sizeof(banyan_host_hit); }
size_t banyan_sizeof_host_info(void) { return sizeof(banyan_host_info); }

/* lod.c - levels of detail (banyan/lod.h; docs/lod.md).
 *
 * A coarser copy of any generator's mesh, part by part (so an avenue or
 * an instanced avenue is reduced tree by tree, variant by variant):
 *   - wood (opaque materials) goes through meshoptimizer's edge-collapse
 *     simplifier (simplify_meshopt.cpp) toward ratio * its triangles;
 *   - leaves (alpha-tested materials, or wind_flutter) are not decimated,
 *     which would punch holes in the cards: whole leaves (connected sets
 *     of vertices) are kept at random, a share `ratio` of them, and each
 *     survivor grows about its petiole base by sqrt(total area / kept
 *     area), so the crown keeps its leaf area and its density from afar
 *     (the thinning of SpeedTree-style leaf LODs);
 *   - with `billboard`, vertical cards and a top card carrying the
 *     library's own pictures of the plant (billboard.c).
 * Everything else (materials, groups, attributes, skeleton, origin,
 * images, instances) is carried over; the choice of leaves is a PCG32
 * stream of (seed, part), so the output is the same bytes on every run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/error.h"
#include "base/finite.h"
#include "base/rng.h"
#include "lod_internal.h"

/* Groups are trees or variants (an avenue has at most a few ten thousand). */
#define LOD_MAX_GROUP (1u << 24)

void banyan_lod_params_init(banyan_lod_params *p) {
    if (!p) return;
    memset(p, 0, sizeof *p);
    p->ratio = 0.5;
    p->billboard = 0;
    p->billboard_planes = 3;
    p->billboard_size = 256;
    p->seed = 1;
}

size_t banyan_sizeof_lod_params(void) { return sizeof(banyan_lod_params); }

static banyan_status check_params(const banyan_lod_params *p, banyan_error *err) {
    banyan_status s;
    if ((s = banyan_check_range(err, "ratio", p->ratio, 0.001, 1.0, ""))) return s;
    if ((s = banyan_check_int(err, "billboard", p->billboard, 0, 1))) return s;
    if ((s = banyan_check_int(err, "billboard_planes", p->billboard_planes, 2, 8))) return s;
    if ((s = banyan_check_int(err, "billboard_size", p->billboard_size, 32, 4096))) return s;
    if (p->billboard_size & (p->billboard_size - 1))
        return banyan_fail(err, BANYAN_E_RANGE, "billboard_size = %d must be a power of two within [32, 4096]",
                           p->billboard_size);
    if (p->reserved != 0)
        return banyan_fail(err, BANYAN_E_RANGE, "reserved = %d must be 0 (banyan_lod_params_init)", p->reserved);
    return BANYAN_OK;
}

/* The mesh as banyan.h describes it: the arrays there, parts covering the
 * vertices and indices in order, each part's indices inside its own
 * vertices, finite positions, materials and images that exist. */
static banyan_status check_mesh(const banyan_mesh *m, banyan_error *err) {
    if (!m) return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh is NULL");
    if (m->vertex_count == 0 || m->index_count == 0)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                           "mesh is empty (vertex_count = %u, index_count = %u; both must be at least 1)",
                           m->vertex_count, m->index_count);
    if (m->index_count % 3)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh index_count = %u must be a multiple of 3",
                           m->index_count);
    if (!m->positions || !m->indices)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh positions and indices must not be NULL");
    if (m->material_count < 1 || !m->materials)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh material_count = %u must be at least 1 (materials set)",
                           m->material_count);
    if (m->part_count < 1 || !m->parts)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh part_count = %u must be at least 1 (parts set)",
                           m->part_count);
    if (m->attribute_count && !m->attributes)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh attributes is NULL with attribute_count = %u",
                           m->attribute_count);
    for (uint32_t a = 0; a < m->attribute_count; a++)
        if (!m->attributes[a].data)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh attributes[%u].data is NULL", a);
    if (m->image_count && !m->images)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh images is NULL with image_count = %u", m->image_count);
    for (uint32_t i = 0; i < m->image_count; i++) {
        const banyan_image *im = &m->images[i];
        if (!im->pixels || !im->width || !im->height || (im->channels != 3 && im->channels != 4))
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                               "mesh images[%u] is malformed (%ux%u, %u channels; pixels must be set, channels 3 or 4)",
                               i, im->width, im->height, im->channels);
    }
    if (m->instance_count && !m->instances)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh instances is NULL with instance_count = %u",
                           m->instance_count);
    for (uint32_t i = 0; i < m->material_count; i++) {
        int32_t im = m->materials[i].image;
        if (im < 0 || (uint32_t)im > m->image_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh materials[%u].image = %d is out of range [0, %u]", i,
                               im, m->image_count);
    }
    uint32_t v_at = 0, i_at = 0, max_group = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (pt->vertex_offset != v_at || pt->index_offset != i_at || pt->index_count % 3 ||
            (uint64_t)pt->vertex_offset + pt->vertex_count > m->vertex_count ||
            (uint64_t)pt->index_offset + pt->index_count > m->index_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG,
                               "mesh parts[%u] (vertices %u + %u, indices %u + %u) does not continue the parts before "
                               "it within the mesh's %u vertices and %u indices",
                               q, pt->vertex_offset, pt->vertex_count, pt->index_offset, pt->index_count,
                               m->vertex_count, m->index_count);
        if (pt->group >= LOD_MAX_GROUP)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh parts[%u].group = %u must be below %u", q, pt->group,
                               LOD_MAX_GROUP);
        if (pt->material >= m->material_count)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh parts[%u].material = %u is out of range [0, %u)", q,
                               pt->material, m->material_count);
        for (uint32_t k = pt->index_offset; k < pt->index_offset + pt->index_count; k++)
            if (m->indices[k] - pt->vertex_offset >= pt->vertex_count) /* unsigned: below wraps high */
                return banyan_fail(err, BANYAN_E_INVALID_ARG,
                                   "mesh indices[%u] = %u is outside parts[%u]'s vertices [%u, %u)", k, m->indices[k],
                                   q, pt->vertex_offset, pt->vertex_offset + pt->vertex_count);
        v_at += pt->vertex_count;
        i_at += pt->index_count;
        if (pt->group > max_group) max_group = pt->group;
    }
    if (v_at != m->vertex_count || i_at != m->index_count)
        return banyan_fail(err, BANYAN_E_INVALID_ARG,
                           "mesh parts cover %u vertices and %u indices, not all %u and %u", v_at, i_at,
                           m->vertex_count, m->index_count);
    if (!floats_finite(m->positions, 3 * (size_t)m->vertex_count))
        for (uint64_t i = 0; i < 3 * (uint64_t)m->vertex_count; i++)
            if (!isfinite(m->positions[i]))
                return banyan_fail(err, BANYAN_E_RANGE, "mesh positions[%llu] = %g is not finite",
                                   (unsigned long long)i, (double)m->positions[i]);
    for (uint32_t i = 0; i < m->instance_count; i++) {
        const banyan_instance *in = &m->instances[i];
        if (in->variant > max_group)
            return banyan_fail(err, BANYAN_E_INVALID_ARG, "mesh instances[%u].variant = %u names no group [0, %u]", i,
                               in->variant, max_group);
        if (!(in->scale > 0) || !isfinite(in->scale) || !isfinite(in->rotation_z) || !isfinite(in->translation[0]) ||
            !isfinite(in->translation[1]) || !isfinite(in->translation[2]))
            return banyan_fail(err, BANYAN_E_RANGE, "mesh instances[%u] is not finite or its scale = %g is not > 0", i,
                               (double)in->scale);
    }
    return BANYAN_OK;
}

/* Leaves: a part drawn alpha-tested, or fluttering in the wind. */
static int part_is_leaves(const banyan_mesh *m, const banyan_part *pt, const float *flutter) {
    if (m->materials[pt->material].alpha_cutoff > 0) return 1;
    if (!flutter || !pt->vertex_count) return 0;
    double sum = 0;
    for (uint32_t v = pt->vertex_offset; v < pt->vertex_offset + pt->vertex_count; v++) sum += flutter[v];
    return sum > 0.5 * pt->vertex_count;
}

/* What one part keeps: part-local indices into its own vertices, and, for
 * thinned leaves, moved positions (3 * vertex_count, or NULL). */
typedef struct part_out {
    uint32_t *idx;
    uint32_t ni;
    float *pos;
} part_out;

static uint32_t uf_find(uint32_t *parent, uint32_t v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

static double tri_area(const float *P, uint32_t a, uint32_t b, uint32_t c) {
    const float *A = P + 3 * (size_t)a, *B = P + 3 * (size_t)b, *C = P + 3 * (size_t)c;
    double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

/* The growth s >= 1 of the kept leaves (keep[c]) at which their areas,
 * each grown by min(s, cap[c])^2, add up to `total`, solved directly:
 * with the leaves whose cap is below s held at their cap (area B) and the
 * others' area A, s = sqrt((total - B) / A); capping the leaves below that
 * s only raises it, so a few passes over the still uncapped leaves settle
 * it. Where the caps bind everywhere, s is the largest cap (every leaf at
 * its own); s stays within 1e4 (a leaf needs no more). */
static double lod_leaf_growth(const double *karea, const double *cap, const unsigned char *keep, uint32_t n,
                              double total) {
    double a = 0, b = 0, cmax = 1;
    uint32_t m = 0;
    uint32_t *live = malloc(sizeof(uint32_t) * (n ? n : 1));
    for (uint32_t c = 0; c < n; c++)
        if (keep[c]) {
            a += karea[c];
            if (live) live[m++] = c;
        }
    if (!(a > 0) || !(total > a)) {
        free(live);
        return 1.0;
    }
    double s = sqrt(total / a);
    if (!live) return s < 1e4 ? s : 1e4; /* no room for the list: the uncapped growth */
    for (;;) {
        uint32_t w = 0, capped = 0;
        for (uint32_t i = 0; i < m; i++) {
            uint32_t c = live[i];
            if (cap[c] < s) {
                b += karea[c] * cap[c] * cap[c];
                a -= karea[c];
                cmax = cap[c] > cmax ? cap[c] : cmax;
                capped++;
            } else {
                live[w++] = c;
            }
        }
        m = w;
        if (!capped) break;
        if (!m || !(a > 0) || !(total > b)) {
            s = m ? s : cmax;
            break;
        }
        s = sqrt((total - b) / a);
    }
    free(live);
    return s < 1 ? 1 : s > 1e4 ? 1e4 : s;
}

/* Thins one leaf part: whole leaves kept at random, survivors grown about
 * their petiole base so the part's leaf area stays. */
static int thin_leaves(const banyan_mesh *m, uint32_t q, const banyan_lod_params *p, const double blo[3],
                       const double bhi[3], part_out *po) {
    const banyan_part *pt = &m->parts[q];
    uint32_t nv = pt->vertex_count, ni = pt->index_count, vo = pt->vertex_offset;
    const float *P = m->positions + 3 * (size_t)vo;
    const uint32_t *I = m->indices + pt->index_offset;
    const float *px = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_X);
    const float *py = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Y);
    const float *pz = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_PIVOT_Z);
    int ok = 0;
    uint32_t *parent = malloc(sizeof(uint32_t) * (nv ? nv : 1)), *comp = malloc(sizeof(uint32_t) * (nv ? nv : 1));
    double *area = calloc(nv ? nv : 1, sizeof(double)), *piv = calloc(3 * (size_t)(nv ? nv : 1), sizeof(double));
    float *minv = malloc(sizeof(float) * (nv ? nv : 1));
    uint32_t *order = malloc(sizeof(uint32_t) * (nv ? nv : 1)), *npiv = calloc(nv ? nv : 1, sizeof(uint32_t));
    unsigned char *keep = calloc(nv ? nv : 1, 1);
    po->idx = malloc(sizeof(uint32_t) * (ni ? ni : 1));
    po->pos = malloc(3 * sizeof(float) * (nv ? nv : 1));
    if (!parent || !comp || !area || !piv || !minv || !order || !npiv || !keep || !po->idx || !po->pos) goto done;
    for (uint32_t v = 0; v < nv; v++) parent[v] = v;
    for (uint32_t k = 0; k + 2 < ni; k += 3) {
        uint32_t a = uf_find(parent, I[k] - vo);
        for (int j = 1; j < 3; j++) {
            uint32_t b = uf_find(parent, I[k + j] - vo);
            if (a != b) {
                if (b < a) {
                    uint32_t t = a;
                    a = b;
                    b = t;
                }
                parent[b] = a; /* the lowest vertex is the root: numbering does not depend on the order */
            }
        }
    }
    /* Leaves numbered by their first vertex; only sets with a triangle. */
    uint32_t n = 0;
    for (uint32_t v = 0; v < nv; v++) comp[v] = UINT32_MAX;
    for (uint32_t k = 0; k + 2 < ni; k += 3) {
        uint32_t r = uf_find(parent, I[k] - vo);
        area[r] += tri_area(P, I[k] - vo, I[k + 1] - vo, I[k + 2] - vo);
        comp[r] = 0;
    }
    for (uint32_t v = 0; v < nv; v++)
        if (parent[v] == v && comp[v] == 0) {
            comp[v] = n;
            area[n] = area[v]; /* n <= v: compacting in place */
            minv[n] = INFINITY;
            n++;
        }
    for (uint32_t v = 0; v < nv; v++) comp[v] = comp[uf_find(parent, v)];
    /* Petiole base: the wind pivot when the mesh has one; else the card's
     * lowest-v vertices (atlas cells put the petiole at the cell's bottom),
     * or the leaf's centre without uvs. */
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t c = comp[v];
        if (c == UINT32_MAX) continue;
        float vv = m->uvs && !px ? m->uvs[2 * ((size_t)vo + v) + 1] : 0;
        if (vv < minv[c] - 1e-6f) {
            minv[c] = vv;
            npiv[c] = 0;
            piv[3 * (size_t)c] = piv[3 * (size_t)c + 1] = piv[3 * (size_t)c + 2] = 0;
        }
        if (vv <= minv[c] + 1e-6f) {
            double q3[3] = {P[3 * (size_t)v], P[3 * (size_t)v + 1], P[3 * (size_t)v + 2]};
            if (px && py && pz) q3[0] = px[vo + v], q3[1] = py[vo + v], q3[2] = pz[vo + v];
            for (int j = 0; j < 3; j++) piv[3 * (size_t)c + j] += q3[j];
            npiv[c]++;
        }
    }
    uint32_t k_keep = n;
    if (p->ratio < 1 && n) {
        double want = floor(p->ratio * n + 0.5);
        k_keep = want < 1 ? 1 : (uint32_t)want;
    }
    pcg32 r;
    pcg32_seed(&r, p->seed, 0x1eaf10dULL + q);
    for (uint32_t i = 0; i < n; i++) order[i] = i;
    /* The leaves that hold the part's lowest and highest vertex on each
     * axis are kept first (a lone leaf far out sets the bounds an engine
     * culls by, and the levels keep them); then the rest at random. */
    uint32_t ext[6] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX}; /* lo x, hi x, lo y, ... */
    for (uint32_t v = 0; v < nv; v++) {
        if (comp[v] == UINT32_MAX) continue;
        for (int j = 0; j < 3; j++) {
            const float x = P[3 * (size_t)v + j];
            if (ext[2 * j] == UINT32_MAX || x < P[3 * (size_t)ext[2 * j] + j]) ext[2 * j] = v;
            if (ext[2 * j + 1] == UINT32_MAX || x > P[3 * (size_t)ext[2 * j + 1] + j]) ext[2 * j + 1] = v;
        }
    }
    uint32_t fixed = 0;
    for (int e = 0; e < 6 && n; e++) {
        uint32_t c = comp[ext[e]];
        if (keep[c] || fixed >= k_keep) continue;
        for (uint32_t i = fixed; i < n; i++) /* c's place in order: swap it to the front */
            if (order[i] == c) {
                order[i] = order[fixed];
                order[fixed++] = c;
                break;
            }
        keep[c] = 1;
    }
    for (uint32_t i = fixed; i < k_keep && i < n; i++) { /* partial Fisher-Yates: the first k_keep are kept */
        uint32_t j = i + rng_below(&r, n - i), t = order[i];
        order[i] = order[j];
        order[j] = t;
        keep[order[i]] = 1;
    }
    double total = 0, kept = 0;
    for (uint32_t c = 0; c < n; c++) {
        total += area[c];
        if (keep[c]) kept += area[c];
    }
    for (uint32_t c = 0; c < n; c++)
        for (int j = 0; j < 3; j++) piv[3 * (size_t)c + j] /= npiv[c] ? npiv[c] : 1;
    /* A survivor grows by s, but never out of the plant's bounds (a leaf
     * at the crown's rim, an ivy leaf off its wall): cap[c] is the most it
     * may grow; s is then found so that the kept area, each leaf grown by
     * min(s, cap), matches the whole part's. */
    double *cap = area; /* reused: per leaf, kept leaves' caps (the areas are summed already) */
    double *karea = malloc(sizeof(double) * (n ? n : 1));
    if (!karea) goto done;
    for (uint32_t c = 0; c < n; c++) karea[c] = area[c], cap[c] = keep[c] ? 1e9 : 1;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t c = comp[v];
        if (c == UINT32_MAX || !keep[c]) continue;
        for (int j = 0; j < 3; j++) {
            double o = piv[3 * (size_t)c + j], d = P[3 * (size_t)v + j] - o, room = d > 0 ? bhi[j] - o : blo[j] - o;
            if (fabs(d) > 1e-12) {
                double g = room / d; /* NaN (a hostile pivot) reads as 1, as fmax(1, NaN) */
                g = g > 1.0 ? g : 1.0;
                cap[c] = g < cap[c] ? g : cap[c];
            }
        }
    }
    double s_hi = lod_leaf_growth(karea, cap, keep, n, total);
    free(karea);
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t c = comp[v];
        double sc = c != UINT32_MAX && keep[c] ? fmin(s_hi, cap[c]) : 1.0;
        for (int j = 0; j < 3; j++) {
            double x = P[3 * (size_t)v + j];
            if (sc != 1.0) {
                double o = piv[3 * (size_t)c + j];
                x = o + sc * (x - o);
            }
            po->pos[3 * (size_t)v + j] = (float)x;
        }
    }
    po->ni = 0;
    for (uint32_t k = 0; k + 2 < ni; k += 3)
        if (keep[comp[I[k] - vo]])
            for (int j = 0; j < 3; j++) po->idx[po->ni++] = I[k + j] - vo;
    ok = 1;
done:
    free(parent); free(comp); free(area); free(piv); free(minv); free(order); free(npiv); free(keep);
    return ok ? 0 : -1;
}

static int reduce_wood(const banyan_mesh *m, const banyan_part *pt, double ratio, part_out *po) {
    uint32_t nv = pt->vertex_count, ni = pt->index_count, vo = pt->vertex_offset;
    uint32_t *local = malloc(sizeof(uint32_t) * (ni ? ni : 1));
    if (!local) return -1;
    for (uint32_t k = 0; k < ni; k++) local[k] = m->indices[pt->index_offset + k] - vo;
    if (ratio >= 1 || ni < 3) {
        po->idx = local;
        po->ni = ni;
        return 0;
    }
    double want = floor(ratio * (ni / 3) + 0.5);
    uint32_t target = want < 1 ? 1 : (uint32_t)want;
    int used = 0;
    int rc = lod_simplify_part(m->positions + 3 * (size_t)vo, m->normals ? m->normals + 3 * (size_t)vo : NULL,
                               m->uvs ? m->uvs + 2 * (size_t)vo : NULL, nv, local, ni, target, &po->idx, &po->ni,
                               &used);
    free(local);
    return rc;
}

banyan_status lod_copy_common(const banyan_mesh *m, banyan_mesh *o, int materials_images) {
    memcpy(o->origin, m->origin, sizeof o->origin);
    if (materials_images) {
    o->material_count = m->material_count;
    o->materials = malloc(sizeof(banyan_material) * m->material_count);
    if (!o->materials) return BANYAN_E_NOMEM;
    memcpy(o->materials, m->materials, sizeof(banyan_material) * m->material_count);
    }
    if (m->skel_point_count && m->skel_points) {
        size_t ns = m->skel_point_count;
        o->skel_points = malloc(3 * sizeof(float) * ns);
        o->skel_radius = malloc(sizeof(float) * ns);
        o->skel_tag = malloc(sizeof(int32_t) * ns);
        if (!o->skel_points || !o->skel_radius || !o->skel_tag) return BANYAN_E_NOMEM;
        memcpy(o->skel_points, m->skel_points, 3 * sizeof(float) * ns);
        if (m->skel_radius) memcpy(o->skel_radius, m->skel_radius, sizeof(float) * ns);
        else memset(o->skel_radius, 0, sizeof(float) * ns);
        if (m->skel_tag) memcpy(o->skel_tag, m->skel_tag, sizeof(int32_t) * ns);
        else memset(o->skel_tag, 0, sizeof(int32_t) * ns);
        o->skel_point_count = m->skel_point_count;
        if (m->skel_edge_count && m->skel_edges) {
            o->skel_edges = malloc(2 * sizeof(uint32_t) * m->skel_edge_count);
            if (!o->skel_edges) return BANYAN_E_NOMEM;
            memcpy(o->skel_edges, m->skel_edges, 2 * sizeof(uint32_t) * m->skel_edge_count);
            o->skel_edge_count = m->skel_edge_count;
        }
    }
    if (materials_images && m->image_count) {
        o->images = calloc(m->image_count, sizeof(banyan_image));
        if (!o->images) return BANYAN_E_NOMEM;
        o->image_count = m->image_count;
        for (uint32_t i = 0; i < m->image_count; i++) {
            const banyan_image *a = &m->images[i];
            size_t bytes = (size_t)a->width * a->height * a->channels;
            o->images[i] = *a;
            o->images[i].pixels = malloc(bytes);
            if (!o->images[i].pixels) return BANYAN_E_NOMEM;
            memcpy(o->images[i].pixels, a->pixels, bytes);
        }
    }
    if (m->instance_count) {
        o->instances = malloc(sizeof(banyan_instance) * m->instance_count);
        if (!o->instances) return BANYAN_E_NOMEM;
        memcpy(o->instances, m->instances, sizeof(banyan_instance) * m->instance_count);
        o->instance_count = m->instance_count;
    }
    return BANYAN_OK;
}

/* Reduced copy: each part's kept vertices in their old order, then its
 * kept triangles renumbered. */
static banyan_status lod_reduce(const banyan_mesh *m, const banyan_lod_params *p, prog *pg, banyan_mesh **out,
                                banyan_error *err) {
    const float *flutter = banyan_mesh_attribute(m, BANYAN_ATTR_WIND_FLUTTER);
    banyan_status st = BANYAN_E_NOMEM;
    part_out *po = calloc(m->part_count, sizeof(part_out));
    uint32_t *remap = malloc(sizeof(uint32_t) * m->vertex_count);
    banyan_mesh *o = calloc(1, sizeof *o);
    if (!po || !remap || !o) goto fail;
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m->vertex_count; v++)
        for (int j = 0; j < 3; j++) { /* finite (check_mesh): plain compares give fmin's and fmax's values */
            double x = m->positions[3 * (size_t)v + j];
            blo[j] = x < blo[j] ? x : blo[j];
            bhi[j] = x > bhi[j] ? x : bhi[j];
        }
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        if (prog_at(pg, 0.9 * q / m->part_count)) { /* between parts: meshoptimizer cannot be stopped inside one */
            st = BANYAN_E_LIMIT;
            goto fail;
        }
        int rc = part_is_leaves(m, pt, flutter) ? thin_leaves(m, q, p, blo, bhi, &po[q])
                                                : reduce_wood(m, pt, p->ratio, &po[q]);
        if (rc) goto fail;
    }
    if (prog_at(pg, 0.9)) {
        st = BANYAN_E_LIMIT;
        goto fail;
    }
    /* Count what stays. */
    uint64_t nv = 0, ni = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        for (uint32_t v = 0; v < pt->vertex_count; v++) remap[pt->vertex_offset + v] = UINT32_MAX;
        for (uint32_t k = 0; k < po[q].ni; k++) remap[pt->vertex_offset + po[q].idx[k]] = 0;
        for (uint32_t v = 0; v < pt->vertex_count; v++)
            if (remap[pt->vertex_offset + v] == 0) remap[pt->vertex_offset + v] = (uint32_t)nv++;
        ni += po[q].ni;
    }
    o->vertex_count = (uint32_t)nv;
    o->index_count = (uint32_t)ni;
    size_t nvs = nv ? nv : 1;
    o->positions = malloc(3 * sizeof(float) * nvs);
    o->normals = m->normals ? malloc(3 * sizeof(float) * nvs) : NULL;
    o->uvs = m->uvs ? malloc(2 * sizeof(float) * nvs) : NULL;
    o->colors = m->colors ? malloc(4 * sizeof(float) * nvs) : NULL;
    o->indices = malloc(sizeof(uint32_t) * (ni ? ni : 1));
    o->parts = calloc(m->part_count, sizeof(banyan_part));
    if (!o->positions || (m->normals && !o->normals) || (m->uvs && !o->uvs) || (m->colors && !o->colors) ||
        !o->indices || !o->parts)
        goto fail;
    o->part_count = m->part_count;
    if (m->attribute_count) {
        o->attributes = calloc(m->attribute_count, sizeof(banyan_attribute));
        if (!o->attributes) goto fail;
        o->attribute_count = m->attribute_count;
        for (uint32_t a = 0; a < m->attribute_count; a++) {
            memcpy(o->attributes[a].name, m->attributes[a].name, BANYAN_NAME_MAX);
            if (!(o->attributes[a].data = malloc(sizeof(float) * nvs))) goto fail;
        }
    }
    uint32_t at_i = 0;
    for (uint32_t q = 0; q < m->part_count; q++) {
        const banyan_part *pt = &m->parts[q];
        banyan_part *op = &o->parts[q];
        *op = *pt;
        op->vertex_offset = UINT32_MAX;
        op->vertex_count = 0;
        for (uint32_t v = 0; v < pt->vertex_count; v++) {
            uint32_t src = pt->vertex_offset + v, dst = remap[src];
            if (dst == UINT32_MAX) continue;
            if (op->vertex_offset == UINT32_MAX) op->vertex_offset = dst;
            op->vertex_count++;
            const float *P = po[q].pos ? po[q].pos + 3 * (size_t)v : m->positions + 3 * (size_t)src;
            memcpy(o->positions + 3 * (size_t)dst, P, 3 * sizeof(float));
            if (o->normals) memcpy(o->normals + 3 * (size_t)dst, m->normals + 3 * (size_t)src, 3 * sizeof(float));
            if (o->uvs) memcpy(o->uvs + 2 * (size_t)dst, m->uvs + 2 * (size_t)src, 2 * sizeof(float));
            if (o->colors) memcpy(o->colors + 4 * (size_t)dst, m->colors + 4 * (size_t)src, 4 * sizeof(float));
            for (uint32_t a = 0; a < m->attribute_count; a++) o->attributes[a].data[dst] = m->attributes[a].data[src];
        }
        if (op->vertex_offset == UINT32_MAX) { /* an emptied part stays, at the running offset */
            op->vertex_offset = q ? o->parts[q - 1].vertex_offset + o->parts[q - 1].vertex_count : 0;
        }
        op->index_offset = at_i;
        op->index_count = po[q].ni;
        for (uint32_t k = 0; k < po[q].ni; k++) o->indices[at_i++] = remap[pt->vertex_offset + po[q].idx[k]];
    }
    if ((st = lod_copy_common(m, o, 1))) goto fail;
    for (uint32_t q = 0; q < m->part_count; q++) free(po[q].idx), free(po[q].pos);
    free(po);
    free(remap);
    *out = o;
    banyan_error_clear(err);
    return BANYAN_OK;
fail:
    if (po)
        for (uint32_t q = 0; q < m->part_count; q++) free(po[q].idx), free(po[q].pos);
    free(po);
    free(remap);
    banyan_mesh_free(o);
    if (st == BANYAN_E_LIMIT) return prog_fail(pg, err, "the level of detail");
    return banyan_fail(err, st ? st : BANYAN_E_NOMEM, "out of memory making a level of detail of %u vertices",
                       m->vertex_count);
}

banyan_status banyan_mesh_lod(const banyan_mesh *mesh, const banyan_lod_params *p, banyan_mesh **out,
                              banyan_error *err) {
    return banyan_mesh_lod_budget(mesh, p, NULL, out, err);
}

banyan_status banyan_mesh_lod_budget(const banyan_mesh *mesh, const banyan_lod_params *p, const banyan_budget *budget,
                                     banyan_mesh **out, banyan_error *err) {
    BANYAN_CHECK_OUT(out, err);
    banyan_lod_params defaults;
    if (!p) {
        banyan_lod_params_init(&defaults);
        p = &defaults;
    }
    banyan_status s;
    if ((s = check_params(p, err))) return s;
    if ((s = check_mesh(mesh, err))) return s;
    prog g;
    if ((s = prog_budget_from(&g, budget, err))) return s;
    return p->billboard ? lod_billboard(mesh, p, &g, out, err) : lod_reduce(mesh, p, &g, out, err);
}

/* ivy_look.h - the look measures on a grown ivy and its mesh
 * (docs/ivy.md, "How the look is measured"): the stem architecture seen
 * on the wall's face, and the leaf blades (connected components of the
 * leaf part, in the order mesh.c emits them, each with the petiole that
 * carries it from its bud). */
#ifndef BANYAN_IVY_LOOK_H
#define BANYAN_IVY_LOOK_H

#include <stdio.h>
#include <stdlib.h>

#include "ivy/ivy_internal.h"
#include "test_files.h"

/* The ivy preset presets/<name>.json on the defaults: params and its
 * boxes (at most cap). */
static inline banyan_status ivy_look_preset(const char *name, banyan_ivy_params *p, banyan_box *hosts, uint32_t cap,
                                            uint32_t *n_hosts, banyan_error *err) {
    char path[1024];
    snprintf(path, sizeof path, "%s/presets/%s.json", BANYAN_SOURCE_DIR, name);
    banyan_ivy_params_init(p);
    return test_load_preset(BANYAN_GEN_IVY, p, path, hosts, cap, n_hosts, err);
}

/* ivy_wall's params into p and its boxes as a host set (NULL, the
 * library's message printed, when the preset cannot be read). */
static inline banyan_hosts *ivy_look_wall(banyan_ivy_params *p) {
    banyan_box boxes[8];
    uint32_t n = 0;
    banyan_error err = {0, ""};
    banyan_hosts *h = NULL;
    if (ivy_look_preset("ivy_wall", p, boxes, 8, &n, &err) == BANYAN_OK &&
        banyan_hosts_create(boxes, n, NULL, 0, &h, &err) == BANYAN_OK)
        return h;
    fprintf(stderr, "ivy_look_wall: %s\n", err.message);
    return NULL;
}

/* The plant of p grown p->steps steps on hosts (banyan_ivy_create, then
 * banyan_ivy_step); NULL, the library's message printed, on failure. */
static inline banyan_ivy *ivy_look_grow(const banyan_ivy_params *p, const banyan_hosts *hosts) {
    banyan_ivy *iv = NULL;
    banyan_error err = {0, ""};
    if (banyan_ivy_create(p, hosts, &iv, &err) == BANYAN_OK && banyan_ivy_step(iv, p->steps, &err) == BANYAN_OK)
        return iv;
    fprintf(stderr, "ivy_look_grow: %s\n", err.message);
    banyan_ivy_free(iv);
    return NULL;
}

#define IVY_LOOK_PETIOLE_VERTS 6 /* 3 sides x 2 rings, the last part-0 vertices, one per blade (mesh.c) */

/* Stem length of the attached internodes on the faces whose outward normal
 * is within 25 deg of `face_n` (an internode belongs to its end bud's
 * nearest face), and the parts of it within 15 and 30 deg of vertical
 * (up or down), the internode seen along that face. */
typedef struct ivy_stem_angles {
    double length, within15, within30;
} ivy_stem_angles;

static inline ivy_stem_angles ivy_look_stem_angles(const banyan_ivy *iv, v3 face_n) {
    ivy_stem_angles a = {0, 0, 0};
    const double c15 = cos(15.0 * BANYAN_PI / 180), c30 = cos(30.0 * BANYAN_PI / 180);
    for (int32_t i = 0; i < iv->n; i++) {
        const ivy_bud *b = &iv->buds[i];
        if (b->parent < 0 || !b->attached) continue;
        ivy_near nr = ivy_nearest_any(iv, b->P);
        if ((uint32_t)nr.host == iv->n_given || v3_dot(nr.normal, face_n) < 0.906) continue;
        v3 d = v3_sub(b->P, iv->buds[b->parent].P);
        d = v3_sub(d, v3_scale(nr.normal, v3_dot(d, nr.normal)));
        double len = v3_len(d);
        if (!(len > 1e-9)) continue;
        double c = fabs(d.z) / len;
        a.length += len;
        if (c >= c15) a.within15 += len;
        if (c >= c30) a.within30 += len;
    }
    return a;
}

/* One leaf blade. */
typedef struct ivy_blade {
    uint32_t first, count; /* its vertices (consecutive) */
    double area;           /* m^2 */
    v3 centre;             /* mean of its vertices */
    v3 normal;             /* area-weighted, from positions; unit */
    double size;           /* largest vertex-to-vertex distance */
    v3 base;               /* its petiole's first ring centre: the bud it grows from */
} ivy_blade;

static inline uint32_t ivy_look_find(uint32_t *up, uint32_t a) {
    while (up[a] != a) a = up[a] = up[up[a]];
    return a;
}

static inline v3 ivy_look_vert(const banyan_mesh *m, uint32_t v) {
    return v3_make(m->positions[3 * v], m->positions[3 * v + 1], m->positions[3 * v + 2]);
}

/* The blades of an ivy mesh (parts: 0 stems and petioles, 1 blades), in
 * emission order; *n their count. NULL (and *n = 0) without a leaf part
 * or memory. The caller frees. */
static inline ivy_blade *ivy_look_blades(const banyan_mesh *m, uint32_t *n) {
    *n = 0;
    if (m->part_count < 2) return NULL;
    const banyan_part *lp = &m->parts[1], *sp = &m->parts[0];
    const uint32_t v0 = lp->vertex_offset, nv = lp->vertex_count;
    uint32_t *up = malloc(sizeof(uint32_t) * (nv ? nv : 1));
    v3 *nsum = calloc(nv ? nv : 1, sizeof(v3));
    double *area = calloc(nv ? nv : 1, sizeof(double));
    ivy_blade *bl = malloc(sizeof(ivy_blade) * (nv ? nv : 1));
    if (!up || !nsum || !area || !bl) {
        free(up), free(nsum), free(area), free(bl);
        return NULL;
    }
    for (uint32_t k = 0; k < nv; k++) up[k] = k;
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3)
        for (int e = 1; e < 3; e++) {
            uint32_t a = ivy_look_find(up, m->indices[t] - v0), b = ivy_look_find(up, m->indices[t + e] - v0);
            if (a != b) up[a] = b;
        }
    for (uint32_t t = lp->index_offset; t + 2 < lp->index_offset + lp->index_count; t += 3) {
        v3 a = ivy_look_vert(m, m->indices[t]), b = ivy_look_vert(m, m->indices[t + 1]), c = ivy_look_vert(m, m->indices[t + 2]);
        uint32_t r = ivy_look_find(up, m->indices[t] - v0);
        v3 x = v3_cross(v3_sub(b, a), v3_sub(c, a));
        nsum[r] = v3_add(nsum[r], x);
        area[r] += 0.5 * v3_len(x);
    }
    /* A blade's vertices are consecutive: walk runs of one root. */
    uint32_t nb = 0;
    for (uint32_t s = 0; s < nv;) {
        uint32_t r = ivy_look_find(up, s), e = s;
        while (e < nv && ivy_look_find(up, e) == r) e++;
        ivy_blade *b = &bl[nb++];
        b->first = v0 + s;
        b->count = e - s;
        b->area = area[r];
        b->normal = v3_norm_or(nsum[r], v3_make(0, 0, 1));
        v3 c = v3_make(0, 0, 0);
        double big = 0;
        for (uint32_t k = s; k < e; k++) {
            v3 q = ivy_look_vert(m, v0 + k);
            c = v3_add(c, q);
            for (uint32_t j = k + 1; j < e; j++) {
                double d = v3_dist(q, ivy_look_vert(m, v0 + j));
                if (d > big) big = d;
            }
        }
        b->centre = v3_scale(c, 1.0 / (e - s));
        b->size = big;
        s = e;
    }
    /* Petioles: the last IVY_LOOK_PETIOLE_VERTS * nb vertices of part 0,
     * in blade order; the first ring (3 vertices) sits at the bud. */
    uint64_t np = (uint64_t)IVY_LOOK_PETIOLE_VERTS * nb;
    for (uint32_t k = 0; k < nb; k++) {
        bl[k].base = bl[k].centre;
        if (np > sp->vertex_count) continue;
        uint32_t v = sp->vertex_offset + sp->vertex_count - (uint32_t)np + IVY_LOOK_PETIOLE_VERTS * k;
        bl[k].base = v3_scale(v3_add(v3_add(ivy_look_vert(m, v), ivy_look_vert(m, v + 1)), ivy_look_vert(m, v + 2)), 1.0 / 3);
    }
    free(up);
    free(nsum);
    free(area);
    *n = nb;
    return bl;
}

#endif

/* The fused roots surface (spec roots.md 5,
 * docs/roots.md "Fused surface"): the whole net as one closed surface in
 * which touching roots merge with smooth fillets, as a strangler fig's
 * roots fuse (anastomosis). Method: every segment of the final polylines
 * is a tapered capsule (a-b, radii ra-rb from net->rad, the pipe model's);
 * on the voxels of a narrow band round them (voxel h = voxel_size r) the
 * signed distance of each polyline is the plain minimum over its capsules
 * (a smooth minimum there would bulge every joint), and the polylines
 * are merged by the polynomial smooth minimum with
 * k = fuse_radius r (0.25 + 0.75 maturity), folded in polyline order so
 * the bytes do not depend on anything else. Near a host the field takes
 * the CSG difference with it (max(d, gap - clearance)): roots press flat
 * onto the bark instead of entering it; below the ground they go on into
 * the soil and the surface is closed by the plane 2 r under ground_z.
 * OpenVDB meshes the level set (fused_vdb.cpp, tools::volumeToMesh);
 * here the mesh gets outward smooth normals, bark uvs from the nearest
 * capsule (u round it, v its arc length over the circumference, as the
 * tubes' uvs; a triangle across u's wrap gets its own copies of the
 * vertices), `root_kind` and `root_id` of the nearest capsule, its wind
 * and birth values (wind.c: its root's pivot, level and phase, stiffness
 * and birth between its two points), and the tubes' colour, material and
 * skeleton. */
#ifdef FUSED_TIMING
#define _POSIX_C_SOURCE 199309L
#endif
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "mesh/tube.h"
#include "mesh/wind.h"
#include "capsule.h"
#include "fused_vdb.h"
#include "roots_internal.h"
/* Build with -DFUSED_TIMING to print the stages' times (docs/roots.md). */
#ifdef FUSED_TIMING
#include <stdio.h>
#include "base/platform.h"
static double stage_ms(void) { return plat_clock() * 1e3; }
#define STAGE(i) stage_t[i] = stage_ms()
#else
#define STAGE(i) (void)0
#endif

#define BIG 1e30f
#define BLK 512
/* Band half-width in voxels. Only the signs outside it matter: the field
 * is about 1-Lipschitz (a tapered capsule's a little more), so the two
 * voxels of an edge that the surface crosses both lie within h of it. */
#define BAND_VOXELS 1.25
/* Roots stop this far (times r) outside a host: marching's linear
 * interpolation then keeps vertices out of a curved host too. */
#define HOST_GAP 0.02
/* Field values nearer zero than this (times h) move out to it. */
#define SNAP 0.1
/* The surface is closed this far (times r) under the ground. */
#define SOIL_DEPTH 2.0

typedef struct blk_meta {
    int32_t bx, by, bz;
    uint32_t stamp;      /* last polyline that touched the block, + 1 */
    uint32_t head, tail; /* list of capsules touching the block (caps_next chain) */
} blk_meta;

typedef struct fgrid {
    double h, cut;
    double list_cut; /* a capsule this near a voxel joins its block's list */
    blk_meta *meta;
    float *acc, *tmp;
    uint32_t n, cap;
    uint32_t *table; /* open addressing: block index + 1, 0 = empty */
    uint32_t table_mask;
    uint32_t *lc, *lnext; /* capsule list entries */
    uint32_t nl, capl;
    uint32_t *touched;
    uint32_t n_touched;
    int nomem;
} fgrid;

/* floor and ceil to int without libm's calls (x86-64's baseline has no
 * rounding instruction): the raster asks for four per voxel column. */
static inline int32_t ifloor(double x) {
    int32_t i = (int32_t)x;
    return i - (x < i);
}
static inline int32_t iceil(double x) {
    int32_t i = (int32_t)x;
    return i + (x > i);
}

static inline int32_t floor_div8(int32_t i) { return i >= 0 ? i / 8 : -((-i + 7) / 8); }

static inline uint32_t hash3(int32_t x, int32_t y, int32_t z) {
    uint32_t h = (uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u;
    return h ^ (h >> 15);
}

static uint32_t grid_find(const fgrid *g, int32_t bx, int32_t by, int32_t bz) {
    for (uint32_t s = hash3(bx, by, bz) & g->table_mask;; s = (s + 1) & g->table_mask) {
        uint32_t e = g->table[s];
        if (!e) return UINT32_MAX;
        const blk_meta *m = &g->meta[e - 1];
        if (m->bx == bx && m->by == by && m->bz == bz) return e - 1;
    }
}

static int grid_rehash(fgrid *g, uint32_t size) {
    uint32_t *t = calloc(size, sizeof *t);
    if (!t) return -1;
    free(g->table);
    g->table = t;
    g->table_mask = size - 1;
    for (uint32_t i = 0; i < g->n; i++) {
        uint32_t s = hash3(g->meta[i].bx, g->meta[i].by, g->meta[i].bz) & g->table_mask;
        while (t[s]) s = (s + 1) & g->table_mask;
        t[s] = i + 1;
    }
    return 0;
}

static uint32_t grid_get(fgrid *g, int32_t bx, int32_t by, int32_t bz) {
    uint32_t i = grid_find(g, bx, by, bz);
    if (i != UINT32_MAX) return i;
    if (g->n == g->cap) {
        uint32_t nc = g->cap ? 2 * g->cap : 1024;
        blk_meta *m = realloc(g->meta, sizeof *m * nc);
        if (m) g->meta = m;
        float *a = m ? realloc(g->acc, sizeof(float) * BLK * nc) : NULL;
        if (a) g->acc = a;
        float *t = a ? realloc(g->tmp, sizeof(float) * BLK * nc) : NULL;
        if (t) g->tmp = t;
        uint32_t *tc = t ? realloc(g->touched, sizeof(uint32_t) * nc) : NULL;
        if (tc) g->touched = tc;
        if (!tc) {
            g->nomem = 1;
            return UINT32_MAX;
        }
        g->cap = nc;
    }
    if (2 * (g->n + 1) > g->table_mask + 1 && grid_rehash(g, 2 * (g->table_mask + 1))) {
        g->nomem = 1;
        return UINT32_MAX;
    }
    i = g->n++;
    blk_meta *m = &g->meta[i];
    m->bx = bx, m->by = by, m->bz = bz;
    m->stamp = 0;
    m->head = m->tail = UINT32_MAX;
    for (int v = 0; v < BLK; v++) g->acc[(size_t)i * BLK + v] = BIG;
    uint32_t s = hash3(bx, by, bz) & g->table_mask;
    while (g->table[s]) s = (s + 1) & g->table_mask;
    g->table[s] = i + 1;
    return i;
}

static void grid_list_add(fgrid *g, uint32_t b, uint32_t c) {
    blk_meta *m = &g->meta[b];
    if (m->tail != UINT32_MAX && g->lc[m->tail] == c) return;
    if (g->nl == g->capl) {
        uint32_t nc = g->capl ? 2 * g->capl : 4096;
        uint32_t *a = realloc(g->lc, sizeof(uint32_t) * nc);
        if (a) g->lc = a;
        uint32_t *n = a ? realloc(g->lnext, sizeof(uint32_t) * nc) : NULL;
        if (n) g->lnext = n;
        if (!n) {
            g->nomem = 1;
            return;
        }
        g->capl = nc;
    }
    uint32_t e = g->nl++;
    g->lc[e] = c;
    g->lnext[e] = UINT32_MAX;
    if (m->tail == UINT32_MAX) m->head = e;
    else g->lnext[m->tail] = e;
    m->tail = e;
}

static void grid_free(fgrid *g) {
    free(g->meta);
    free(g->acc);
    free(g->tmp);
    free(g->table);
    free(g->lc);
    free(g->lnext);
    free(g->touched);
}

/* Polynomial smooth minimum (fillet radius about k). */
static inline float smin(float a, float b, float k) {
    float h = k - fabsf(a - b);
    h = (h > 0 ? h : 0) / k; /* no branch: the merge loop vectorises */
    return (a < b ? a : b) - h * h * k * 0.25f;
}

/* Rasterises capsule c (of polyline stamp - 1) into the blocks' tmp. */
static void raster_capsule(fgrid *g, const capsule *c, uint32_t ci, uint32_t stamp) {
    double wide = (c->ra > c->rb ? c->ra : c->rb) * (c->sq - 1.0); /* how much wider a flat root is */
    double h = g->h, ih = 1.0 / h, R = (c->ra > c->rb ? c->ra : c->rb) * c->sq + g->cut;
    v3 lo = v3_make(fmin(c->a.x, c->b.x) - R, fmin(c->a.y, c->b.y) - R, fmin(c->a.z, c->b.z) - R);
    v3 hi = v3_make(fmax(c->a.x, c->b.x) + R, fmax(c->a.y, c->b.y) + R, fmax(c->a.z, c->b.z) + R);
    int32_t i0[3] = {(int32_t)ceil(lo.x / h), (int32_t)ceil(lo.y / h), (int32_t)ceil(lo.z / h)};
    int32_t i1[3] = {(int32_t)floor(hi.x / h), (int32_t)floor(hi.y / h), (int32_t)floor(hi.z / h)};
    double half_diag = 8 * h * 0.8660254037844386;
    for (int32_t bx = floor_div8(i0[0]); bx <= floor_div8(i1[0]); bx++)
        for (int32_t by = floor_div8(i0[1]); by <= floor_div8(i1[1]); by++)
            for (int32_t bz = floor_div8(i0[2]); bz <= floor_div8(i1[2]); bz++) {
                v3 centre = v3_make((bx * 8 + 3.5) * h, (by * 8 + 3.5) * h, (bz * 8 + 3.5) * h);
                if (capsule_dist(c, centre, NULL) - half_diag - wide >= g->cut) continue;
                int32_t x0 = bx * 8 > i0[0] ? bx * 8 : i0[0], x1 = bx * 8 + 7 < i1[0] ? bx * 8 + 7 : i1[0];
                int32_t y0 = by * 8 > i0[1] ? by * 8 : i0[1], y1 = by * 8 + 7 < i1[1] ? by * 8 + 7 : i1[1];
                int32_t z0 = bz * 8 > i0[2] ? bz * 8 : i0[2], z1 = bz * 8 + 7 < i1[2] ? bz * 8 + 7 : i1[2];
                uint32_t b = UINT32_MAX;
                float *tmp = NULL;
                int listed = 0; /* the block's list has the capsule */
                const double list_cut = g->list_cut;
                /* Along a column, p - a and t are linear in z: the squared
                 * distance to the axis comes without a sqrt, which only the
                 * voxels within reach pay. */
                v3 ba = v3_sub(c->b, c->a);
                double l2 = v3_len2(ba), il2 = l2 > 0 ? 1.0 / l2 : 0, dr = c->rb - c->ra;
                double ua = ba.x * ba.x + ba.y * ba.y, iua = ua > 1e-12 * l2 ? 1.0 / ua : 0;
                for (int32_t x = x0; x <= x1; x++)
                    for (int32_t y = y0; y <= y1; y++) {
                        double px = x * h - c->a.x, py = y * h - c->a.y;
                        double dxy = px * ba.x + py * ba.y, pxy2 = px * px + py * py;
                        /* The column only meets the reach round the axis points
                         * s in [s0, s1] horizontally within R, at heights within
                         * R of theirs: a conservative z range, no voxel lost. */
                        double s0 = 0, s1 = 1;
                        if (ua > 1e-12 * l2) {
                            double disc = dxy * dxy - ua * (pxy2 - R * R);
                            if (disc < 0) continue;
                            disc = sqrt(disc);
                            s0 = (dxy - disc) * iua, s1 = (dxy + disc) * iua;
                            s0 = s0 < 0 ? 0 : s0, s1 = s1 > 1 ? 1 : s1;
                            if (s0 > s1) continue;
                        } else if (pxy2 > R * R) {
                            continue;
                        }
                        double za = c->a.z + s0 * ba.z, zb = c->a.z + s1 * ba.z;
                        if (za > zb) {
                            double sw = za;
                            za = zb, zb = sw;
                        }
                        int32_t zl = iceil((za - R) * ih), zh = ifloor((zb + R) * ih);
                        if (zl < z0) zl = z0;
                        if (zh > z1) zh = z1;
                        for (int32_t z = zl; z <= zh; z++) {
                            double pz = z * h - c->a.z, dt = dxy + pz * ba.z;
                            double t = dt * il2;
                            t = t < 0 ? 0 : (t > 1 ? 1 : t);
                            double q2 = pxy2 + pz * pz - t * (2 * dt - t * l2), tr = c->ra + dr * t;
                            double reach = g->cut + tr * c->sq;
                            if (q2 >= reach * reach) continue;
                            double d = c->sq == 1.0 ? sqrt(q2 > 0 ? q2 : 0) - tr
                                                    : flat_dist(c, v3_make(px - t * ba.x, py - t * ba.y, pz - t * ba.z), tr);
                            if (b == UINT32_MAX) {
                                b = grid_get(g, bx, by, bz);
                                if (b == UINT32_MAX) return;
                                blk_meta *m = &g->meta[b];
                                tmp = g->tmp + (size_t)b * BLK;
                                if (m->stamp != stamp) {
                                    m->stamp = stamp;
                                    for (int v = 0; v < BLK; v++) tmp[v] = BIG;
                                    g->touched[g->n_touched++] = b;
                                }
                            }
                            if (!listed && d < list_cut) {
                                grid_list_add(g, b, ci);
                                listed = 1;
                            }
                            int v = ((x - bx * 8) << 6) | ((y - by * 8) << 3) | (z - bz * 8);
                            if ((float)d < tmp[v]) tmp[v] = (float)d;
                        }
                    }
            }
}

/* The nearest capsule to p: the block's list, else every capsule. */
static uint32_t nearest_capsule(const fgrid *g, const capsule *caps, uint32_t n_caps, v3 p, double *t_out) {
    int32_t x = ifloor(p.x / g->h + 0.5), y = ifloor(p.y / g->h + 0.5), z = ifloor(p.z / g->h + 0.5);
    uint32_t b = grid_find(g, floor_div8(x), floor_div8(y), floor_div8(z)), best = UINT32_MAX;
    double bd = HUGE_VAL, t;
    if (b != UINT32_MAX)
        for (uint32_t e = g->meta[b].head; e != UINT32_MAX; e = g->lnext[e]) {
            double d = capsule_dist(&caps[g->lc[e]], p, &t);
            if (d < bd) bd = d, best = g->lc[e], *t_out = t;
        }
    if (best == UINT32_MAX)
        for (uint32_t c = 0; c < n_caps; c++) {
            double d = capsule_dist(&caps[c], p, &t);
            if (d < bd) bd = d, best = c, *t_out = t;
        }
    return best;
}

typedef struct fvert {
    double u, v;
    int32_t kind, id;
    uint32_t cap; /* the nearest capsule, and where along it (0..1): the attributes */
    double t;
    uint32_t src; /* the marching vertex (position, normal) */
} fvert;

/* The uv of q on capsule cp at t: u round it (the tube frame of its first
 * point), v along its polyline (tube_dv, as the tubes'). */
static void uv_on(const capsule *cp, const v3 *T, const v3 *N, const double *vcum, double r, v3 q, double t,
                  double *u, double *v) {
    v3 e = v3_norm_or(v3_sub(cp->b, cp->a), T[cp->at]);
    v3 n0 = v3_norm_or_perp(v3_madd(N[cp->at], e, -v3_dot(N[cp->at], e)), e), b0 = v3_cross(e, n0);
    v3 o = v3_sub(q, v3_lerp(cp->a, cp->b, t));
    double l = v3_dist(cp->a, cp->b), rt = cp->ra + (cp->rb - cp->ra) * t;
    *u = dm_atan2(v3_dot(o, b0), v3_dot(o, n0)) / (2 * BANYAN_PI) + 0.5;
    *v = vcum[cp->at] + tube_dv(t * l, cp->ra, rt, r);
}

/* A triangle whose corners lie nearest to different roots takes one
 * root's uvs at all three corners (the root of the corner whose capsule
 * comes first): each other corner becomes a copy of its vertex with the
 * uv of its position on that capsule, shared by the triangles round it
 * that ask the same. Interpolating two roots' unrelated uvs drew tight
 * stripes across such triangles. fv grows (*cap entries); returns the
 * entry count, 0 when out of memory. */
static uint32_t seam_uvs(fvert **pfv, uint32_t *cap, uint32_t nv, uint32_t *tri, uint32_t nt, const float *pos,
                         double h, const capsule *caps, const v3 *T, const v3 *N, const double *vcum, double r) {
    uint32_t n = nv, room = 0, *head = malloc(sizeof(uint32_t) * (nv ? nv : 1)), *next = NULL, *key = NULL;
    if (!head) return 0;
    for (uint32_t i = 0; i < nv; i++) head[i] = UINT32_MAX;
    for (uint32_t f = 0; f < nt && n; f++) {
        uint32_t *I = tri + 3 * (size_t)f, ref = 0;
        fvert *fv = *pfv;
        for (int j = 1; j < 3; j++)
            if (fv[I[j]].cap < fv[I[ref]].cap) ref = (uint32_t)j;
        const uint32_t rc = fv[I[ref]].cap;
        for (uint32_t j = 0; j < 3 && n; j++) {
            uint32_t s = I[j], e;
            if (j == ref || caps[(*pfv)[s].cap].poly == caps[rc].poly) continue;
            for (e = head[s]; e != UINT32_MAX && key[e - nv] != rc; e = next[e - nv]) {}
            if (e == UINT32_MAX) {
                if (n == *cap || n - nv == room) {
                    uint32_t grow = room ? room : 1024;
                    fvert *nf = realloc(*pfv, sizeof *nf * ((size_t)*cap + grow));
                    if (nf) *pfv = nf, *cap += grow;
                    uint32_t *nn = nf ? realloc(next, sizeof(uint32_t) * ((size_t)room + grow)) : NULL;
                    if (nn) next = nn;
                    uint32_t *nk = nn ? realloc(key, sizeof(uint32_t) * ((size_t)room + grow)) : NULL;
                    if (!nk) {
                        n = 0;
                        break;
                    }
                    key = nk, room += grow;
                }
                fvert *c = &(*pfv)[n];
                *c = (*pfv)[s];
                const capsule *cp = &caps[rc];
                v3 q = v3_make(pos[3 * s] * h, pos[3 * s + 1] * h, pos[3 * s + 2] * h);
                double t;
                capsule_dist(cp, q, &t);
                uv_on(cp, T, N, vcum, r, q, t, &c->u, &c->v);
                next[n - nv] = head[s], key[n - nv] = rc, head[s] = n;
                e = n++;
            }
            I[j] = e;
        }
    }
    free(head);
    free(next);
    free(key);
    return n;
}

/* The capsules of every polyline but the aerial roots' (threads:
 * aerial.c), their tube frames T and N (T + n_pts) and the v coordinate
 * along each; returns the tubes' side area. */
static double capsules_of(const roots_net *net, const banyan_roots_params *p, capsule *caps, v3 *T, double *vcum,
                          double r) {
    v3 *N = T + net->n_pts;
    double area = 0;
    uint32_t n_caps = 0;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2 || pl->kind == ROOT_AERIAL) continue; /* threads: aerial.c */
        tube_frames(net->pts + pl->off, pl->n, v3_make(0, 0, 0), T + pl->off, N + pl->off);
        vcum[pl->off] = 0;
        for (uint32_t i = 0; i + 1 < pl->n; i++) {
            uint32_t at = pl->off + i;
            capsule *c = &caps[n_caps++];
            roots_capsule_set(c, net, p, t, at);
            double l = v3_dist(c->a, c->b);
            vcum[at + 1] = vcum[at] + tube_dv(l, c->ra, c->rb, r);
            area += BANYAN_PI * (c->ra + c->rb) * l;
        }
    }
    return area;
}

/* The field: per polyline the minimum of its capsules, then the smooth
 * union (smin over k) of the polylines in order. 0, or 1 when out of
 * memory, 2 when the run stopped. */
static int field_union(fgrid *g, const roots_net *net, const capsule *caps, float k) {
    for (uint32_t t = 0, ci = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->n < 2 || pl->kind == ROOT_AERIAL) continue; /* threads: aerial.c */
        if (prog_at(net->prog, ROOTS_AT_MESH + 0.5 * (1.0 - ROOTS_AT_MESH) * t / net->n_poly)) return 2;
        g->n_touched = 0;
        for (uint32_t i = 0; i + 1 < pl->n; i++, ci++) raster_capsule(g, &caps[ci], ci, t + 1);
        if (g->nomem) return 1;
        for (uint32_t j = 0; j < g->n_touched; j++) {
            size_t b = (size_t)g->touched[j] * BLK;
            float *acc = g->acc + b, *tmp = g->tmp + b;
            if (k > 0)
                for (int v = 0; v < BLK; v++) acc[v] = tmp[v] < BIG ? smin(acc[v], tmp[v], k) : acc[v];
            else
                for (int v = 0; v < BLK; v++) acc[v] = tmp[v] < acc[v] ? tmp[v] : acc[v];
        }
    }
    return 0;
}

/* Host difference and the soil's floor, then the band's clamp, on every
 * block; each block's stamp becomes 1 when a voxel of it is inside. 1 when
 * the run stopped. */
static int host_and_floor(fgrid *g, const roots_net *net, double band, double h, double r) {
    const roots_world *w = &net->w;
    double gap = HOST_GAP * r, floor_z = w->ground_z - SOIL_DEPTH * r;
    double half_diag = 8 * h * 0.8660254037844386, range = band + gap;
    for (uint32_t b = 0; b < g->n; b++) {
        if ((b & 63) == 0 && roots_stop(net)) return 1; /* a voxel's host query each: slow among many hosts */
        blk_meta *m = &g->meta[b];
        float *acc = g->acc + (size_t)b * BLK;
        v3 centre = v3_make((m->bx * 8 + 3.5) * h, (m->by * 8 + 3.5) * h, (m->bz * 8 + 3.5) * h);
        int near_host = world_clearance_in(w, centre, 0, half_diag + range, NULL, NULL) < half_diag + range;
        for (int v = 0; v < BLK; v++) {
            float d = acc[v];
            if (d >= band) {
                acc[v] = (float)band;
                continue;
            }
            v3 q = v3_make((m->bx * 8 + (v >> 6)) * h, (m->by * 8 + ((v >> 3) & 7)) * h, (m->bz * 8 + (v & 7)) * h);
            if (w->ground && floor_z - q.z > d) d = (float)(floor_z - q.z);
            if (near_host) {
                double c = world_clearance_in(w, q, 0, range, NULL, NULL);
                if (gap - c > d) d = (float)(gap - c);
            }
            /* A value at or near zero puts the vertices of the cells
             * round that voxel on or near one point: faces of zero or
             * sliver area, sheets that nearly touch. Such a value moves
             * out to SNAP h on its side (0 counts as outside): the
             * surface crosses no edge nearer than about SNAP h to a
             * voxel. */
            if (d < SNAP * h && d > -SNAP * h) d = (float)(d < 0 ? -SNAP * h : SNAP * h);
            acc[v] = d > band ? (float)band : (d < -band ? (float)-band : d);
        }
        int inside = 0;
        for (int v = 0; v < BLK; v++) inside |= acc[v] < 0;
        m->stamp = (uint32_t)inside; /* the stamps are done with */
    }
    return 0;
}

/* Which blocks go to OpenVDB, packed to the front of acc, their origins
 * in tmp (3 ints a block, in 512 floats per block; tmp is free by now);
 * returns how many. A block with no voxel inside only meets the surface on
 * an edge to an inside voxel of a face neighbour, its voxel there within
 * the band; without such an edge OpenVDB's background (outside, +band)
 * stands in for the block: the same signs, the same values on every edge
 * the surface crosses, so the same mesh from fewer leaves to scan (about a
 * third of the blocks stay). */
static uint32_t pack_surface_blocks(fgrid *g, double band) {
    for (uint32_t b = 0; b < g->n; b++) {
        blk_meta *m = &g->meta[b];
        const float *acc = g->acc + (size_t)b * BLK;
        int keep = m->stamp & 1;
        for (int f = 0; f < 6 && !keep; f++) {
            int ax = f >> 1, shift = 6 - 3 * ax, theirs = f & 1 ? 0 : 7;
            int32_t nb[3] = {m->bx, m->by, m->bz};
            nb[ax] += f & 1 ? 1 : -1;
            uint32_t o = grid_find(g, nb[0], nb[1], nb[2]);
            if (o == UINT32_MAX || !(g->meta[o].stamp & 1)) continue;
            const float *nacc = g->acc + (size_t)o * BLK;
            for (int v = 0; v < BLK && !keep; v++)
                keep = ((v >> shift) & 7) == theirs && nacc[v] < 0 && acc[v ^ (7 << shift)] < band;
        }
        m->stamp |= (uint32_t)keep << 1;
    }
    int32_t *origin = (int32_t *)g->tmp;
    uint32_t n_surf = 0;
    for (uint32_t b = 0; b < g->n; b++) {
        const blk_meta *m = &g->meta[b];
        float *acc = g->acc + (size_t)b * BLK;
        if (!(m->stamp & 2)) continue;
        origin[3 * n_surf] = m->bx * 8, origin[3 * n_surf + 1] = m->by * 8, origin[3 * n_surf + 2] = m->bz * 8;
        if (n_surf != b) memmove(g->acc + (size_t)n_surf * BLK, acc, sizeof(float) * BLK);
        n_surf++;
    }
    return n_surf;
}

/* OpenVDB may put two vertices of one face on the same point (a face of
 * zero area, seen where a cell is split into two sheets): those vertices
 * become one, the faces that collapse go, and the vertices are renumbered
 * densely (*nv, *nt the counts). 1 when out of memory. */
static int weld_coincident(fused_vdb_out *vo, uint32_t *nv, uint32_t *nt) {
    uint32_t nv0 = *nv, nt0 = *nt;
    uint32_t *map = malloc(sizeof *map * nv0);
    if (!map) return 1;
    for (uint32_t i = 0; i < nv0; i++) map[i] = i;
    int any = 0;
    for (uint32_t f = 0; f < nt0; f++)
        for (int j = 0; j < 3; j++) {
            uint32_t a = vo->tri[3 * f + j], b = vo->tri[3 * f + (j + 1) % 3];
            if (!memcmp(vo->pos + 3 * (size_t)a, vo->pos + 3 * (size_t)b, 3 * sizeof(float))) {
                while (map[a] != a) a = map[a];
                while (map[b] != b) b = map[b];
                if (a != b) map[a > b ? a : b] = a < b ? a : b;
                any = 1;
            }
        }
    if (any) {
        uint32_t mt = 0, mv = 0;
        for (uint32_t i = 0; i < nv0; i++) {
            uint32_t a = i;
            while (map[a] != a) a = map[a];
            map[i] = a;
        }
        for (uint32_t f = 0; f < nt0; f++) {
            uint32_t a = map[vo->tri[3 * f]], b = map[vo->tri[3 * f + 1]], c = map[vo->tri[3 * f + 2]];
            if (a == b || b == c || a == c) continue;
            vo->tri[3 * mt] = a, vo->tri[3 * mt + 1] = b, vo->tri[3 * mt + 2] = c;
            mt++;
        }
        /* dense numbering: a root (map[i] == i) keeps its order */
        uint32_t *nid = malloc(sizeof *nid * nv0);
        if (!nid) {
            free(map);
            return 1;
        }
        for (uint32_t i = 0; i < nv0; i++)
            if (map[i] == i) {
                nid[i] = mv;
                memmove(vo->pos + 3 * (size_t)mv, vo->pos + 3 * (size_t)i, 3 * sizeof(float));
                mv++;
            }
        for (uint32_t t = 0; t < 3 * mt; t++) vo->tri[t] = nid[vo->tri[t]];
        free(nid);
        *nv = mv, *nt = mt;
    }
    free(map);
    return 0;
}

/* Orientation: OpenVDB's winding, made outward by the signed volume. */
static void orient_outward(fused_vdb_out *vo, uint32_t nt) {
    double vol = 0;
    for (uint32_t f = 0; f < nt; f++) {
        const float *A = vo->pos + 3 * (size_t)vo->tri[3 * f], *B = vo->pos + 3 * (size_t)vo->tri[3 * f + 1],
                    *C = vo->pos + 3 * (size_t)vo->tri[3 * f + 2];
        vol += A[0] * ((double)B[1] * C[2] - (double)B[2] * C[1]) - A[1] * ((double)B[0] * C[2] - (double)B[2] * C[0]) +
               A[2] * ((double)B[0] * C[1] - (double)B[1] * C[0]);
    }
    if (vol < 0)
        for (uint32_t f = 0; f < nt; f++) {
            uint32_t x = vo->tri[3 * f + 1];
            vo->tri[3 * f + 1] = vo->tri[3 * f + 2];
            vo->tri[3 * f + 2] = x;
        }
}

/* Marching cuts the crease where the roots meet a host's edge: a
 * vertex there may sit a little inside (up to about h / 3). It goes
 * back out along the distance field's normal, to half the gap. 1 when the
 * run stopped. */
static int push_off_hosts(const roots_net *net, float *pos, uint32_t nv, double h, double r) {
    for (uint32_t i = 0; i < nv; i++) {
        if ((i & 1023) == 0 && roots_stop(net)) return 1; /* a host query per vertex */
        float *f = pos + 3 * (size_t)i;
        v3 q = v3_make(f[0] * h, f[1] * h, f[2] * h), n;
        int which;
        double c = world_clearance_in(&net->w, q, 0, HOST_GAP * r, &n, &which);
        if (c >= 0.5 * HOST_GAP * r || which < 0) continue;
        q = v3_madd(q, n, 0.5 * HOST_GAP * r - c);
        f[0] = (float)(q.x / h), f[1] = (float)(q.y / h), f[2] = (float)(q.z / h);
    }
    return 0;
}

static void stretch_birth(mesh_builder *mb, const wind_slots *ws) {
    /* The surface starts off G and ends short of the last tip: its
     * birth is stretched to 0..1 so growth starts and ends on time. */
    float *bv = mb->attr[ws->birth], lo = bv[0], hi = bv[0];
    for (uint32_t i = 1; i < mb->nv; i++) lo = bv[i] < lo ? bv[i] : lo, hi = bv[i] > hi ? bv[i] : hi;
    double span = (double)hi - lo; /* in double: the last vertex's is exactly 1 */
    for (uint32_t i = 0; i < mb->nv; i++) bv[i] = span > 0 ? (float)(((double)bv[i] - lo) / span) : 0.0f;
}

/* OpenVDB's stop between its meshing stages (fused_vdb_in.stop): the
 * budget and the cancel, on the generator's thread. */
static int vdb_stop(void *user) { return roots_stop((const roots_net *)user); }

/* Smooth normals' sums: each triangle's normal, weighted by its area (the
 * cross product's length), added to its three vertices' sums in nacc. */
static void face_normal_sums(const fused_vdb_out *vo, uint32_t nt, double *nacc) {
    for (uint32_t f = 0; f < nt; f++) {
        const uint32_t *I = vo->tri + 3 * (size_t)f;
        v3 A = v3_make(vo->pos[3 * I[0]], vo->pos[3 * I[0] + 1], vo->pos[3 * I[0] + 2]);
        v3 B = v3_make(vo->pos[3 * I[1]], vo->pos[3 * I[1] + 1], vo->pos[3 * I[1] + 2]);
        v3 C = v3_make(vo->pos[3 * I[2]], vo->pos[3 * I[2] + 1], vo->pos[3 * I[2] + 2]);
        v3 n = v3_cross(v3_sub(B, A), v3_sub(C, A));
        for (int j = 0; j < 3; j++) {
            nacc[3 * I[j]] += n.x, nacc[3 * I[j] + 1] += n.y, nacc[3 * I[j] + 2] += n.z;
        }
    }
}

/* Each vertex's nearest capsule: its polyline's kind and id, where along
 * the capsule it lies (t) and its uv on it. Returns 1 when stopped
 * (cancel or budget), else 0. */
static int vertex_uvs(const roots_net *net, const fgrid *g, const capsule *caps, uint32_t n_caps, const v3 *T,
                      const v3 *N, const double *vcum, double r, double h, const fused_vdb_out *vo, uint32_t nv,
                      fvert *fv) {
    for (uint32_t i = 0; i < nv; i++) {
        if ((i & 1023) == 0 && roots_stop(net)) return 1;
        v3 q = v3_make(vo->pos[3 * i] * h, vo->pos[3 * i + 1] * h, vo->pos[3 * i + 2] * h);
        double t = 0;
        uint32_t c = nearest_capsule(g, caps, n_caps, q, &t);
        const capsule *cp = &caps[c];
        uv_on(cp, T, N, vcum, r, q, t, &fv[i].u, &fv[i].v);
        fv[i].kind = net->poly[cp->poly].kind;
        fv[i].id = net->poly[cp->poly].id;
        fv[i].cap = c, fv[i].t = t, fv[i].src = i;
    }
    return 0;
}

/* A triangle across u's wrap takes copies of its low-u vertices at u + 1:
 * copy j of vertex dsrc[j] is vertex n_fv + j (dup: each vertex's copy,
 * UINT32_MAX for none), the triangle's indices moved to it. Returns the
 * number of copies. */
static uint32_t wrap_copies(fused_vdb_out *vo, uint32_t nt, const fvert *fv, uint32_t n_fv, uint32_t *dup,
                            uint32_t *dsrc) {
    uint32_t extra = 0;
    for (uint32_t f = 0; f < nt; f++) {
        uint32_t *I = vo->tri + 3 * (size_t)f;
        double u0 = fv[I[0]].u, u1 = fv[I[1]].u, u2 = fv[I[2]].u;
        double lo = fmin(u0, fmin(u1, u2)), hi = fmax(u0, fmax(u1, u2));
        if (hi - lo <= 0.5) continue;
        for (int j = 0; j < 3; j++)
            if (fv[I[j]].u < 0.5) {
                if (dup[I[j]] == UINT32_MAX) dsrc[extra] = I[j], dup[I[j]] = n_fv + extra++;
                I[j] = dup[I[j]];
            }
    }
    return extra;
}

static banyan_status fused_nomem(banyan_error *err) {
    return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the fused roots surface");
}

/* The fused surface's mesh: its n_fv vertices (then the wrap's `extra`
 * copies at u + 1) with their smooth normals, uvs, kind and id, and the
 * wind and birth of their nearest capsule, between its two points; its
 * triangles; the aerial roots swept as threads; birth stretched to 0..1;
 * the skeleton. Counts go to stats when given. */
static banyan_status fused_mesh(const roots_net *net, const banyan_roots_params *p, const capsule *caps,
                                const fused_vdb_out *vo, uint32_t nt, const fvert *fv, uint32_t n_fv, uint32_t extra,
                                const uint32_t *dsrc, const double *nacc, double h, banyan_mesh **out,
                                banyan_roots_stats *stats, banyan_error *err) {
    roots_wind rw;
    if (roots_wind_build(net, p, &rw)) return fused_nomem(err);
    mesh_builder mb;
    int a_kind, a_id;
    wind_slots ws;
    roots_mesh_init(&mb, p, &a_kind, &a_id, &ws);
    uint32_t thread_v = 0, thread_i = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].kind == ROOT_AERIAL) {
            uint32_t v, i;
            roots_aerial_counts(&net->poly[t], &v, &i);
            thread_v += v, thread_i += i;
        }
    mb_reserve(&mb, n_fv + extra + thread_v, 3 * nt + thread_i);
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t j = 0; j < (pass ? extra : n_fv); j++) {
            uint32_t i = pass ? dsrc[j] : j, s = fv[i].src;
            v3 q = v3_make(vo->pos[3 * s] * h, vo->pos[3 * s + 1] * h, vo->pos[3 * s + 2] * h);
            v3 n = v3_norm(v3_make(nacc[3 * s], nacc[3 * s + 1], nacc[3 * s + 2]));
            mb_set_attr(&mb, a_kind, fv[i].kind);
            mb_set_attr(&mb, a_id, fv[i].id);
            /* the nearest capsule's values, between its two points */
            const capsule *cp = &caps[fv[i].cap];
            double t = fv[i].t, s0 = rw.stiff[cp->at], b0 = rw.birth[cp->at];
            wind_set(&mb, &ws, rw.pivot[cp->poly], roots_wind_level(fv[i].kind), s0 + (rw.stiff[cp->at + 1] - s0) * t,
                     rw.phase[cp->poly], 0.0);
            wind_birth(&mb, &ws, b0 + (rw.birth[cp->at + 1] - b0) * t);
            mb_vertex(&mb, q, n, fv[i].u + pass, fv[i].v);
        }
    for (uint32_t f = 0; f < nt; f++) mb_tri(&mb, vo->tri[3 * f], vo->tri[3 * f + 1], vo->tri[3 * f + 2]);
    if (thread_v) roots_aerial_sweep_all(&mb, net, nt, a_kind, a_id, &ws, &rw);
    if (!mb.status && mb.nv) stretch_birth(&mb, &ws);
    if (roots_mesh_skeleton(&mb, net, p)) {
        mb_free(&mb);
        roots_wind_free(&rw);
        return fused_nomem(err);
    }
    uint32_t mv = mb.nv, mi = mb.ni;
    banyan_status st = mb_finish(&mb, out, err);
    if (st == BANYAN_OK && stats) {
        stats->vertices = mv;
        stats->triangles = mi / 3;
    }
    roots_wind_free(&rw);
    return st;
}

/* The field's grid (voxel h, capsules reaching band + k) and the smooth
 * union of the capsules in it (field_union). Returns 0, 1 when out of
 * memory, 2 when stopped. */
static int field_build(fgrid *g, const roots_net *net, const capsule *caps, float k, double h, double band) {
    g->h = h;
    g->cut = band + k;
    /* A vertex's field is 0, so some capsule is within k / 4 of it (smin
     * goes at most k / 4 below the minimum), and it lies within 0.87 h of
     * the voxel whose block it looks in. */
    g->list_cut = 0.25 * k + 1.25 * h;
    if (grid_rehash(g, 4096)) return 1;
    return field_union(g, net, caps, k);
}

/* The failure of OpenVDB's meshing other than out of memory or stopped:
 * its module missing, too many vertices, or volumeToMesh failing. */
static banyan_status vdb_fail(int vs, banyan_error *err) {
    if (vs == FUSED_VDB_NO_MODULE)
        return banyan_fail(err, BANYAN_E_INTERNAL,
                           "the fused roots surface needs " FUSED_VDB_MODULE " (OpenVDB) beside " FUSED_VDB_LIBRARY
                           "; it is missing or does not load: reinstall banyan, or set surface to tubes");
    return banyan_fail(err, vs == FUSED_VDB_TOO_BIG ? BANYAN_E_LIMIT : BANYAN_E_INTERNAL,
                       "OpenVDB could not mesh the fused roots surface (%s)",
                       vs == FUSED_VDB_TOO_BIG ? "too many vertices" : "volumeToMesh failed");
}

banyan_status roots_net_mesh_fused(const roots_net *net, const banyan_roots_params *p, banyan_mesh **out,
                                   banyan_roots_stats *stats, banyan_error *err) {
    const double r = net->r, h = p->voxel_size * r;
    const float k = (float)(p->fuse_radius * r * (0.25 + 0.75 * p->maturity));
    const double band = BAND_VOXELS * h;
    banyan_status st = BANYAN_OK;
#ifdef FUSED_TIMING
    double stage_t[6];
#endif

    /* Capsules, and an estimate of the vertices: a tube's side over h^2. */
    uint32_t n_caps = 0;
    for (uint32_t t = 0; t < net->n_poly; t++)
        if (net->poly[t].n >= 2 && net->poly[t].kind != ROOT_AERIAL) n_caps += net->poly[t].n - 1;
    if (n_caps == 0) return banyan_fail(err, BANYAN_E_INTERNAL, "the roots net has no root to mesh");
    capsule *caps = malloc(sizeof *caps * n_caps);
    v3 *T = malloc(sizeof(v3) * 2 * (net->n_pts ? net->n_pts : 1));
    double *vcum = malloc(sizeof(double) * (net->n_pts ? net->n_pts : 1));
    fgrid g;
    memset(&g, 0, sizeof g);
    fused_vdb_out vo;
    memset(&vo, 0, sizeof vo);
    fvert *fv = NULL;
    uint32_t *dup = NULL, *dsrc = NULL;
    double *nacc = NULL;
    if (!caps || !T || !vcum) goto nomem;
    v3 *N = T + net->n_pts;
    double area = capsules_of(net, p, caps, T, vcum, r);
    double est = area / (h * h);
    if (est > 2.0 * p->max_vertices) {
        st = banyan_fail(err, BANYAN_E_LIMIT,
                         "the fused roots surface needs about %.0f vertices, more than max_vertices = %d; raise "
                         "max_vertices or voxel_size, or use surface = tubes",
                         est, p->max_vertices);
        goto done;
    }
    /* Known before the work: at least the band's voxels about the surface
     * (two floats each) and the mesh's vertices (about 64 bytes each; 4
     * more for birth, 32 with the wind attributes too). */
    if (prog_reserve(net->prog, est * (2.0 * BAND_VOXELS * 8.0 + (p->wind ? 96.0 : 68.0)))) goto stopped;

    STAGE(0);
    /* The field: per polyline the minimum of its capsules, then the smooth
     * union of the polylines in order. Capsules only reach voxels where
     * they are nearer than band + k: farther, smin leaves the band alone. */
    int fu = field_build(&g, net, caps, k, h, band);
    if (fu == 1) goto nomem;
    if (fu == 2) goto stopped;

    STAGE(1);
    /* Host difference and the soil's floor; then the band's clamp. */
    {
        if (host_and_floor(&g, net, band, h, r)) goto stopped;
        uint32_t n_surf = pack_surface_blocks(&g, band);
        int32_t *origin = (int32_t *)g.tmp;
        if (prog_at(net->prog, ROOTS_AT_MESH + 0.55 * (1.0 - ROOTS_AT_MESH))) goto stopped;
        STAGE(2);
#ifdef FUSED_TIMING
        fprintf(stderr, "fused: %u of %u blocks to OpenVDB\n", n_surf, g.n);
#endif
        fused_vdb_in vi = {origin, g.acc, n_surf, (float)band, vdb_stop, (void *)net};
        int vs = fused_vdb_mesh(&vi, &vo);
        /* The field is done with (the lists stay for the nearest capsule):
         * its memory goes before the mesh's arrives, lowering the peak. */
        free(g.acc);
        free(g.tmp);
        g.acc = g.tmp = NULL;
        if (vs == FUSED_VDB_NOMEM) goto nomem;
        if (vs == FUSED_VDB_STOPPED) goto stopped;
        if (vs != FUSED_VDB_OK) {
            st = vdb_fail(vs, err);
            goto done;
        }
    }
    STAGE(3);
    if (roots_stop(net)) goto stopped;
    if (vo.n_pos == 0 || vo.n_tri == 0) {
        st = banyan_fail(err, BANYAN_E_INTERNAL, "the fused roots surface is empty");
        goto done;
    }

    uint32_t nv = vo.n_pos, nt = vo.n_tri;
    if (weld_coincident(&vo, &nv, &nt)) goto nomem;

    orient_outward(&vo, nt);

    if (push_off_hosts(net, vo.pos, nv, h, r)) goto stopped;

    /* Smooth normals (area-weighted face normals), uvs and attributes. */
    nacc = calloc((size_t)3 * nv, sizeof(double));
    uint32_t n_fv = nv, fv_cap = nv;
    fv = malloc(sizeof *fv * nv);
    if (!nacc || !fv) goto nomem;
    face_normal_sums(&vo, nt, nacc);
    if (vertex_uvs(net, &g, caps, n_caps, T, N, vcum, r, h, &vo, nv, fv)) goto stopped;
    n_fv = seam_uvs(&fv, &fv_cap, nv, vo.tri, nt, vo.pos, h, caps, T, N, vcum, r);
    dup = malloc(sizeof *dup * (n_fv ? n_fv : 1));
    dsrc = malloc(sizeof *dsrc * (n_fv ? n_fv : 1));
    if (!n_fv || !dup || !dsrc) goto nomem;
    for (uint32_t i = 0; i < n_fv; i++) dup[i] = UINT32_MAX;
    const uint32_t extra = wrap_copies(&vo, nt, fv, n_fv, dup, dsrc);
    if ((uint64_t)n_fv + extra > (uint64_t)p->max_vertices) {
        st = banyan_fail(err, BANYAN_E_LIMIT,
                         "the fused roots surface has %llu vertices, more than max_vertices = %d; raise "
                         "max_vertices or voxel_size, or use surface = tubes",
                         (unsigned long long)n_fv + extra, p->max_vertices);
        goto done;
    }

    STAGE(4);
    if (roots_stop(net)) goto stopped;
    st = fused_mesh(net, p, caps, &vo, nt, fv, n_fv, extra, dsrc, nacc, h, out, stats, err);
#ifdef FUSED_TIMING
    STAGE(5);
    fprintf(stderr, "fused: field %.1f, host and soil %.1f, OpenVDB %.1f, uvs and attributes %.1f, builder %.1f ms; "
            "%u blocks, %u capsules, %u vertices\n", stage_t[1] - stage_t[0], stage_t[2] - stage_t[1],
            stage_t[3] - stage_t[2], stage_t[4] - stage_t[3], stage_t[5] - stage_t[4], g.n, n_caps, nv + extra);
#endif
    goto done;

nomem:
    st = fused_nomem(err);
    goto done;
stopped:
    st = prog_fail(net->prog, err, "fused roots surface");
done:
    free(caps);
    free(T);
    free(vcum);
    grid_free(&g);
    free(vo.pos);
    free(vo.tri);
    free(fv);
    free(dup);
    free(dsrc);
    free(nacc);
    return st;
}

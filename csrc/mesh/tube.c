/* Tube sweeper; see tube.h. Shared by every generator (spec README,
 * "Output"; roots.md section 5 "Rings"). */
#include "tube.h"

#include <stdlib.h>

void tube_counts(uint32_t n, int sides, int cap_start, int cap_end, uint32_t *verts, uint32_t *indices) {
    uint32_t ring = (uint32_t)sides + 1;
    uint32_t caps = (cap_start ? 1u : 0u) + (cap_end ? 1u : 0u);
    *verts = n * ring + caps * (ring + 1);
    *indices = (n - 1) * (uint32_t)sides * 6 + caps * (uint32_t)sides * 3;
}

int tube_bark_tiles(double r, double tile) {
    double k = tile > 0 ? floor(6.283185307179586 * r / tile + 0.5) : 1.0;
    return k > 1 ? (k < 1e6 ? (int)k : 1000000) : 1;
}

/* u for `sides` + 1 vertices spread evenly over ku tiles. */
static void even_u(float *us, int sides, int ku) {
    for (int j = 0; j <= sides; j++) us[j] = (float)((double)ku * j / sides);
}

static v3 tangent_at(const v3 *p, uint32_t n, uint32_t i, v3 prev) {
    v3 d;
    if (i == 0) d = v3_sub(p[1], p[0]);
    else if (i == n - 1) d = v3_sub(p[n - 1], p[n - 2]);
    else {
        /* Bisector of the two unit segment directions: a ring tilted to it
         * meets both neighbours' rings evenly. */
        v3 a = v3_norm_or(v3_sub(p[i], p[i - 1]), prev), b = v3_norm_or(v3_sub(p[i + 1], p[i]), prev);
        d = v3_add(a, b);
    }
    return v3_norm_or(d, prev);
}

/* Rotation-minimising frames walked point by point (tube_frames, and
 * tube_sweep, which keeps no per-point scratch); each segment's vector,
 * length and unit direction are made once. */
typedef struct frame_walk {
    const v3 *p;
    uint32_t n, i;
    v3 T, N;            /* the frame at point i */
    v3 v, u;            /* segment i, p[i+1] - p[i], and its unit (when l > 1e-300) */
    double d2, l;       /* its squared length and length */
    v3 u0;              /* segment i - 1's unit and length (l0 = 0 at point 0) */
    double l0;
} frame_walk;

static inline void segment(const v3 *p, uint32_t i, v3 *v, v3 *u, double *d2, double *l) {
    *v = v3_sub(p[i + 1], p[i]);
    *d2 = v3_dot(*v, *v);
    *l = sqrt(*d2);
    *u = *l > 1e-300 ? v3_scale(*v, 1.0 / *l) : *v; /* = v3_norm_or's unit */
}

static void walk_start(frame_walk *w, const v3 *p, uint32_t n, v3 first_normal) {
    w->p = p;
    w->n = n;
    w->i = 0;
    w->l0 = 0;
    w->u0 = v3_make(0, 0, 0);
    segment(p, 0, &w->v, &w->u, &w->d2, &w->l);
    w->T = w->l > 1e-300 ? w->u : v3_norm_or(v3_sub(p[n - 1], p[0]), v3_make(0, 0, 1));
    v3 n0 = v3_sub(first_normal, v3_scale(w->T, v3_dot(first_normal, w->T)));
    w->N = v3_len2(n0) > 1e-12 ? v3_norm(n0) : v3_any_perp(w->T);
}

/* To point i + 1 (< n). */
static void walk_next(frame_walk *w) {
    uint32_t i = w->i;
    v3 T = w->T, v2 = w->v, u2 = w->u, T1;
    double d22 = w->d2, l2 = w->l;
    if (i + 2 == w->n) {
        T1 = w->l > 1e-300 ? w->u : T;
    } else {
        /* Bisector of the two unit segment directions: a ring tilted to it
         * meets both neighbours' rings evenly. */
        segment(w->p, i + 1, &v2, &u2, &d22, &l2);
        v3 a = w->l > 1e-300 ? w->u : T, b = l2 > 1e-300 ? u2 : T;
        T1 = v3_norm_or(v3_add(a, b), T);
    }
    /* Double reflection: reflect across the bisector plane of x_i,
     * x_{i+1}, then across the plane that maps the reflected tangent onto
     * T_{i+1}. */
    v3 v1 = w->v;
    double c1 = w->d2;
    v3 rL = w->N, tL = T;
    if (c1 > 1e-24) {
        rL = v3_madd(w->N, v1, -2.0 / c1 * v3_dot(v1, w->N));
        tL = v3_madd(T, v1, -2.0 / c1 * v3_dot(v1, T));
    }
    v3 v3r = v3_sub(T1, tL);
    double c2 = v3_len2(v3r);
    v3 r = c2 > 1e-24 ? v3_madd(rL, v3r, -2.0 / c2 * v3_dot(v3r, rL)) : rL;
    /* Re-orthonormalise against float drift. */
    r = v3_sub(r, v3_scale(T1, v3_dot(r, T1)));
    w->N = v3_len2(r) > 1e-24 ? v3_norm(r) : v3_any_perp(T1);
    w->T = T1;
    w->u0 = w->u;
    w->l0 = w->l;
    w->v = v2;
    w->u = u2;
    w->d2 = d22;
    w->l = l2;
    w->i = i + 1;
}

void tube_frames(const v3 *pts, uint32_t n, v3 first_normal, v3 *T, v3 *N) {
    frame_walk w;
    walk_start(&w, pts, n, first_normal);
    for (uint32_t i = 0;; i++) {
        T[i] = w.T;
        N[i] = w.N;
        if (i + 1 >= n) break;
        walk_next(&w);
    }
}

/* Quads between consecutive rings; ring i starts at first + i * (sides+1).
 * Every ring pair repeats one pattern of offsets from its first vertex:
 * built once, then each pair is one add per index (the loop vectorises). */
static void stitch(mesh_builder *mb, uint32_t first, uint32_t n, int sides) {
    uint32_t ring = (uint32_t)sides + 1, per = 6 * (uint32_t)sides;
    uint32_t *I = mb_indices(mb, (n - 1) * per);
    if (!I) return;
    uint32_t pat[6 * 256];
    for (uint32_t j = 0; j < (uint32_t)sides; j++) {
        uint32_t *q = pat + 6 * j;
        q[0] = j; q[1] = j + 1; q[2] = ring + j + 1;
        q[3] = j; q[4] = ring + j + 1; q[5] = ring + j;
    }
    for (uint32_t i = 0, r0 = first; i + 1 < n; i++, r0 += ring, I += per)
        for (uint32_t k = 0; k < per; k++) I[k] = r0 + pat[k];
}

/* v gained over a segment of length l whose radius goes linearly from
 * r0 to r1: the integral of dl / (2 pi r), so that along a tapering tube
 * a texel stays as tall as it is wide (u runs once around whatever the
 * radius) and bark textures do not stretch. A radius that is not
 * positive falls back to r_mean. */
double tube_dv(double l, double r0, double r1, double r_mean) {
    const double two_pi = 6.283185307179586;
    /* v counts tiles: one tile spans BANYAN_BARK_TILE_ASPECT circumferences */
    if (!(r0 > 1e-12 && r1 > 1e-12)) return (r_mean > 1e-12 ? l / (two_pi * r_mean) : l) / BANYAN_BARK_TILE_ASPECT;
    double d = r1 - r0;
    if (fabs(d) < 1e-6 * r0) return l / (two_pi * 0.5 * (r0 + r1)) / BANYAN_BARK_TILE_ASPECT;
    return l * dm_log(r1 / r0) / (two_pi * d) / BANYAN_BARK_TILE_ASPECT;
}

static inline void put3(float *f, v3 p) {
    f[0] = (float)p.x; f[1] = (float)p.y; f[2] = (float)p.z;
}

static void cap(mesh_builder *mb, const v3 *ring, v3 centre, v3 normal, int sides, int at_end) {
    uint32_t c = mb_vertices(mb, (uint32_t)sides + 2);
    uint32_t *I = mb_indices(mb, 3 * (uint32_t)sides);
    if (c == UINT32_MAX || !I) return;
    v3 ref = v3_sub(ring[0], centre);
    double rr = v3_len(ref), s = rr > 0 ? 0.5 / rr : 0.0;
    v3 ax = v3_norm_or_perp(ref, normal), ay = v3_cross(normal, ax);
    float *P = mb->pos + 3 * (size_t)c, *N = mb->nrm + 3 * (size_t)c, *T = mb->uv + 2 * (size_t)c;
    put3(P, centre);
    put3(N, normal);
    T[0] = T[1] = 0.5f;
    for (int j = 0; j <= sides; j++) {
        v3 p = ring[j % sides], d = v3_sub(p, centre);
        put3(P + 3 * (j + 1), p);
        put3(N + 3 * (j + 1), normal);
        T[2 * (j + 1)] = (float)(0.5 + v3_dot(d, ax) * s);
        T[2 * (j + 1) + 1] = (float)(0.5 + v3_dot(d, ay) * s);
    }
    uint32_t first = c + 1;
    for (uint32_t j = 0; j < (uint32_t)sides; j++, I += 3) {
        I[0] = c;
        I[1] = at_end ? first + j : first + j + 1;
        I[2] = at_end ? first + j + 1 : first + j;
    }
}

/* Writes one ring's sides + 1 vertices (the seam repeats vertex 0): its
 * positions, normals and uvs (u round the ring: us, or even steps when
 * NULL; v given). */
static void put_ring(float *P, float *N, float *UV, const v3 *ring, const v3 *nrm, int sides, float v,
                     const float *us) {
    float du = 1.0f / (float)sides;
    for (int j = 0; j <= sides; j++) {
        put3(P + 3 * j, ring[j < sides ? j : 0]);
        UV[2 * j] = us ? us[j] : (float)j * du;
        UV[2 * j + 1] = v;
    }
    for (int j = 0; j <= sides; j++) put3(N + 3 * j, nrm[j < sides ? j : 0]);
}

/* Perimeter of ring (sides vertices, closed) and, when u is not NULL, the
 * arc-length fraction of each vertex (u[sides] = 1, the seam). */
static double ring_perimeter(const v3 *ring, int sides, float *u) {
    double c = 0;
    for (int j = 0; j < sides; j++) {
        if (u) u[j] = (float)c;
        c += v3_dist(ring[j], ring[j + 1 < sides ? j + 1 : 0]);
    }
    if (u) {
        for (int j = 0; j < sides; j++) u[j] = c > 1e-12 ? (float)(u[j] / c) : (float)j / (float)sides;
        u[sides] = 1.0f;
    }
    return c;
}

void tube_sweep_rings(mesh_builder *mb, const v3 *centres, const v3 *rings, uint32_t n, const tube_opts *o) {
    int sides = o->sides;
    if (n < 2 || sides < 3 || sides > 256) return;
    uint32_t nv, ni;
    tube_counts(n, sides, o->cap_start, o->cap_end, &nv, &ni);
    if (mb_reserve(mb, nv, ni)) return;
    /* Per ring: radius (distance of its first vertex), tangent and v
     * (tube_dv: arc length over the local circumference). */
    double rsum = 0;
    for (uint32_t i = 0; i < n; i++) rsum += v3_dist(rings[(size_t)i * sides], centres[i]);
    double r_mean = rsum / n;
    uint32_t ring_len = (uint32_t)sides + 1;
    uint32_t first = mb_vertices(mb, n * ring_len);
    if (first == UINT32_MAX) return;
    float *P = mb->pos + 3 * (size_t)first, *N = mb->nrm + 3 * (size_t)first, *UV = mb->uv + 2 * (size_t)first;
    double vv_acc = o->v_offset, r_prev = v3_dist(rings[0], centres[0]), r_cur = r_prev;
    v3 prevT = v3_norm(v3_sub(centres[n - 1], centres[0]));
    v3 derived[256];
    /* Arc-length uvs: each ring's perimeter and u made once, kept for the
     * next ring's v. */
    int ku = o->u_tiles > 1 ? o->u_tiles : 1;
    float us_buf[257], *us = o->arc_uv || ku > 1 ? us_buf : NULL;
    if (!o->arc_uv && ku > 1) even_u(us_buf, sides, ku);
    double pa = 0;
    for (uint32_t i = 0; i < n; i++, P += 3 * ring_len, N += 3 * ring_len, UV += 2 * ring_len) {
        if (o->arc_uv) { /* the perimeter stands for the circumference */
            double pb = ring_perimeter(rings + (size_t)i * sides, sides, us);
            if (ku > 1)
                for (int j = 0; j <= sides; j++) us[j] *= (float)ku;
            if (i) vv_acc += ku * tube_dv(v3_dist(centres[i], centres[i - 1]), pa / 6.283185307179586,
                                          pb / 6.283185307179586, r_mean);
            pa = pb;
        } else if (i) {
            vv_acc += ku * tube_dv(v3_dist(centres[i], centres[i - 1]),
                                   v3_dist(rings[(size_t)(i - 1) * sides], centres[i - 1]),
                                   v3_dist(rings[(size_t)i * sides], centres[i]), r_mean);
        }
        const v3 *ring = rings + (size_t)i * sides;
        float vv = (float)vv_acc;
        if (o->ring_normals) { /* no tangents but the caps' (below) */
            put_ring(P, N, UV, ring, o->ring_normals + (size_t)i * sides, sides, vv, us);
            continue;
        }
        v3 T = tangent_at(centres, n, i, prevT);
        prevT = T;
        /* A taper tilts the normals along the tube: n = (radial - dr T) /
         * sqrt(1 + dr^2), with dr the radius slope per metre. */
        uint32_t a = i ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
        double r_next = b == i ? r_cur : v3_dist(rings[(size_t)b * sides], centres[b]);
        double ra = a == i ? r_cur : r_prev, rb = b == i ? r_cur : r_next;
        double ds = v3_dist(centres[b], centres[a]);
        double dr = ds > 1e-12 ? (rb - ra) / ds : 0;
        double k = 1.0 / sqrt(1.0 + dr * dr);
        v3 fallback = v3_any_perp(T);
        for (int j = 0; j < sides; j++) {
            v3 radial = v3_sub(ring[j], centres[i]);
            radial = v3_madd(radial, T, -v3_dot(radial, T));
            double l2 = v3_len2(radial);
            radial = l2 > 1e-300 ? v3_scale(radial, 1.0 / sqrt(l2)) : fallback;
            derived[j] = v3_scale(v3_madd(radial, T, -dr), k);
        }
        put_ring(P, N, UV, ring, derived, sides, vv, us);
        r_prev = r_cur;
        r_cur = r_next;
    }
    stitch(mb, first, n, sides);
    if (o->ring_normals) {
        /* The last tangent, which the caps fall back on: its own segment's
         * direction, or where that is degenerate the walk's. */
        v3 d = v3_sub(centres[n - 1], centres[n - 2]);
        if (v3_len(d) > 1e-300) prevT = tangent_at(centres, n, n - 1, prevT);
        else
            for (uint32_t i = 0; i < n; i++) prevT = tangent_at(centres, n, i, prevT);
    }
    if (o->cap_start) cap(mb, rings, centres[0], v3_neg(tangent_at(centres, n, 0, prevT)), sides, 0);
    if (o->cap_end)
        cap(mb, rings + (size_t)(n - 1) * sides, centres[n - 1], tangent_at(centres, n, n - 1, prevT), sides, 1);
}

/* Round ring i: its frame, radius, taper and the widening across a bend. */
typedef struct ring_geom {
    v3 c, T, N, B, bend;
    double ri, dr, k, nb, bb, reach;
} ring_geom;

/* a, b: the unit directions of the segments before and after point i (T
 * where one is degenerate); used only at interior points. */
static inline void ring_setup(ring_geom *g, const v3 *pts, const double *radii, uint32_t n, uint32_t i, v3 T,
                              v3 N, v3 a, v3 b) {
    g->bend = v3_make(0, 0, 0);
    double stretch = 1.0;
    if (i > 0 && i + 1 < n) {
        double c = v3_dot(a, T);
        if (c > 0.2 && c < 0.999999) {
            stretch = 1.0 / c;
            g->bend = v3_norm(v3_sub(b, a));
        }
    }
    g->c = pts[i];
    g->T = T;
    g->N = N;
    g->B = v3_cross(T, N);
    g->ri = radii[i];
    g->dr = tube_taper_slope(pts, radii, n, i);
    g->k = 1.0 / sqrt(1.0 + g->dr * g->dr);
    /* (d . bend)(stretch - 1) for d = c N + s B, split by c and s. */
    g->nb = g->ri * v3_dot(N, g->bend) * (stretch - 1.0);
    g->bb = g->ri * v3_dot(g->B, g->bend) * (stretch - 1.0);
    g->reach = g->ri * stretch;
}

/* Vertex at angle (cosine c, sine s) of a round ring and its normal. */
static inline void ring_vertex(const ring_geom *g, double c, double s, v3 *p, v3 *nr) {
    v3 d = v3_add(v3_scale(g->N, c), v3_scale(g->B, s));
    *p = v3_madd(v3_madd(g->c, d, g->ri), g->bend, c * g->nb + s * g->bb);
    *nr = v3_scale(v3_madd(d, g->T, -g->dr), g->k);
}

/* Round ring i of tube_round_rings; returns its widest reach. */
static double round_ring(const v3 *pts, const double *radii, uint32_t n, uint32_t i, v3 T, v3 N, const double *cs,
                         const double *sn, int sides, v3 *ring, v3 *nr) {
    ring_geom g;
    v3 a = T, b = T;
    if (i > 0 && i + 1 < n) {
        a = v3_norm_or(v3_sub(pts[i], pts[i - 1]), T);
        b = v3_norm_or(v3_sub(pts[i + 1], pts[i]), T);
    }
    ring_setup(&g, pts, radii, n, i, T, N, a, b);
    for (int j = 0; j < sides; j++) ring_vertex(&g, cs[j], sn[j], &ring[j], &nr[j]);
    return g.reach;
}

/* A round ring straight into the mesh, as put_ring would write it (us:
 * its u per vertex, seam included). */
static void put_round_ring(const ring_geom *g, const double *cs, const double *sn, const float *us, int sides,
                           float *P, float *N, float *UV, float v) {
    for (int j = 0; j < sides; j++) {
        v3 p, nr;
        ring_vertex(g, cs[j], sn[j], &p, &nr);
        put3(P + 3 * j, p);
        put3(N + 3 * j, nr);
        UV[2 * j] = us[j];
        UV[2 * j + 1] = v;
    }
    for (int c = 0; c < 3; c++) { /* the seam repeats vertex 0 */
        P[3 * sides + c] = P[c];
        N[3 * sides + c] = N[c];
    }
    UV[2 * sides] = us[sides];
    UV[2 * sides + 1] = v;
}

void tube_round_rings(const v3 *pts, const double *radii, uint32_t n, const v3 *T, const v3 *N, const double *cs,
                      const double *sn, int sides, v3 *rings, v3 *normals, double *extent) {
    for (uint32_t i = 0; i < n; i++) {
        double e = round_ring(pts, radii, n, i, T[i], N[i], cs, sn, sides, rings + (size_t)i * sides,
                              normals + (size_t)i * sides);
        if (extent) extent[i] = e;
    }
}

void tube_sweep(mesh_builder *mb, const v3 *pts, const double *radii, uint32_t n, const tube_opts *o) {
    int sides = o->sides;
    if (n < 2 || sides < 3 || sides > 256 || mb->status) return;
    if (mb->ring_sides != sides) { /* the builder keeps the last table: most tubes repeat it */
        for (int j = 0; j < sides; j++) {
            double a = 6.283185307179586 * j / sides;
            mb->ring_cs[j] = dm_cos(a);
            mb->ring_sn[j] = dm_sin(a);
        }
        float du = 1.0f / (float)sides;
        for (int j = 0; j <= sides; j++) mb->ring_u[j] = (float)j * du; /* as put_ring's */
        mb->ring_sides = sides;
    }
    const double *cs = mb->ring_cs, *sn = mb->ring_sn;
    uint32_t nv, ni, ring_len = (uint32_t)sides + 1;
    tube_counts(n, sides, o->cap_start, o->cap_end, &nv, &ni);
    uint32_t first = mb_reserve(mb, nv, ni) ? UINT32_MAX : mb_vertices(mb, n * ring_len);
    if (first == UINT32_MAX) return;
    /* u: once round, or over u_tiles tiles; v: tube_dv, arc length over
     * the local circumference, times the tiles. */
    int ku = o->u_tiles > 1 ? o->u_tiles : 1;
    float us_k[257];
    const float *us = mb->ring_u;
    if (ku > 1) {
        even_u(us_k, sides, ku);
        us = us_k;
    }
    double rsum = 0, vv = o->v_offset;
    for (uint32_t i = 0; i < n; i++) rsum += radii[i];
    double r_mean = rsum / n;
    /* Frames are walked along with the rings, each ring made straight into
     * the mesh: no scratch per point or per vertex. */
    frame_walk w;
    walk_start(&w, pts, n, o->first_normal);
    v3 T0 = w.T, N0 = w.N;
    for (uint32_t i = 0;; i++) {
        if (i) vv += ku * tube_dv(w.l0, radii[i - 1], radii[i], r_mean);
        size_t at = (size_t)first + (size_t)i * ring_len;
        ring_geom g;
        ring_setup(&g, pts, radii, n, i, w.T, w.N, w.l0 > 1e-300 ? w.u0 : w.T, w.l > 1e-300 ? w.u : w.T);
        put_round_ring(&g, cs, sn, us, sides, mb->pos + 3 * at, mb->nrm + 3 * at, mb->uv + 2 * at,
                       (float)vv);
        if (i + 1 >= n) break;
        walk_next(&w);
    }
    stitch(mb, first, n, sides);
    v3 ring[256], nrm[256];
    if (o->cap_start) {
        round_ring(pts, radii, n, 0, T0, N0, cs, sn, sides, ring, nrm);
        cap(mb, ring, pts[0], v3_neg(T0), sides, 0);
    }
    if (o->cap_end) {
        round_ring(pts, radii, n, n - 1, w.T, w.N, cs, sn, sides, ring, nrm);
        cap(mb, ring, pts[n - 1], w.T, sides, 1);
    }
}

/* Queries on mesh hosts (docs/hosts.md, "Queries"): closest points by
 * Embree's point query with a per-triangle callback, the sign by the
 * closest feature's pseudonormal or by three rays, segment distances and
 * sphere sweeps exact per triangle, first hits by rtcIntersect1. The
 * host set itself is built in hosts.c. */
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "hosts.h"

/* ----------------------------------------------------- closest point */

/* Closest point of triangle abc to p (Ericson, Real-Time Collision
 * Detection 5.1.5). *region: 0 face, 1..3 vertex a, b, c, 4..6 edge ab,
 * bc, ca. */
static v3 closest_on_triangle(v3 p, v3 a, v3 b, v3 c, int *region) {
    v3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) { *region = 1; return a; }
    v3 bp = v3_sub(p, b);
    double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) { *region = 2; return b; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        *region = 4;
        return v3_madd(a, ab, d1 / (d1 - d3));
    }
    v3 cp = v3_sub(p, c);
    double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) { *region = 3; return c; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        *region = 6;
        return v3_madd(a, ac, d2 / (d2 - d6));
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        *region = 5;
        return v3_madd(b, v3_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    double den = 1.0 / (va + vb + vc);
    *region = 0;
    return v3_madd(v3_madd(a, ab, vb * den), ac, vc * den);
}


typedef struct nq_ctx {
    const host_mesh *m;
    v3 p;           /* local */
    double best2;
    v3 q;
    uint32_t prim;
    int region;
} nq_ctx;

static bool nq_cb(struct RTCPointQueryFunctionArguments *a) {
    nq_ctx *c = (nq_ctx *)a->userPtr;
    const uint32_t *t = c->m->tri + 3 * (size_t)a->primID;
    /* The plane is no nearer than the triangle: most leaves end here. */
    double hp = v3_dot(v3_sub(c->p, vtx(c->m, t[0])), f3(c->m->fnrm + 3 * (size_t)a->primID));
    if (hp * hp >= c->best2) return false;
    int region;
    v3 q = closest_on_triangle(c->p, vtx(c->m, t[0]), vtx(c->m, t[1]), vtx(c->m, t[2]), &region);
    double d2 = v3_len2(v3_sub(c->p, q));
    if (d2 < c->best2) {
        c->best2 = d2;
        c->q = q;
        c->prim = a->primID;
        c->region = region;
        a->query->radius = (float)(sqrt(d2) * (1.0 + 1e-6)) + FLT_MIN;
        return true;
    }
    return false;
}

/* The pseudonormal of the closest feature. */
static v3 feature_normal(const host_mesh *m, uint32_t prim, int region) {
    const uint32_t *t = m->tri + 3 * (size_t)prim;
    if (region == 0) return f3(m->fnrm + 3 * (size_t)prim);
    if (region <= 3) return f3(m->vnrm + 3 * (size_t)t[region - 1]);
    /* An edge's: the sum of its two faces' normals (its own face's alone
     * on a hole or a non-manifold edge). */
    v3 n = f3(m->fnrm + 3 * (size_t)prim);
    uint32_t tw = m->twin[3 * (size_t)prim + (size_t)(region - 4)];
    return tw == UINT32_MAX ? n : v3_norm_or(v3_add(n, f3(m->fnrm + 3 * (size_t)(tw / 3))), n);
}

/* ---------------------------------------------------- inside by rays */

typedef struct count_ctx {
    struct RTCIntersectContext ctx; /* first: Embree hands the filter this pointer */
    const host_mesh *m;
    v3 dir;
    int wind, cross;
} count_ctx;

static void count_filter(const struct RTCFilterFunctionNArguments *a) {
    count_ctx *c = (count_ctx *)a->context;
    for (unsigned i = 0; i < a->N; i++) {
        if (!a->valid[i]) continue;
        /* RTCHitN_primID is C++ only: the SOA layout's primID row. */
        unsigned prim = ((const unsigned *)a->hit)[5 * a->N + i];
        double dn = v3_dot(f3(c->m->fnrm + 3 * (size_t)prim), c->dir);
        c->wind += dn > 0 ? 1 : -1; /* leaving the solid counts +1 */
        c->cross++;
        a->valid[i] = 0; /* go on to the next crossing */
    }
}

static int ray_says_inside(const host_mesh *m, v3 pl, v3 dir) {
    count_ctx c;
    rtcInitIntersectContext(&c.ctx);
    c.ctx.filter = count_filter;
    c.m = m;
    c.dir = dir;
    c.wind = c.cross = 0;
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)pl.x, rh.ray.org_y = (float)pl.y, rh.ray.org_z = (float)pl.z;
    rh.ray.dir_x = (float)dir.x, rh.ray.dir_y = (float)dir.y, rh.ray.dir_z = (float)dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1((RTCScene)m->scene, &c.ctx, &rh);
    return m->sign_by_rays == 2 ? (c.cross & 1) : c.wind != 0;
}

/* Three fixed directions off every axis and diagonal: a ray through an
 * edge or a small hole is outvoted by the other two. */
static const double RAY_DIRS[3][3] = {
    {0.2672612419124244, 0.5345224838248488, 0.8017837257372732},
    {-0.8164965809277261, 0.4082482904638631, -0.4082482904638631},
    {0.4364357804719848, -0.8728715609439696, -0.2182178902359924},
};

static int inside_by_rays(const host_mesh *m, v3 pl) {
    int yes = 0;
    for (int k = 0; k < 3; k++) {
        yes += ray_says_inside(m, pl, v3_load(RAY_DIRS[k]));
        if (yes >= 2 || yes + (2 - k) < 2) break; /* decided */
    }
    return yes >= 2;
}

static int outside_bounds(const host_mesh *m, v3 p) {
    return p.x < m->lo.x || p.x > m->hi.x || p.y < m->lo.y || p.y > m->hi.y || p.z < m->lo.z || p.z > m->hi.z;
}

int hmesh_inside(const host_mesh *m, v3 p) {
    if (!m->closed || outside_bounds(m, p)) return 0;
    return inside_by_rays(m, v3_sub(p, m->origin));
}

/* --------------------------------------------------------- queries */

/* The closest triangle to p within cap: c->prim (UINT32_MAX when none),
 * c->best2, c->q and c->region, all relative to m->origin. */
static void point_query(const host_mesh *m, v3 p, double cap, nq_ctx *c) {
    c->m = m;
    c->p = v3_sub(p, m->origin);
    c->best2 = cap < 1e30 ? cap * cap : HUGE_VAL;
    c->prim = UINT32_MAX;
    c->region = 0;
    c->q = c->p;
    struct RTCPointQuery q;
    q.x = (float)c->p.x, q.y = (float)c->p.y, q.z = (float)c->p.z;
    q.time = 0.0f;
    q.radius = cap < 1e30 ? (float)cap : INFINITY;
    struct RTCPointQueryContext qc;
    rtcInitPointQueryContext(&qc);
    rtcPointQuery((RTCScene)m->scene, &q, &qc, nq_cb, c);
}

int hmesh_nearest(const host_mesh *m, v3 p, double cap, mesh_near *out) {
    nq_ctx c;
    point_query(m, p, cap, &c);
    if (c.prim == UINT32_MAX) {
        int in = m->closed && hmesh_inside(m, p);
        out->dist = in ? -cap : cap;
        out->point = p;
        out->normal = v3_make(0, 0, 1);
        out->prim = UINT32_MAX;
        return 0;
    }
    double d = sqrt(c.best2);
    v3 fn = feature_normal(m, c.prim, c.region);
    v3 dp = v3_sub(c.p, c.q);
    int inside = 0;
    if (m->closed && d > 0) inside = m->sign_by_rays ? inside_by_rays(m, c.p) : v3_dot(dp, fn) < 0;
    out->prim = c.prim;
    out->point = v3_add(c.q, m->origin);
    if (d > 1e-12) {
        v3 n = v3_scale(dp, 1.0 / d);
        out->normal = inside ? v3_neg(n) : n;
    } else {
        out->normal = fn;
    }
    out->dist = inside ? -d : d;
    return 1;
}

double hmesh_distance(const host_mesh *m, v3 p, double cap) {
    mesh_near n;
    hmesh_nearest(m, p, cap, &n);
    return n.dist;
}

double hmesh_prim_distance(const host_mesh *m, uint32_t prim, v3 p) {
    const uint32_t *t = m->tri + 3 * (size_t)prim;
    int region;
    v3 pl = v3_sub(p, m->origin);
    return v3_dist(pl, closest_on_triangle(pl, vtx(m, t[0]), vtx(m, t[1]), vtx(m, t[2]), &region));
}

v3 hmesh_prim_closest(const host_mesh *m, uint32_t prim, v3 p) {
    const uint32_t *t = m->tri + 3 * (size_t)prim;
    int region;
    v3 pl = v3_sub(p, m->origin);
    return v3_add(closest_on_triangle(pl, vtx(m, t[0]), vtx(m, t[1]), vtx(m, t[2]), &region), m->origin);
}

double hmesh_udistance(const host_mesh *m, v3 p, double cap, uint32_t *prim) {
    nq_ctx c;
    point_query(m, p, cap, &c);
    if (prim) *prim = c.prim;
    return c.prim == UINT32_MAX ? cap : sqrt(c.best2);
}

int hmesh_segment_hit(const host_mesh *m, v3 a, v3 b, double *t, v3 *normal) {
    v3 al = v3_sub(a, m->origin), d = v3_sub(b, a);
    struct RTCIntersectContext ic;
    rtcInitIntersectContext(&ic);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)al.x, rh.ray.org_y = (float)al.y, rh.ray.org_z = (float)al.z;
    rh.ray.dir_x = (float)d.x, rh.ray.dir_y = (float)d.y, rh.ray.dir_z = (float)d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = 1.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1((RTCScene)m->scene, &ic, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return 0;
    if (t) *t = rh.ray.tfar;
    if (normal) {
        v3 n = f3(m->fnrm + 3 * (size_t)rh.hit.primID);
        *normal = v3_dot(n, d) > 0 ? v3_neg(n) : n;
    }
    return 1;
}

/* ------------------------------------- segments and sweeps, exactly */

/* The distance to one triangle is convex along any line (a triangle is a
 * convex set), so, as for a box, a segment's least distance and a moving
 * sphere's first contact are exact per triangle; the mesh's are the least
 * over the triangles near the segment. Unlike sphere tracing on the
 * (non-convex) mesh distance, this lets a sphere pressed against a surface
 * slide along it. Triangles are found with point queries round the
 * middles of pieces about 2 r (or 2 cap) long, so each query sphere holds
 * few triangles; most are dropped by the capsule's box or their plane. */

/* Squared distance between segments p1-q1 and p2-q2 (Ericson 5.1.9). */
static double seg_seg_dist2(v3 p1, v3 q1, v3 p2, v3 q2) {
    v3 d1 = v3_sub(q1, p1), d2 = v3_sub(q2, p2), r = v3_sub(p1, p2);
    double a = v3_dot(d1, d1), e = v3_dot(d2, d2), f = v3_dot(d2, r), s, t;
    if (a <= 1e-300 && e <= 1e-300) return v3_len2(r);
    if (a <= 1e-300) {
        s = 0;
        t = f / e;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
    } else {
        double c = v3_dot(d1, r);
        if (e <= 1e-300) {
            t = 0;
            s = -c / a;
            s = s < 0 ? 0 : s > 1 ? 1 : s;
        } else {
            double b = v3_dot(d1, d2), den = a * e - b * b;
            s = den > 0 ? (b * f - c * e) / den : 0;
            s = s < 0 ? 0 : s > 1 ? 1 : s;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = -c / a;
                s = s < 0 ? 0 : s > 1 ? 1 : s;
            } else if (t > 1) {
                t = 1;
                s = (b - c) / a;
                s = s < 0 ? 0 : s > 1 ? 1 : s;
            }
        }
    }
    return v3_len2(v3_sub(v3_madd(p1, d1, s), v3_madd(p2, d2, t)));
}

typedef struct tri3 {
    v3 v[3], n; /* local; unit normal in double (the stored float one cannot
                   certify a sphere pressed against the face to 1e-9 r) */
} tri3;

/* Triangle prim, or 0 when it lies outside the box lo-hi (a capsule's). */
static int tri_get(const host_mesh *m, uint32_t prim, v3 lo, v3 hi, tri3 *T) {
    const uint32_t *t = m->tri + 3 * (size_t)prim;
    const float *a = m->pos + 4 * (size_t)t[0], *b = m->pos + 4 * (size_t)t[1], *c = m->pos + 4 * (size_t)t[2];
    if ((a[0] < lo.x && b[0] < lo.x && c[0] < lo.x) || (a[0] > hi.x && b[0] > hi.x && c[0] > hi.x) ||
        (a[1] < lo.y && b[1] < lo.y && c[1] < lo.y) || (a[1] > hi.y && b[1] > hi.y && c[1] > hi.y) ||
        (a[2] < lo.z && b[2] < lo.z && c[2] < lo.z) || (a[2] > hi.z && b[2] > hi.z && c[2] > hi.z))
        return 0;
    T->v[0] = f3(a), T->v[1] = f3(b), T->v[2] = f3(c);
    T->n = v3_norm(v3_cross(v3_sub(T->v[1], T->v[0]), v3_sub(T->v[2], T->v[0])));
    return 1;
}

/* The box round segment a + s d grown by `near`. */
static void capsule_box(v3 a, v3 d, double near, v3 *lo, v3 *hi) {
    v3 b = v3_add(a, d);
    *lo = v3_make(fmin(a.x, b.x) - near, fmin(a.y, b.y) - near, fmin(a.z, b.z) - near);
    *hi = v3_make(fmax(a.x, b.x) + near, fmax(a.y, b.y) + near, fmax(a.z, b.z) + near);
}

/* The triangle cannot come nearer than `near` to segment a + s d: both
 * ends on one side of its plane at least that far. */
static int tri_far(const tri3 *T, v3 a, v3 d, double near) {
    double pa = v3_dot(v3_sub(a, T->v[0]), T->n), pb = pa + v3_dot(d, T->n);
    return (pa >= near && pb >= near) || (pa <= -near && pb <= -near);
}

/* Distance from segment a + s d to triangle T. */
static double tri_seg_dist(const tri3 *T, v3 a, v3 d) {
    double pa = v3_dot(v3_sub(a, T->v[0]), T->n), pd = v3_dot(d, T->n);
    int region;
    if (pd != 0) {
        double s = -pa / pd;
        if (s >= 0 && s <= 1) { /* crosses the plane: through the triangle? */
            v3 x = v3_madd(a, d, s);
            if (v3_len2(v3_sub(x, closest_on_triangle(x, T->v[0], T->v[1], T->v[2], &region))) <= 1e-24) return 0;
        }
    }
    v3 b = v3_add(a, d);
    double best = fmin(v3_len2(v3_sub(a, closest_on_triangle(a, T->v[0], T->v[1], T->v[2], &region))),
                       v3_len2(v3_sub(b, closest_on_triangle(b, T->v[0], T->v[1], T->v[2], &region))));
    for (int k = 0; k < 3; k++) best = fmin(best, seg_seg_dist2(a, b, T->v[k], T->v[(k + 1) % 3]));
    return sqrt(best);
}

typedef struct seg_ctx {
    const host_mesh *m;
    v3 a, d;       /* local */
    v3 lo, hi;     /* the capsule's box at the first cap */
    double best;
    int first;     /* stop at the first triangle below the cap */
} seg_ctx;

static bool seg_cb(struct RTCPointQueryFunctionArguments *q) {
    seg_ctx *c = (seg_ctx *)q->userPtr;
    tri3 T;
    if (!tri_get(c->m, q->primID, c->lo, c->hi, &T) || tri_far(&T, c->a, c->d, c->best)) return false;
    double dist = tri_seg_dist(&T, c->a, c->d);
    if (dist >= c->best) return false;
    c->best = dist;
    if (!c->first) return false;
    q->query->radius = 0.0f; /* any distance below the cap will do: stop looking */
    return true;
}

double hmesh_segment_distance(const host_mesh *m, v3 a, v3 b, double cap, int first) {
    /* In pieces of at most 2 cap (at least 1e-3 of the whole): a query
     * sphere round a long segment's middle would hold many triangles far
     * from it. */
    v3 al = v3_sub(a, m->origin), d = v3_sub(b, a);
    double L = v3_len(d), best = cap;
    int pieces = 1;
    if (cap < 1e30 && L > 2.0 * cap) pieces = L > 2000.0 * cap ? 1000 : (int)ceil(L / (2.0 * cap));
    for (int k = 0; k < pieces && best > 0 && !(first && best < cap); k++) {
        seg_ctx c;
        c.m = m;
        c.a = v3_madd(al, d, (double)k / pieces);
        c.d = v3_scale(d, 1.0 / pieces);
        c.best = best;
        c.first = first;
        capsule_box(c.a, c.d, best < 1e30 ? best : 1e30, &c.lo, &c.hi);
        v3 mid = v3_madd(c.a, c.d, 0.5);
        struct RTCPointQuery q;
        q.x = (float)mid.x, q.y = (float)mid.y, q.z = (float)mid.z;
        q.time = 0.0f;
        q.radius = best < 1e30 ? (float)((0.5 * L / pieces + best) * (1.0 + 1e-6)) : INFINITY;
        struct RTCPointQueryContext qc;
        rtcInitPointQueryContext(&qc);
        rtcPointQuery((RTCScene)m->scene, &q, &qc, seg_cb, &c);
        best = c.best;
    }
    return best;
}

/* f(t) = distance from p + t d to T, less r, and its slope. */
static double tri_f(const tri3 *T, v3 p, v3 d, double t, double r, double *slope, v3 *grad) {
    int region;
    v3 x = v3_madd(p, d, t), q = closest_on_triangle(x, T->v[0], T->v[1], T->v[2], &region), g = v3_sub(x, q);
    double dist = v3_len(g);
    g = dist > 0 ? v3_scale(g, 1.0 / dist) : (v3_dot(d, T->n) > 0 ? v3_neg(T->n) : T->n);
    if (slope) *slope = dist > 0 ? v3_dot(g, d) : -v3_len(d);
    if (grad) *grad = g;
    return dist - r;
}

/* First t in [0, tmax] at which a sphere of radius r moving p -> p + t d
 * gets nearer than r - eps to T, falling (then the t where it is at r), or
 * a value > tmax. Convex f: as trace_box in roots/collide.c. */
static double tri_first_contact(const tri3 *T, v3 p, v3 d, double tmax, double r, double eps, v3 *nh) {
    double L = v3_len(d), g0, gm, f0 = tri_f(T, p, d, 0, r, &g0, nh);
    if (g0 >= -1e-12 * L) return 2.0; /* not falling at 0: never nearer */
    if (f0 < -eps) return 0.0;       /* already touching, moving in */
    double fm = tri_f(T, p, d, tmax, r, &gm, NULL), hi = tmax, fhi = fm;
    if (fm >= -eps) {
        if (gm <= 0) return 2.0; /* falling up to tmax: its least is fm */
        /* The minimum lies inside: bisect on the slope until a point below
         * -eps, or until the tangents at the bracket's ends (f lies above
         * both) prove there is none. */
        double lo = 0, up = tmax, flo = f0, glo = g0, fup = fm, gup = gm;
        int found = 0;
        for (int it = 0; it < 50; it++) {
            double tx = (fup - flo + glo * lo - gup * up) / (glo - gup);
            if (flo + glo * (tx - lo) >= -eps) break;
            double mid = 0.5 * (lo + up), g, f = tri_f(T, p, d, mid, r, &g, NULL);
            if (f < -eps) {
                hi = mid, fhi = f, found = 1;
                break;
            }
            if (g < 0) lo = mid, flo = f, glo = g;
            else up = mid, fup = f, gup = g;
        }
        if (!found) return 2.0;
    }
    /* The crossing of f = 0 between lo (free) and hi: regula falsi, Illinois. */
    double lo = 0, flo = f0 > 0 ? f0 : 0;
    if (f0 <= 0) {
        tri_f(T, p, d, 0, r, NULL, nh);
        return 0.0;
    }
    int side = 0;
    for (int it = 0; it < 80 && hi - lo > 1e-13 * tmax; it++) {
        double mid = lo + (hi - lo) * flo / (flo - fhi);
        if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
        double f = tri_f(T, p, d, mid, r, NULL, NULL);
        if (f < 0) {
            hi = mid, fhi = f;
            if (side == -1) flo *= 0.5;
            side = -1;
        } else {
            lo = mid, flo = f;
            if (side == 1) fhi *= 0.5;
            side = 1;
            if (f < 1e-12 * r) break;
        }
    }
    tri_f(T, p, d, lo, r, NULL, nh);
    return lo;
}

typedef struct sweep_ctx {
    const host_mesh *m;
    v3 p, d;       /* local */
    v3 lo, hi;     /* the swept sphere's box */
    double r, eps, half;
    double t;      /* earliest contact so far */
    v3 n;
} sweep_ctx;

static bool sweep_cb(struct RTCPointQueryFunctionArguments *q) {
    sweep_ctx *c = (sweep_ctx *)q->userPtr;
    tri3 T;
    if (!tri_get(c->m, q->primID, c->lo, c->hi, &T)) return false;
    v3 dd = v3_scale(c->d, c->t);
    if (tri_far(&T, c->p, dd, c->r - c->eps)) return false;
    v3 n;
    double t = tri_first_contact(&T, c->p, c->d, c->t, c->r, c->eps, &n);
    if (t >= c->t) return false;
    c->t = t; /* later triangles are only asked about [0, t] */
    c->n = n;
    return false;
}

double hmesh_sweep(const host_mesh *m, v3 p, v3 d, double r, double eps, v3 *normal) {
    double L = v3_len(d);
    if (!(L > 0)) return 1.0;
    /* In pieces of at most r, the first contact ending the sweep: a query
     * sphere round a long move's middle would hold many triangles far from
     * it (r, not 2 r: a sphere pressed against the surface, the usual case,
     * finds every triangle under its query sphere near enough to test in
     * full; 1.3 % fewer instructions for the default net on a 50k-triangle
     * trunk). */
    int pieces = L > r ? (L > 1000.0 * r ? 1000 : (int)ceil(L / r)) : 1;
    v3 pl = v3_sub(p, m->origin), dp = v3_scale(d, 1.0 / pieces);
    for (int k = 0; k < pieces; k++) {
        sweep_ctx c;
        c.m = m;
        c.p = v3_madd(pl, d, (double)k / pieces);
        c.d = dp;
        c.r = r;
        c.eps = eps;
        c.half = 0.5 * L / pieces;
        c.t = 1.0;
        c.n = v3_make(0, 0, 1);
        capsule_box(c.p, dp, r, &c.lo, &c.hi);
        v3 mid = v3_madd(c.p, dp, 0.5);
        struct RTCPointQuery q;
        q.x = (float)mid.x, q.y = (float)mid.y, q.z = (float)mid.z;
        q.time = 0.0f;
        q.radius = (float)((c.half + r) * (1.0 + 1e-6));
        struct RTCPointQueryContext qc;
        rtcInitPointQueryContext(&qc);
        rtcPointQuery((RTCScene)m->scene, &q, &qc, sweep_cb, &c);
        if (c.t < 1.0) {
            if (normal) *normal = c.n;
            return ((double)k + c.t) / pieces;
        }
    }
    return 1.0;
}

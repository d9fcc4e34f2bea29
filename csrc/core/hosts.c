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
 * wound mesh, whose nonzero value is the union of overlapping shells,
 * else the parity of the crossings. Closest points come from Embree's
 * point query with a per-triangle callback; rays from rtcIntersect1. */
#include "hosts.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"

#define MAX_VERTICES 33554432u /* 2^25 over the whole set */

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

static inline v3 vtx(const host_mesh *m, uint32_t i) {
    const float *f = m->pos + 4 * (size_t)i;
    return v3_make(f[0], f[1], f[2]);
}
static inline v3 f3(const float *f) { return v3_make(f[0], f[1], f[2]); }

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
    return f3(m->enrm + 9 * (size_t)prim + 3 * (size_t)(region - 4));
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

int hmesh_nearest(const host_mesh *m, v3 p, double cap, mesh_near *out) {
    nq_ctx c;
    c.m = m;
    c.p = v3_sub(p, m->origin);
    c.best2 = cap < 1e30 ? cap * cap : HUGE_VAL;
    c.prim = UINT32_MAX;
    c.region = 0;
    c.q = c.p;
    struct RTCPointQuery q;
    q.x = (float)c.p.x, q.y = (float)c.p.y, q.z = (float)c.p.z;
    q.time = 0.0f;
    q.radius = cap < 1e30 ? (float)cap : INFINITY;
    struct RTCPointQueryContext qc;
    rtcInitPointQueryContext(&qc);
    rtcPointQuery((RTCScene)m->scene, &q, &qc, nq_cb, &c);
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

double hmesh_udistance(const host_mesh *m, v3 p, double cap, uint32_t *prim) {
    nq_ctx c;
    c.m = m;
    c.p = v3_sub(p, m->origin);
    c.best2 = cap < 1e30 ? cap * cap : HUGE_VAL;
    c.prim = UINT32_MAX;
    c.region = 0;
    c.q = c.p;
    struct RTCPointQuery q;
    q.x = (float)c.p.x, q.y = (float)c.p.y, q.z = (float)c.p.z;
    q.time = 0.0f;
    q.radius = cap < 1e30 ? (float)cap : INFINITY;
    struct RTCPointQueryContext qc;
    rtcInitPointQueryContext(&qc);
    rtcPointQuery((RTCScene)m->scene, &q, &qc, nq_cb, &c);
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

double hmesh_sweep(const host_mesh *m, v3 p, v3 d, double r, double tol, v3 *normal) {
    double L = v3_len(d), t = 0;
    if (!(L > 0)) return 1.0;
    for (int it = 0; it < 256; it++) {
        mesh_near nr;
        int found = hmesh_nearest(m, v3_madd(p, d, t), (1.0 - t) * L + r + tol, &nr);
        if (!found && nr.dist > 0) return 1.0; /* nothing within the rest of the move */
        double f = nr.dist - r;
        if (f < tol) {
            if (normal) *normal = nr.normal;
            return t;
        }
        t += f / L; /* the distance is 1-Lipschitz: the sphere stays free */
        if (t >= 1.0) return 1.0;
    }
    if (normal) *normal = v3_make(0, 0, 1);
    return t; /* grazing a surface for long: stop where it is still free */
}

/* ------------------------------------- segments and sweeps, exactly */

/* The distance to one triangle is convex along any line (a triangle is a
 * convex set), so, as for a box, a segment's least distance and a moving
 * sphere's first contact are exact per triangle; the mesh's are the least
 * over the triangles near the segment. Unlike sphere tracing on the
 * (non-convex) mesh distance, this lets a sphere pressed against a surface
 * slide along it. Triangles are found with a point query round the
 * segment's middle; most are dropped by their plane or bounding sphere. */

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

double hmesh_sweep_exact(const host_mesh *m, v3 p, v3 d, double r, double eps, v3 *normal) {
    double L = v3_len(d);
    if (!(L > 0)) return 1.0;
    /* In pieces of at most 2 r, the first contact ending the sweep: a query
     * sphere round a long move's middle would hold many triangles far from
     * it. */
    int pieces = L > 2.0 * r ? (L > 2000.0 * r ? 1000 : (int)ceil(L / (2.0 * r))) : 1;
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

/* --------------------------------------------------------- building */

static void mesh_free(host_mesh *m) {
    if (m->scene) rtcReleaseScene((RTCScene)m->scene);
    free(m->pos);
    free(m->tri);
    free(m->fnrm);
    free(m->enrm);
    free(m->vnrm);
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
    uint32_t *slot = malloc(sizeof *slot * cap);
    if (!slot) return 0;
    memset(slot, 0xff, sizeof *slot * cap);
    for (uint32_t i = 0; i < nv; i++) {
        const float *f = pos + 4 * (size_t)i;
        uint32_t b[3];
        memcpy(b, f, sizeof b);
        for (int k = 0; k < 3; k++)
            if (b[k] == 0x80000000u) b[k] = 0; /* -0 == +0 */
        uint32_t h = (b[0] * 73856093u) ^ (b[1] * 19349663u) ^ (b[2] * 83492791u);
        h ^= h >> 15;
        for (uint32_t j = h & (cap - 1);; j = (j + 1) & (cap - 1)) {
            if (slot[j] == UINT32_MAX) {
                slot[j] = i;
                remap[i] = i;
                break;
            }
            const float *g = pos + 4 * (size_t)slot[j];
            if (g[0] == f[0] && g[1] == f[1] && g[2] == f[2]) {
                remap[i] = slot[j];
                break;
            }
        }
    }
    free(slot);
    return 1;
}

static double angle_at(v3 a, v3 b, v3 c) { /* angle at a of triangle abc; float is plenty for a weight */
    v3 u = v3_sub(b, a), v = v3_sub(c, a);
    float cosine = (float)(v3_dot(u, v) / sqrt(v3_len2(u) * v3_len2(v)));
    return acosf(cosine < -1 ? -1 : cosine > 1 ? 1 : cosine);
}

static void store3(float *f, v3 v) {
    f[0] = (float)v.x;
    f[1] = (float)v.y;
    f[2] = (float)v.z;
}

#define MESH_FAIL(code, ...)                                                       \
    do {                                                                           \
        free(remap), free(val), free(up), free(twin), free(vol);      \
        return banyan_fail(err, code, __VA_ARGS__);                                \
    } while (0)

/* Builds host `hi` (mesh number `mi`) into m. */
static banyan_status mesh_build(RTCDevice dev, const banyan_host_mesh *in, uint32_t hi, uint32_t mi, host_mesh *m,
                                banyan_error *err) {
    uint32_t *remap = NULL, *val = NULL, *up = NULL, *twin = NULL;
    double *vol = NULL;
    const uint32_t nv = in->vertex_count, nt_in = in->triangle_count;
    if (nv < 3 || nt_in < 1)
        MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u) is empty: vertex_count = %u, triangle_count = %u (a mesh "
                  "host needs at least 3 vertices and 1 triangle)", hi, mi, nv, nt_in);
    if (!in->positions || !in->indices)
        MESH_FAIL(BANYAN_E_INVALID_ARG, "hosts[%u] (mesh %u): positions or indices is NULL", hi, mi);
    if (in->closed < -1 || in->closed > 1)
        MESH_FAIL(BANYAN_E_RANGE, "hosts[%u] (mesh %u): closed = %d must be -1 (auto), 0 (open) or 1 (closed)", hi,
                  mi, in->closed);
    const double *T = in->transform;
    for (int i = 0; i < 12; i++)
        if (!isfinite(T[i]))
            MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): transform[%d] = %g must be finite", hi, mi, i, T[i]);
    double det = T[0] * (T[5] * T[10] - T[6] * T[9]) - T[1] * (T[4] * T[10] - T[6] * T[8]) +
                 T[2] * (T[4] * T[9] - T[5] * T[8]);
    double mx = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) mx = fmax(mx, fabs(T[4 * r + c]));
    if (!(fabs(det) > 1e-12 * mx * mx * mx) || mx == 0)
        MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): transform is singular (determinant %g); a host needs "
                  "extent on every axis (scale != 0)", hi, mi, det);

    /* World positions checked and bounded, then stored relative to the
     * centre of the bounds. */
    m->pos = malloc(sizeof(float) * 4 * (size_t)nv);
    if (!m->pos) MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] (%u vertices)", hi, nv);
    v3 lo = v3_make(HUGE_VAL, HUGE_VAL, HUGE_VAL), hiw = v3_neg(lo);
    for (uint32_t i = 0; i < nv; i++) {
        const float *p = in->positions + 3 * (size_t)i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): vertex %u = (%g, %g, %g) is not finite", hi, mi, i,
                      p[0], p[1], p[2]);
        v3 w = v3_make(T[0] * p[0] + T[1] * p[1] + T[2] * p[2] + T[3], T[4] * p[0] + T[5] * p[1] + T[6] * p[2] + T[7],
                       T[8] * p[0] + T[9] * p[1] + T[10] * p[2] + T[11]);
        if (!(fabs(w.x) <= 1e6 && fabs(w.y) <= 1e6 && fabs(w.z) <= 1e6))
            MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): vertex %u lies at (%g, %g, %g) m in the world; "
                      "coordinates must be within [-1e6, 1e6] m", hi, mi, i, w.x, w.y, w.z);
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
    double diag = v3_dist(lo, hiw);

    /* Weld, check indices, drop zero-area triangles; mirrored transforms
     * flip the winding so that outward stays outward. */
    remap = malloc(sizeof *remap * (size_t)nv);
    m->tri = malloc(sizeof(uint32_t) * 3 * (size_t)nt_in);
    m->fnrm = malloc(sizeof(float) * 3 * (size_t)nt_in);
    if (!remap || !m->tri || !m->fnrm || !weld(m->pos, nv, remap))
        MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] (%u triangles)", hi, nt_in);
    const int flip = det < 0;
    const double area_eps = 1e-14 * diag * diag;
    uint32_t nt = 0;
    for (uint32_t t = 0; t < nt_in; t++) {
        const uint32_t *ix = in->indices + 3 * (size_t)t;
        for (int k = 0; k < 3; k++)
            if (ix[k] >= nv)
                MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): triangle %u index %u is out of range [0, %u]", hi,
                          mi, t, ix[k], nv - 1);
        uint32_t a = remap[ix[0]], b = remap[ix[flip ? 2 : 1]], c = remap[ix[flip ? 1 : 2]];
        v3 n = v3_cross(v3_sub(vtx(m, b), vtx(m, a)), v3_sub(vtx(m, c), vtx(m, a)));
        double len = v3_len(n);
        if (a == b || b == c || a == c || !(len > area_eps)) continue;
        uint32_t *o = m->tri + 3 * (size_t)nt;
        o[0] = a, o[1] = b, o[2] = c;
        store3(m->fnrm + 3 * (size_t)nt, v3_scale(n, 1.0 / len));
        nt++;
    }
    m->dropped = nt_in - nt;
    if (nt == 0)
        MESH_FAIL(BANYAN_E_BAD_HOST, "hosts[%u] (mesh %u): all %u triangles have zero area", hi, mi, nt_in);
    m->nt = nt;

    /* Edges: the 3 nt sides bucketed by their lower vertex (a counting
     * sort), then matched by their upper vertex inside each small bucket. */
    const size_t ne = 3 * (size_t)nt;
    val = malloc(sizeof *val * ne);
    twin = malloc(sizeof *twin * ne);
    up = malloc(sizeof *up * (size_t)nt);
    uint32_t *start = calloc((size_t)nv + 1, sizeof *start);
    if (!val || !twin || !up || !start) {
        free(start);
        MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] edges", hi);
    }
#define SIDE_B(e) (m->tri[(e) % 3 == 2 ? (e) - 2 : (e) + 1])
#define SIDE_LO(e) (m->tri[e] < SIDE_B(e) ? m->tri[e] : SIDE_B(e))
#define SIDE_HI(e) (m->tri[e] < SIDE_B(e) ? SIDE_B(e) : m->tri[e])
    for (size_t e = 0; e < ne; e++) start[SIDE_LO(e) + 1]++, twin[e] = UINT32_MAX;
    for (uint32_t v = 0; v < nv; v++) start[v + 1] += start[v];
    for (size_t e = 0; e < ne; e++) val[start[SIDE_LO(e)]++] = (uint32_t)e;
    for (uint32_t v = nv; v > 0; v--) start[v] = start[v - 1]; /* back to bucket starts */
    start[0] = 0;
    for (uint32_t t = 0; t < nt; t++) up[t] = t;
    uint32_t boundary = 0, nonmanifold = 0;
    int consistent = 1;
    double boundary_len = 0;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t *b = val + start[v], k = start[v + 1] - start[v];
        for (uint32_t i = 0; i < k; i++) {
            if (b[i] == UINT32_MAX) continue; /* taken by an earlier side */
            uint32_t e0 = b[i], h = SIDE_HI(e0), same = 1, e1 = UINT32_MAX;
            for (uint32_t j = i + 1; j < k; j++) {
                if (b[j] == UINT32_MAX || SIDE_HI(b[j]) != h) continue;
                uint32_t ra = uf_find(up, e0 / 3), rb = uf_find(up, b[j] / 3); /* round one edge: one shell */
                if (ra != rb) up[ra > rb ? ra : rb] = ra < rb ? ra : rb;
                e1 = b[j];
                b[j] = UINT32_MAX;
                same++;
            }
            if (same == 1) {
                boundary++;
                boundary_len += v3_dist(vtx(m, m->tri[e0]), vtx(m, SIDE_B(e0)));
            } else if (same == 2) {
                twin[e0] = e1, twin[e1] = e0;
                if (m->tri[e0] == m->tri[e1]) consistent = 0; /* both sides run the same way */
            } else {
                nonmanifold++;
            }
        }
    }
#undef SIDE_B
#undef SIDE_LO
#undef SIDE_HI
    free(start);
    free(val), val = NULL;
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
    double area = 0;
    for (uint32_t t = 0; t < nt; t++) {
        const uint32_t *ix = m->tri + 3 * (size_t)t;
        area += 0.5 * v3_len(v3_cross(v3_sub(vtx(m, ix[1]), vtx(m, ix[0])), v3_sub(vtx(m, ix[2]), vtx(m, ix[0]))));
    }
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

    /* Pseudonormals: edges from their two faces, vertices by angle. */
    m->enrm = malloc(sizeof(float) * 9 * (size_t)nt);
    m->vnrm = calloc(3 * (size_t)nv, sizeof(float));
    if (!m->enrm || !m->vnrm) MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] normals", hi);
    for (size_t e = 0; e < ne; e++) {
        v3 n = f3(m->fnrm + 3 * (e / 3));
        if (twin[e] != UINT32_MAX) n = v3_norm_or(v3_add(n, f3(m->fnrm + 3 * (twin[e] / 3))), n);
        store3(m->enrm + 3 * e, n);
    }
    {
        double *acc = calloc(3 * (size_t)nv, sizeof *acc);
        if (!acc) MESH_FAIL(BANYAN_E_NOMEM, "out of memory for hosts[%u] normals", hi);
        for (uint32_t t = 0; t < nt; t++) {
            const uint32_t *ix = m->tri + 3 * (size_t)t;
            v3 n = f3(m->fnrm + 3 * (size_t)t), a = vtx(m, ix[0]), b = vtx(m, ix[1]), c = vtx(m, ix[2]);
            double w[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
            for (int k = 0; k < 3; k++) {
                double *s = acc + 3 * (size_t)ix[k];
                s[0] += w[k] * n.x, s[1] += w[k] * n.y, s[2] += w[k] * n.z;
            }
        }
        for (uint32_t i = 0; i < nv; i++) {
            const double *s = acc + 3 * (size_t)i;
            store3(m->vnrm + 3 * (size_t)i, v3_norm(v3_make(s[0], s[1], s[2])));
        }
        free(acc);
    }
    free(remap), remap = NULL;
    free(up), up = NULL;
    free(twin), twin = NULL;
    free(vol), vol = NULL;

    /* The BVH. */
    RTCScene sc = rtcNewScene(dev);
    if (!sc) MESH_FAIL(BANYAN_E_NOMEM, "Embree could not make a scene for hosts[%u]", hi);
    m->scene = sc;
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    /* Embree's Morton builder (LOW) for big sculpts, twice as fast to build;
     * the SAH tree (MEDIUM), a little faster to query, below 200k. */
    rtcSetSceneBuildQuality(sc, nt > 200000 ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) MESH_FAIL(BANYAN_E_NOMEM, "Embree could not make a geometry for hosts[%u]", hi);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m->pos, 0, 4 * sizeof(float), nv);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->tri, 0, 3 * sizeof(uint32_t), nt);
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    enum RTCError e = rtcGetDeviceError(dev);
    if (e != RTC_ERROR_NONE)
        MESH_FAIL(e == RTC_ERROR_OUT_OF_MEMORY ? BANYAN_E_NOMEM : BANYAN_E_INTERNAL,
                  "Embree failed to build hosts[%u] (error %d)", hi, (int)e);
    return BANYAN_OK;
}

static void box_bounds(const obb *o, v3 *lo, v3 *hi) {
    v3 e = v3_make(0, 0, 0);
    for (int k = 0; k < 3; k++) {
        e.x += fabs(o->ax[k].x) * o->h[k];
        e.y += fabs(o->ax[k].y) * o->h[k];
        e.z += fabs(o->ax[k].z) * o->h[k];
    }
    *lo = v3_sub(o->c, e);
    *hi = v3_add(o->c, e);
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
        box_bounds(&H->boxes[i], &H->lo[i], &H->hi[i]);
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
    *out = H;
    banyan_error_clear(err);
    return BANYAN_OK;
fail:
    banyan_hosts_free(H);
    return s;
}

banyan_status hosts_from_boxes(const banyan_box *boxes, uint32_t n, banyan_hosts **out, banyan_error *err) {
    return banyan_hosts_create(boxes, n, NULL, 0, out, err);
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
    const double lo[3] = {H->lo[index].x, H->lo[index].y, H->lo[index].z};
    const double hi[3] = {H->hi[index].x, H->hi[index].y, H->hi[index].z};
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
    set_nearest(H, v3_load(p), max_distance, hit);
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
    v3 a = v3_load(origin), d = v3_load(dir);
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
    v3 p = v3_load(from), d = v3_sub(v3_load(to), p);
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
        double t = hmesh_sweep(&H->meshes[i], p, v3_scale(d, best), radius, tol, NULL) * best;
        if (t < best || (which < 0 && t < 1.0)) best = t, which = (int)(H->n_boxes + i);
    }
    if (which >= 0) {
        banyan_host_hit near;
        hit_clear(&near);
        v3 at = v3_madd(p, d, best);
        set_nearest(H, at, HUGE_VAL, &near);
        hit_store(hit, which, near.primitive, best, v3_load(near.point), v3_load(near.normal));
    }
    banyan_error_clear(err);
    return BANYAN_OK;
}

int32_t banyan_hosts_inside(const banyan_hosts *H, const double p[3]) {
    if (!H || !p) return 0;
    v3 q = v3_load(p);
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

/* Collision queries of the roots generator: the sphere of radius r against
 * the hosts and the ground (spec roots.md 1, "Collision", and the hard
 * invariant; spec README "Hosts": distances and contact on the real
 * surface). The spec's face test (d < r with the foot point inside the
 * face) misses spheres that reach past an edge or a corner, and boxes a
 * long move jumps over; here every test uses the exact signed distance to
 * the host and traces whole moves, so a point the walk accepts is never
 * closer than r to any host.
 * Boxes come first, each query exactly as before mesh hosts existed: the
 * distance to a convex box is convex along a line, which makes the traces
 * exact up to bisection. A mesh (hosts/hosts.h) is not convex, but each of
 * its triangles is: moves and segments are taken exactly per triangle
 * (hmesh_sweep, hmesh_segment_distance), so a sphere pressed against
 * a mesh slides along it as along a box, which sphere tracing on the
 * mesh's (1-Lipschitz, non-convex) distance cannot do. Nearby-obstacle
 * bounds use the Lipschitz ball. Each mesh query is capped at the range
 * that can change the answer. */
#include "roots_internal.h"

/* Signed distance to the box and the outward unit normal of its distance
 * field (as obb_signed_distance / obb_closest_surface, in one pass). */
static inline double box_sd(const obb *o, v3 p, v3 *n) {
    v3 d = v3_sub(p, o->c);
    double lx = v3_dot(d, o->ax[0]), ly = v3_dot(d, o->ax[1]), lz = v3_dot(d, o->ax[2]);
    double qx = fabs(lx) - o->h[0], qy = fabs(ly) - o->h[1], qz = fabs(lz) - o->h[2];
    double mx = qx > 0 ? qx : 0, my = qy > 0 ? qy : 0, mz = qz > 0 ? qz : 0;
    double out2 = mx * mx + my * my + mz * mz;
    if (out2 > 0) {
        double inv = 1.0 / sqrt(out2);
        v3 nn = v3_scale(o->ax[0], copysign(mx * inv, lx));
        nn = v3_madd(nn, o->ax[1], copysign(my * inv, ly));
        *n = v3_madd(nn, o->ax[2], copysign(mz * inv, lz));
        return out2 * inv;
    }
    /* Inside: the nearest face (ties go to the lower axis). */
    if (qx >= qy && qx >= qz) {
        *n = v3_scale(o->ax[0], copysign(1.0, lx));
        return qx;
    }
    if (qy >= qz) {
        *n = v3_scale(o->ax[1], copysign(1.0, ly));
        return qy;
    }
    *n = v3_scale(o->ax[2], copysign(1.0, lz));
    return qz;
}

/* Signed distance only. */
static inline double box_dist(const obb *o, v3 p) {
    v3 d = v3_sub(p, o->c);
    double qx = fabs(v3_dot(d, o->ax[0])) - o->h[0];
    double qy = fabs(v3_dot(d, o->ax[1])) - o->h[1];
    double qz = fabs(v3_dot(d, o->ax[2])) - o->h[2];
    double inside = qx > qy ? (qx > qz ? qx : qz) : (qy > qz ? qy : qz);
    if (inside <= 0) return inside;
    qx = qx > 0 ? qx : 0;
    qy = qy > 0 ? qy : 0;
    qz = qz > 0 ? qz : 0;
    return sqrt(qx * qx + qy * qy + qz * qz);
}

#define MESH_SIGN_REACH 2.0

/* Queries go to the nearest triangle of the last point asked on mesh j
 * first: the surface is no farther than it, so the query's cap shrinks to
 * that (Embree then visits the few leaves round it). Embree holds the
 * query's centre and radius in float: the margin covers their rounding,
 * and a query that still finds nothing is asked again at the full cap. */
static inline double hint_cap(const roots_world *w, uint32_t j, v3 p, double cap) {
    uint32_t h = w->hint[j];
    if (h == UINT32_MAX) return cap;
    const host_mesh *m = &w->meshes[j];
    v3 l = v3_sub(p, m->origin);
    double d = hmesh_prim_distance(m, h, p);
    double c = d * (1.0 + 1e-6) + 1e-6 * (fabs(l.x) + fabs(l.y) + fabs(l.z)) + 1e-9;
    return c < cap ? c : cap;
}

/* Signed distance to mesh j, exact where it is below cap (> 0) or
 * negative (without n, a point deeper inside than MESH_SIGN_REACH r or cap
 * may get that depth instead: an upper bound); cap, a lower bound, where
 * it is not. *n (when non-NULL) gets the distance-field normal when the
 * value is below cap. A point outside the mesh's bounds grown by cap is
 * farther than cap from it. */
static double mesh_clear(const roots_world *w, uint32_t j, v3 p, double cap, v3 *n) {
    const host_mesh *m = &w->meshes[j];
    if (hosts_far_from(w->set, w->n_hosts + j, p, cap)) return cap;
    /* A query that finds nothing within its cap decides the sign with rays;
     * one that finds a surface, with its pseudonormal: look at least
     * MESH_SIGN_REACH r far, where the roots mostly are. */
    double q = cap > MESH_SIGN_REACH * w->r ? cap : MESH_SIGN_REACH * w->r;
    double qh = hint_cap(w, j, p, q);
    mesh_near nr;
    if (!(qh < q && hmesh_nearest(m, p, qh, &nr)) && !hmesh_nearest(m, p, q, &nr)) {
        if (nr.dist >= 0) return cap;
        if (!n) return nr.dist; /* deeper inside than q: -q bounds it, which is all a free test needs */
        hmesh_nearest(m, p, HUGE_VAL, &nr); /* how deep, and which way out */
    }
    w->hint[j] = nr.prim;
    if (nr.dist >= cap) return cap;
    if (n) *n = nr.normal;
    return nr.dist;
}

/* Unsigned distance to mesh j from a point known to be outside it (or on
 * either side of an open mesh): exact below cap, cap beyond. No inside
 * test, which costs rays (hmesh_udistance). A point within the free ball
 * of a point known to be outside is outside too. */
static double mesh_uclear(const roots_world *w, uint32_t j, v3 p, double cap) {
    if (hosts_far_from(w->set, w->n_hosts + j, p, cap)) return cap;
    uint32_t prim = UINT32_MAX;
    double hc = hint_cap(w, j, p, cap), d = hc < cap ? hmesh_udistance(&w->meshes[j], p, hc, &prim) : cap;
    if (prim == UINT32_MAX) d = hmesh_udistance(&w->meshes[j], p, cap, &prim);
    if (prim == UINT32_MAX) return cap;
    w->hint[j] = prim;
    return d < cap ? d : cap;
}

/* The cap for a mesh query that only matters below `best` and `range`:
 * below best (> 0) only an inside point can matter, which any small cap
 * finds. */
static inline double mesh_cap(const roots_world *w, double best, double range) {
    double c = best < range ? best : range;
    return c > w->eps ? c : w->eps;
}

/* Least clearance over the ground (when with_ground) and the boxes. */
static inline double boxes_clearance(const roots_world *w, v3 p, int with_ground) {
    double best = w->ground && with_ground ? p.z - w->ground_z : 1e300;
    for (uint32_t i = 0; i < w->n_hosts; i++) {
        double c = box_dist(&w->hosts[i], p);
        if (c < best) best = c;
    }
    return best;
}

double world_clearance_in(const roots_world *w, v3 p, int with_ground, double range, v3 *normal, int *which) {
    if (!normal && !which) {
        double best = boxes_clearance(w, p, with_ground);
        for (uint32_t j = 0; j < w->n_meshes; j++) {
            double c = mesh_clear(w, j, p, mesh_cap(w, best, range), NULL);
            if (c < best) best = c;
        }
        return best;
    }
    double best = 1e300;
    v3 bn = v3_make(0, 0, 1);
    int bw = -2;
    if (w->ground && with_ground) {
        best = p.z - w->ground_z;
        bw = -1;
    }
    for (uint32_t i = 0; i < w->n_hosts; i++) {
        v3 n;
        double c = box_sd(&w->hosts[i], p, &n);
        if (c < best) {
            best = c;
            bn = n;
            bw = (int)i;
        }
    }
    for (uint32_t j = 0; j < w->n_meshes; j++) {
        double cap = mesh_cap(w, best, range);
        v3 n;
        double c = mesh_clear(w, j, p, cap, &n);
        if (c < cap && c < best) {
            best = c;
            bn = n;
            bw = (int)(w->n_hosts + j);
        }
    }
    if (normal) *normal = bn;
    if (which) *which = bw;
    return best;
}

double world_clearance_boxes(const roots_world *w, v3 p) { return boxes_clearance(w, p, 1); }

double world_clearance_outside(const roots_world *w, v3 p, double range) {
    double best = world_clearance_boxes(w, p);
    for (uint32_t j = 0; j < w->n_meshes; j++) {
        double c = mesh_uclear(w, j, p, mesh_cap(w, best, range));
        if (c < best) best = c;
    }
    return best;
}

v3 world_spoke(const roots_world *w, v3 c, v3 q) {
    double reach = v3_dist(c, q), t_min = 1.0;
    for (uint32_t j = 0; j < w->n_meshes; j++) {
        double t;
        v3 n;
        if (hosts_far_from(w->set, w->n_hosts + j, c, reach)) continue;
        if (hmesh_segment_hit(&w->meshes[j], c, q, &t, &n) && t < t_min) t_min = t;
    }
    /* just short of the surface: 1e-6 of the spoke */
    return t_min < 1.0 ? v3_lerp(c, q, t_min * (1.0 - 1e-6)) : q;
}

/* First t where the sphere along p + t d comes closer than r to box o, or
 * 1; *nh = normal at the last free position. */
static double trace_box(const obb *o, v3 p, v3 d, double L, double r, v3 *nh) {
    v3 n0, n1, n;
    double f0 = box_sd(o, p, &n0) - r;
    if (f0 > L) return 1.0; /* out of reach: the distance is 1-Lipschitz */
    double g0 = v3_dot(n0, d);
    if (g0 >= -1e-12 * L) return 1.0; /* convex and not falling at 0 */
    if (f0 < -1e-9 * r) {             /* already touching: no progress */
        *nh = n0;
        return 0.0;
    }
    double f1 = box_sd(o, v3_add(p, d), &n1) - r, hi = 1.0, fhi = f1;
    if (f1 >= 0) {
        if (v3_dot(n1, d) <= 0) return 1.0; /* still falling at 1: the minimum is f1 >= 0 */
        /* The minimum lies inside: bisect on the slope, stop at the first
         * point below r. */
        double a = 0, b = 1;
        int found = 0;
        for (int it = 0; it < 40; it++) {
            double m = 0.5 * (a + b);
            double f = box_sd(o, v3_madd(p, d, m), &n) - r;
            if (f < 0) {
                hi = m;
                fhi = f;
                found = 1;
                break;
            }
            if (v3_dot(n, d) < 0) a = m;
            else b = m;
        }
        if (!found) return 1.0;
    }
    /* The crossing between lo (free) and hi (touching): regula falsi with
     * the Illinois step, exact at once where the distance is linear (a
     * face), a few steps round an edge; bisection would take ~36. */
    double lo = 0, flo = f0 > 0 ? f0 : 0;
    int side = 0;
    for (int it = 0; it < 80 && hi - lo > 1e-13; it++) {
        double m = lo + (hi - lo) * flo / (flo - fhi);
        if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
        double f = box_dist(o, v3_madd(p, d, m)) - r;
        if (f < 0) {
            hi = m;
            fhi = f;
            if (side == -1) flo *= 0.5;
            side = -1;
        } else {
            lo = m;
            flo = f;
            if (side == 1) fhi *= 0.5;
            side = 1;
            if (f < 1e-12 * r) break; /* free, and touching within 1e-12 r */
        }
    }
    box_sd(o, v3_madd(p, d, lo), nh);
    return lo;
}

double world_trace_ex(const roots_world *w, v3 p, v3 d, int meshes_free, v3 *normal, int *which) {
    double L = v3_len(d), best = 1.0;
    v3 bn = v3_make(0, 0, 1);
    int bw = -2;
    if (L <= 0) {
        if (normal) *normal = bn;
        if (which) *which = bw;
        return 1.0;
    }
    if (w->ground && d.z < 0) {
        double f0 = p.z - w->ground_z - w->r;
        if (f0 + d.z < 0) {
            double t = f0 > 0 ? f0 / -d.z : 0.0;
            if (t < best) {
                best = t;
                bw = -1;
            }
        }
    }
    for (uint32_t i = 0; i < w->n_hosts && best > 0; i++) {
        v3 n = bn;
        double t = trace_box(&w->hosts[i], p, d, L, w->r, &n);
        if (t < best) {
            best = t;
            bn = n;
            bw = (int)i;
        }
    }
    /* Meshes: exact per triangle (convex, as a box), over the part of the
     * move still free. */
    for (uint32_t j = 0; j < w->n_meshes && best > 0 && !meshes_free; j++) {
        if (hosts_far_from(w->set, w->n_hosts + j, p, L * best + w->r)) continue;
        v3 n = bn;
        double t = best * hmesh_sweep(&w->meshes[j], p, v3_scale(d, best), w->r, w->eps, &n);
        if (t < best) {
            best = t;
            bn = n;
            bw = (int)(w->n_hosts + j);
        }
    }
    if (bw == -1) bn = v3_make(0, 0, 1);
    if (normal) *normal = bn;
    if (which) *which = bw;
    return best;
}

/* Least signed distance to box o along a -> a + d (convex: bisect on the
 * slope). Stops early with a value below `stop` once one is found, or
 * with a lower bound >= stop once the tangents at the bracket's ends prove
 * the minimum cannot go below it. */
static double segment_box(const obb *o, v3 a, v3 d, double L, double stop) {
    v3 n;
    double fa = box_sd(o, a, &n);
    if (fa - L >= stop) return fa - L;
    double ga = v3_dot(n, d);
    v3 nb;
    double fb = box_sd(o, v3_add(a, d), &nb), gb = v3_dot(nb, d);
    double best = fa < fb ? fa : fb;
    if (best < stop || ga >= 0 || gb <= 0) return best;
    double lo = 0, hi = 1, flo = fa, glo = ga, fhi = fb, ghi = gb;
    for (int it = 0; it < 50; it++) {
        /* Convexity: f >= both tangent lines; they cross at the bound. */
        double tx = (fhi - flo + glo * lo - ghi * hi) / (glo - ghi);
        double bound = flo + glo * (tx - lo);
        if (bound >= stop) return bound < best ? bound : best;
        double m = 0.5 * (lo + hi);
        double f = box_sd(o, v3_madd(a, d, m), &n), g = v3_dot(n, d);
        if (f < best) best = f;
        if (best < stop) break;
        if (g < 0) lo = m, flo = f, glo = g;
        else hi = m, fhi = f, ghi = g;
    }
    return best;
}

double world_segment_clearance(const roots_world *w, v3 a, v3 b, double stop) {
    v3 d = v3_sub(b, a);
    double L = v3_len(d), best = 1e300;
    if (w->ground) best = (a.z < b.z ? a.z : b.z) - w->ground_z;
    for (uint32_t i = 0; i < w->n_hosts && best >= stop; i++) {
        double c = segment_box(&w->hosts[i], a, d, L, stop);
        if (c < best) best = c;
    }
    /* Meshes: the segment's exact unsigned distance (a lies outside every
     * closed mesh: callers pass free points), so stop is a lower bound
     * when nothing is nearer. */
    for (uint32_t j = 0; j < w->n_meshes && best >= stop && stop > 0; j++) {
        if (hosts_far_from(w->set, w->n_hosts + j, a, L + stop)) continue;
        double c = hmesh_segment_distance(&w->meshes[j], a, b, stop, 1);
        if (c < best) best = c;
    }
    return best;
}

int world_near(const roots_world *w, v3 p, double range, double *c, v3 *n, int cap) {
    int k = 0;
    if (w->ground && p.z - w->ground_z < range && k < cap) {
        c[k] = p.z - w->ground_z;
        n[k++] = v3_make(0, 0, 1);
    }
    for (uint32_t i = 0; i < w->n_hosts && k < cap; i++) {
        v3 nn;
        double d = box_sd(&w->hosts[i], p, &nn);
        if (d < range) {
            c[k] = d;
            n[k++] = nn;
        }
    }
    for (uint32_t j = 0; j < w->n_meshes && k < cap && range > 0; j++) {
        double d = mesh_uclear(w, j, p, range); /* p is free: outside */
        if (d < range) { /* n = 0 marks the Lipschitz bound clearance(p + o) >= d - |o| */
            c[k] = d;
            n[k++] = v3_make(0, 0, 0);
        }
    }
    return k;
}

double world_segment_deepest(const roots_world *w, v3 a, v3 b, double *t_min) {
    v3 d = v3_sub(b, a), n;
    double best = 1e300, bt = 0.5;
    if (w->ground) {
        best = (a.z < b.z ? a.z : b.z) - w->ground_z;
        bt = a.z < b.z ? 0.0 : 1.0;
    }
    for (uint32_t i = 0; i < w->n_hosts; i++) {
        const obb *o = &w->hosts[i];
        double lo = 0, hi = 1;
        box_sd(o, a, &n);
        if (v3_dot(n, d) >= 0) hi = 0; /* rising from a: the minimum is at a */
        else {
            box_sd(o, b, &n);
            if (v3_dot(n, d) <= 0) lo = 1; /* falling up to b */
        }
        for (int it = 0; it < 16 && hi - lo > 1e-9; it++) { /* a split point needs no more */
            double m = 0.5 * (lo + hi);
            box_sd(o, v3_madd(a, d, m), &n);
            if (v3_dot(n, d) < 0) lo = m;
            else hi = m;
        }
        double t = 0.5 * (lo + hi), c = box_dist(o, v3_madd(a, d, t));
        if (c < best) {
            best = c;
            bt = t;
        }
    }
    /* Meshes. A segment that crosses the surface goes deepest about the
     * middle of the part between its first and last crossing (two rays;
     * for a thin open wall, the crossing). One that does not stays on a's
     * side: the least of 9 unsigned samples, refined by golden-section
     * search within one spacing (a local minimum: a split point needs no
     * more). */
    enum { SAMPLES = 8 };
    double L = v3_len(d);
    for (uint32_t j = 0; j < w->n_meshes; j++) {
        const host_mesh *m = &w->meshes[j];
        if (hosts_far_from(w->set, w->n_hosts + j, a, L + (best > 0 ? best : 0))) continue;
        double t1, t2, mb, mt;
        v3 hn;
        if (hmesh_segment_hit(m, a, b, &t1, &hn)) {
            if (!hmesh_segment_hit(m, b, a, &t2, &hn)) t2 = 1.0 - t1;
            mt = 0.5 * (t1 + (1.0 - t2));
            mb = mesh_clear(w, j, v3_madd(a, d, mt), HUGE_VAL, NULL);
        } else {
            double cap = best < L + w->r ? best : L + w->r;
            if (cap < w->eps) cap = w->eps;
            mb = 1e300, mt = 0.5;
            for (int k = 0; k <= SAMPLES; k++) {
                double t = (double)k / SAMPLES, c = mesh_uclear(w, j, v3_madd(a, d, t), cap);
                if (c < mb) mb = c, mt = t;
            }
            if (!(mb < best)) continue;
            /* Exact over the window: within it the distance stays below mb + L / SAMPLES. */
            cap = mb + L / SAMPLES + w->r;
            double lo = mt - 1.0 / SAMPLES, hi = mt + 1.0 / SAMPLES;
            if (lo < 0) lo = 0;
            if (hi > 1) hi = 1;
            const double g = 0.6180339887498949;
            double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
            double f1 = mesh_uclear(w, j, v3_madd(a, d, x1), cap), f2 = mesh_uclear(w, j, v3_madd(a, d, x2), cap);
            for (int it = 0; it < 8; it++) {
                if (f1 < f2) {
                    hi = x2, x2 = x1, f2 = f1;
                    x1 = hi - g * (hi - lo);
                    f1 = mesh_uclear(w, j, v3_madd(a, d, x1), cap);
                } else {
                    lo = x1, x1 = x2, f1 = f2;
                    x2 = lo + g * (hi - lo);
                    f2 = mesh_uclear(w, j, v3_madd(a, d, x2), cap);
                }
            }
            if (f1 < mb) mb = f1, mt = x1;
            if (f2 < mb) mb = f2, mt = x2;
        }
        if (mb < best) {
            best = mb;
            bt = mt;
        }
    }
    if (t_min) *t_min = bt;
    return best;
}

/* How bad a candidate position is: its displacement plus what it still
 * lacks of clearance r, weighted: a deficit left now costs another push,
 * which may undo this one (a trunk's bottom face lies on the ground). */
static double push_score(const roots_world *w, v3 from, v3 to) {
    double c = world_clearance(w, to, NULL, NULL);
    return v3_dist(from, to) + (c < w->r ? 4.0 * (w->r - c) : 0.0);
}

int world_push_out(const roots_world *w, v3 *p) {
    int moved = 0;
    for (int it = 0; it < 16; it++) {
        v3 n;
        int which;
        double c = world_clearance_in(w, *p, 1, w->r, &n, &which);
        if (c >= w->r - w->eps) return moved;
        /* Along the distance-field normal of the worst obstacle... */
        v3 best = v3_madd(*p, n, w->r - c);
        if (which >= 0 && (uint32_t)which < w->n_hosts) {
            /* ...or out through any face of that host: the nearest face can
             * lead into the ground or another host (a trunk's bottom face
             * lies on the ground), so take the exit that costs least. */
            const obb *o = &w->hosts[which];
            v3 l = obb_to_local(o, *p);
            double lc[3] = {l.x, l.y, l.z}, bs = push_score(w, *p, best);
            /* the exit's distance is |e[k] - lc[k]| up to rounding: this
             * margin (far above it) lets far faces go without their point */
            double slack = 1e-9 * (fabs(l.x) + fabs(l.y) + fabs(l.z) + o->h[0] + o->h[1] + o->h[2] + w->r);
            for (int f = 0; f < 6; f++) {
                int k = f / 2;
                double e[3] = {lc[0], lc[1], lc[2]};
                e[k] = (f & 1 ? 1.0 : -1.0) * (o->h[k] + w->r);
                if ((f & 1) ? lc[k] > e[k] : lc[k] < e[k]) continue; /* already beyond that face */
                if (fabs(e[k] - lc[k]) - slack >= bs) continue;
                v3 q = obb_to_world(o, v3_make(e[0], e[1], e[2]));
                /* The score is the distance plus a penalty >= 0: a face no
                 * nearer than the best score cannot beat it (no query). */
                if (v3_dist(*p, q) >= bs) continue;
                double s = push_score(w, *p, q);
                if (s < bs) {
                    bs = s;
                    best = q;
                }
            }
        }
        *p = best;
        moved = 1;
    }
    {
        /* Still stuck in a crowded corner: the nearest free point among 26
         * directions at growing distances. */
        v3 start = *p;
        for (int k = 0; k < 24; k++) {
            double rho = w->r * 0.25 * (double)(1 << k);
            for (int dz = -1; dz <= 1; dz++)
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        if (!dx && !dy && !dz) continue;
                        v3 q = v3_madd(start, v3_norm(v3_make(dx, dy, dz)), rho);
                        if (world_free(w, q)) {
                            *p = q;
                            return 1;
                        }
                    }
        }
    }
    /* Crowded corner between hosts: rise above every host still in the way.
     * Each round clears one host for good, so this ends. */
    for (uint32_t round = 0; round <= w->n_hosts + w->n_meshes + 1; round++) {
        int changed = 0;
        if (w->ground && p->z < w->ground_z + w->r) {
            p->z = w->ground_z + w->r;
            changed = 1;
        }
        for (uint32_t i = 0; i < w->n_hosts; i++) {
            const obb *o = &w->hosts[i];
            v3 n;
            if (box_sd(o, *p, &n) >= w->r - w->eps) continue;
            double top = o->c.z + fabs(o->ax[0].z) * o->h[0] + fabs(o->ax[1].z) * o->h[1] +
                         fabs(o->ax[2].z) * o->h[2] + w->r * (1.0 + 1e-9);
            if (p->z < top) {
                p->z = top;
                changed = 1;
            }
        }
        for (uint32_t j = 0; j < w->n_meshes; j++) {
            if (mesh_clear(w, j, *p, w->r, NULL) >= w->r - w->eps) continue;
            double top = w->set->hi[w->n_hosts + j].z + w->r * (1.0 + 1e-9);
            if (p->z < top) {
                p->z = top;
                changed = 1;
            }
        }
        if (!changed) break;
    }
    return 1;
}

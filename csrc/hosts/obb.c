/* Oriented-box queries; see obb.h. Everything works in the box's local
 * frame, where the box is [-h, h]^3. Also the public box calls
 * (banyan_box_make, banyan_box_validate). */
#include "obb.h"

#include "base/error.h"

banyan_status obb_from_box(const banyan_box *b, uint32_t index, obb *out, banyan_error *err) {
    if (!b) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts[%u] is NULL", index);
    for (int i = 0; i < 3; i++) {
        if (!isfinite(b->center[i]) || fabs(b->center[i]) > 1e6)
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].center[%d] = %g must be finite, within [-1e6, 1e6] m",
                               index, i, b->center[i]);
        if (!isfinite(b->half[i]) || b->half[i] < 1e-6 || b->half[i] > 1e6)
            return banyan_fail(err, BANYAN_E_BAD_HOST,
                               "hosts[%u].half[%d] = %g must be within [1e-6, 1e6] m (a box needs extent on every axis)",
                               index, i, b->half[i]);
    }
    for (int i = 0; i < 9; i++)
        if (!isfinite(b->rotation[i]))
            return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation[%d] = %g must be finite", index, i,
                               b->rotation[i]);
    m3 r = m3_load(b->rotation);
    for (int c = 0; c < 3; c++) {
        v3 a = m3_col(&r, c);
        for (int d = c; d < 3; d++) {
            double dot = v3_dot(a, m3_col(&r, d)), want = c == d ? 1.0 : 0.0;
            if (fabs(dot - want) > 1e-3)
                return banyan_fail(err, BANYAN_E_BAD_HOST,
                                   "hosts[%u].rotation is not orthonormal (column %d . column %d = %g, want %g); "
                                   "fold scale into half",
                                   index, c, d, dot, want);
        }
    }
    if (m3_det(&r) < 0)
        return banyan_fail(err, BANYAN_E_BAD_HOST, "hosts[%u].rotation has determinant %g; a mirrored box must be "
                           "given as a proper rotation (det +1)", index, m3_det(&r));
    out->c = v3_load(b->center);
    for (int i = 0; i < 3; i++) {
        out->ax[i] = v3_norm(m3_col(&r, i));
        out->h[i] = b->half[i];
    }
    return BANYAN_OK;
}

int obb_contains(const obb *o, v3 p, double margin) {
    v3 l = obb_to_local(o, p);
    return fabs(l.x) <= o->h[0] + margin && fabs(l.y) <= o->h[1] + margin && fabs(l.z) <= o->h[2] + margin;
}

static double clampd(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

v3 obb_closest_point(const obb *o, v3 p) {
    v3 l = obb_to_local(o, p);
    l = v3_make(clampd(l.x, -o->h[0], o->h[0]), clampd(l.y, -o->h[1], o->h[1]), clampd(l.z, -o->h[2], o->h[2]));
    return obb_to_world(o, l);
}

v3 obb_closest_surface(const obb *o, v3 p, v3 *normal) {
    return obb_closest_surface_local(o, p, obb_to_local(o, p), normal);
}

v3 obb_closest_surface_local(const obb *o, v3 p, v3 l, v3 *normal) {
    double c[3] = {l.x, l.y, l.z};
    int outside = 0;
    for (int i = 0; i < 3; i++)
        if (fabs(c[i]) > o->h[i]) outside = 1;
    if (outside) {
        double q[3];
        for (int i = 0; i < 3; i++) q[i] = clampd(c[i], -o->h[i], o->h[i]);
        v3 s = obb_to_world(o, v3_make(q[0], q[1], q[2]));
        if (normal) *normal = v3_norm(v3_sub(p, s));
        return s;
    }
    /* Inside or on the surface: push out through the nearest face. */
    int best = 0;
    double best_gap = o->h[0] - fabs(c[0]);
    for (int i = 1; i < 3; i++) {
        double gap = o->h[i] - fabs(c[i]);
        if (gap < best_gap) { best_gap = gap; best = i; }
    }
    double sign = c[best] >= 0 ? 1.0 : -1.0;
    c[best] = sign * o->h[best];
    if (normal) *normal = v3_scale(o->ax[best], sign);
    return obb_to_world(o, v3_make(c[0], c[1], c[2]));
}

void obb_face(const obb *o, int f, v3 *A, v3 *B, v3 *C) {
    int k = f / 2;                 /* normal axis */
    double s = (f & 1) ? 1.0 : -1.0;
    int i = (k + 1) % 3, j = (k + 2) % 3;
    /* For +k, (e_i x e_j) = e_k points out; for -k swap i and j. */
    if (s < 0) { int t = i; i = j; j = t; }
    v3 base = v3_madd(o->c, o->ax[k], s * o->h[k]);
    v3 a = v3_sub(v3_madd(base, o->ax[i], -o->h[i]), v3_scale(o->ax[j], o->h[j]));
    *A = a;
    *B = v3_madd(a, o->ax[i], 2.0 * o->h[i]);
    *C = v3_madd(a, o->ax[j], 2.0 * o->h[j]);
}

int sphere_touches_quad(v3 s, double r, v3 A, v3 B, v3 C) {
    v3 e1 = v3_sub(B, A), e2 = v3_sub(C, A);
    v3 N = v3_norm(v3_cross(e1, e2));
    double signed_d = v3_dot(v3_sub(s, A), N);
    if (fabs(signed_d) >= r) return 0;
    v3 foot = v3_madd(s, N, -signed_d); /* S + dN or S - dN, whichever lies on the plane */
    /* Solve foot - A = u e1 + v e2 by the 2x2 normal equations. */
    v3 w = v3_sub(foot, A);
    double a11 = v3_dot(e1, e1), a12 = v3_dot(e1, e2), a22 = v3_dot(e2, e2);
    double b1 = v3_dot(w, e1), b2 = v3_dot(w, e2);
    double det = a11 * a22 - a12 * a12;
    if (fabs(det) < 1e-300) return 0;
    double u = (b1 * a22 - b2 * a12) / det, v = (a11 * b2 - a12 * b1) / det;
    return u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0;
}

int obb_sphere_touches_faces(const obb *o, v3 s, double r) {
    for (int f = 0; f < 6; f++) {
        v3 A, B, C;
        obb_face(o, f, &A, &B, &C);
        if (sphere_touches_quad(s, r, A, B, C)) return 1;
    }
    return 0;
}

int obb_sphere_overlaps(const obb *o, v3 s, double r) { return obb_signed_distance(o, s) < r; }

int obb_segment_hit(const obb *o, v3 a, v3 b, double *t_enter) {
    v3 la = obb_to_local(o, a), lb = obb_to_local(o, b);
    double p0[3] = {la.x, la.y, la.z}, d[3] = {lb.x - la.x, lb.y - la.y, lb.z - la.z};
    double t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 3; i++) {
        if (fabs(d[i]) < 1e-300) {
            if (fabs(p0[i]) > o->h[i]) return 0;
            continue;
        }
        double ta = (-o->h[i] - p0[i]) / d[i], tb = (o->h[i] - p0[i]) / d[i];
        if (ta > tb) { double t = ta; ta = tb; tb = t; }
        if (ta > t0) t0 = ta;
        if (tb < t1) t1 = tb;
        if (t0 > t1) return 0;
    }
    if (t_enter) *t_enter = t0;
    return 1;
}

void obb_bounds(const obb *o, v3 *lo, v3 *hi) {
    v3 e = v3_make(0, 0, 0);
    for (int k = 0; k < 3; k++) {
        e.x += fabs(o->ax[k].x) * o->h[k];
        e.y += fabs(o->ax[k].y) * o->h[k];
        e.z += fabs(o->ax[k].z) * o->h[k];
    }
    *lo = v3_sub(o->c, e);
    *hi = v3_add(o->c, e);
}

banyan_box banyan_box_make(double cx, double cy, double cz, double hx, double hy, double hz) {
    banyan_box b = {{cx, cy, cz}, {hx, hy, hz}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    return b;
}

banyan_status banyan_box_validate(const banyan_box *box, uint32_t index, banyan_error *err) {
    obb o;
    banyan_status s = obb_from_box(box, index, &o, err);
    if (!s) banyan_error_clear(err);
    return s;
}

/* The host's shape under a leaf (docs/ivy.md "Leaves fitted to the
 * relief", "Cover"): how tightly a mesh host curves near a point, so that
 * leaves on a statue's nose, brow or eye rims stay smaller than the
 * feature they sit on and the form still reads through the cover (boxes
 * are flat faces: no relief); and how far a point on a box lies from the
 * edge of its face, where the cover frays. */
#include <math.h>

#include "base/dmath.h"
#include "ivy_internal.h"

#define EDGE_PAST 0.05 /* m past an edge where another host would carry the face on */

/* Unit normal of the triangle of mesh m nearest x, or 0 when none lies
 * within cap. */
static int face_normal(const host_mesh *m, v3 x, double cap, v3 *n) {
    mesh_near q;
    if (!hmesh_nearest(m, x, cap, &q) || q.prim >= m->nt) return 0;
    const float *f = m->fnrm + 3 * (size_t)q.prim;
    *n = v3_make(f[0], f[1], f[2]);
    return 1;
}

double ivy_relief_radius(const banyan_ivy *iv, ivy_near at, double h) {
    if (iv->n_mesh == 0 || at.host < (int32_t)iv->mesh0 || !(h > 0)) return HUGE_VAL;
    const host_mesh *m = &iv->meshes[at.host - (int32_t)iv->mesh0];
    const v3 above = v3_madd(at.point, at.normal, 0.5 * h);
    v3 n0;
    if (!face_normal(m, above, h, &n0)) return HUGE_VAL;
    const v3 t = v3_norm_or_perp(v3_cross(at.normal, v3_make(0, 0, 1)), at.normal), s = v3_cross(at.normal, t);
    const v3 dirs[4] = {t, v3_neg(t), s, v3_neg(s)};
    /* The faces' turn over four steps of h along the surface (from half a
     * step above it): a turn of a radians over h is a radius of h / a.
     * Past the end of an open surface the nearest face is the last one:
     * a border is no relief. */
    double turn = 0;
    for (int k = 0; k < 4; k++) {
        v3 nk;
        if (!face_normal(m, v3_madd(above, dirs[k], h), 2 * h, &nk)) continue;
        double c = v3_dot(nk, n0);
        if (!m->closed) c = fabs(c); /* an open mesh's faces may wind either way */
        c = c > 1 ? 1 : (c < -1 ? -1 : c);
        double a = 2 * dm_asin(0.5 * sqrt(2 - 2 * c)); /* the angle, well-conditioned near 0 */
        turn = a > turn ? a : turn;
    }
    return turn > 1e-9 ? h / turn : HUGE_VAL;
}

double ivy_edge_distance(const banyan_ivy *iv, ivy_near at, double cap, v3 *out_dir) {
    if (at.host < 0 || (uint32_t)at.host >= iv->n_given || !(cap > 0)) return HUGE_VAL;
    const obb *o = &iv->hosts[at.host];
    const v3 l = obb_to_local(o, at.point);
    const double L[3] = {l.x, l.y, l.z};
    int f = 0; /* the face's axis: where the point is nearest the box's side */
    for (int k = 1; k < 3; k++)
        if (o->h[k] - fabs(L[k]) < o->h[f] - fabs(L[f])) f = k;
    double best = HUGE_VAL;
    for (int k = 0; k < 3; k++) {
        if (k == f) continue;
        double e = o->h[k] - fabs(L[k]);
        /* A face narrower than four caps across (a pillar, a wall's
         * thickness) is all edge along that axis: none there. */
        if (!(e < cap) || e >= best || o->h[k] < 2 * cap) continue;
        /* The edge's point nearest `at`, and a point past it in the face's
         * plane: an edge on the ground, or one where another host carries
         * the face on (a window's blocks), is no edge of the cover. */
        const v3 out = L[k] < 0 ? v3_neg(o->ax[k]) : o->ax[k];
        const v3 edge = v3_madd(at.point, out, e);
        if (iv->p.ground && edge.z <= iv->p.ground_z + EDGE_PAST) continue;
        if (ivy_grip_distance(iv, v3_madd(edge, out, EDGE_PAST), EDGE_PAST) < 0.5 * EDGE_PAST) continue;
        best = e;
        *out_dir = out;
    }
    return best;
}

/* The relief of a mesh host under a leaf (docs/ivy.md "On mesh hosts"):
 * how tightly the surface curves near a point, so that leaves on a
 * statue's nose, brow or eye rims stay smaller than the feature they sit
 * on and the form still reads through the cover. Boxes are flat faces and
 * report no relief: a wall's cover is not touched. */
#include <math.h>

#include "core/dmath.h"
#include "ivy_internal.h"

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

/* obb.h - exact queries on oriented boxes (hosts). The roots spec's
 * sphere/face quad test is here generalised to oriented boxes, next to
 * the exact distance queries the generators use for their invariants. */
#ifndef BANYAN_OBB_H
#define BANYAN_OBB_H

#include "banyan.h"
#include "base/vec.h"

typedef struct obb {
    v3 c;        /* centre */
    v3 ax[3];    /* unit local axes in world space (columns of rotation) */
    double h[3]; /* half-extents */
} obb;

/* Validates a public box (see banyan_box) and converts it. */
banyan_status obb_from_box(const banyan_box *b, uint32_t index, obb *out, banyan_error *err);

static inline v3 obb_to_local(const obb *o, v3 p) {
    v3 d = v3_sub(p, o->c);
    return v3_make(v3_dot(d, o->ax[0]), v3_dot(d, o->ax[1]), v3_dot(d, o->ax[2]));
}
static inline v3 obb_to_world(const obb *o, v3 l) {
    v3 r = o->c;
    r = v3_madd(r, o->ax[0], l.x);
    r = v3_madd(r, o->ax[1], l.y);
    return v3_madd(r, o->ax[2], l.z);
}

/* The axis-aligned bounds of the box. */
void obb_bounds(const obb *o, v3 *lo, v3 *hi);
/* p inside the box grown by `margin` on every side (margin may be < 0). */
int obb_contains(const obb *o, v3 p, double margin);
/* Closest point of the solid box to p (p itself when inside). */
v3 obb_closest_point(const obb *o, v3 p);
/* Signed distance to the box surface: < 0 inside, exact everywhere.
 * Inline: the ivy asks it for every random-walk candidate. */
static inline double obb_signed_distance(const obb *o, v3 p) {
    v3 l = obb_to_local(o, p);
    double qx = fabs(l.x) - o->h[0], qy = fabs(l.y) - o->h[1], qz = fabs(l.z) - o->h[2];
    double ox = qx > 0 ? qx : 0, oy = qy > 0 ? qy : 0, oz = qz > 0 ? qz : 0;
    double out2 = ox * ox + oy * oy + oz * oz; /* + 0 for a side inside: the same sum as over the outside ones */
    double inside = qx;
    if (qy > inside) inside = qy;
    if (qz > inside) inside = qz;
    return out2 > 0 ? sqrt(out2) : inside;
}
/* Closest point on the box's surface (boundary), also for p inside, with
 * the outward unit normal of the distance field there: the face normal for
 * points inside or on a face, the direction from the surface to p over
 * edges and corners. */
v3 obb_closest_surface(const obb *o, v3 p, v3 *normal);
/* The same given l = obb_to_local(o, p), for a caller that has it. */
v3 obb_closest_surface_local(const obb *o, v3 p, v3 l, v3 *normal);

/* Face f (0..5: -x, +x, -y, +y, -z, +z) as the parallelogram
 * A + u(B-A) + v(C-A), u, v in [0,1], with (B-A) x (C-A) pointing out. */
void obb_face(const obb *o, int f, v3 *A, v3 *B, v3 *C);
/* The roots spec's quad test: d = |(S-A).N| < r and the foot point's u, v
 * both in [0, 1]. */
int sphere_touches_quad(v3 s, double r, v3 A, v3 B, v3 C);
/* The spec's quad test against all six faces of a box. */
int obb_sphere_touches_faces(const obb *o, v3 s, double r);
/* Exact: the sphere (centre s, radius r) overlaps the solid box. */
int obb_sphere_overlaps(const obb *o, v3 s, double r);

/* Segment a->b against the solid box (slab method). Returns 1 and the
 * entry parameter t in [0,1] (0 when a is inside) when they meet. */
int obb_segment_hit(const obb *o, v3 a, v3 b, double *t_enter);

#endif

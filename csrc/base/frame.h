/* frame.h - the local frame a generator runs in, kept as the output's
 * banyan_mesh.origin (docs/api.md, "Far from the origin"). Floats keep
 * about 0.5 mm within FRAME_KEEP metres of zero, so a generator shifts its
 * world inputs by an origin near them, runs unchanged, and refuses what
 * would lie farther than FRAME_KEEP from that origin. */
#ifndef BANYAN_BASE_FRAME_H
#define BANYAN_BASE_FRAME_H

#include "banyan.h"
#include "vec.h"

/* Within FRAME_NEAR of the world origin the frame is the world's: every
 * output near 0 keeps the bytes it always had. */
#define FRAME_NEAR 4096.0
/* Float steps are 2^-10 m (0.98 mm) up to 8192 m: rounding stays <= 0.5 mm. */
#define FRAME_KEEP 8192.0

/* Grows [lo, hi] by p (start with lo = +inf, hi = -inf: frame_empty). */
void frame_empty(v3 *lo, v3 *hi);
void frame_add(v3 *lo, v3 *hi, v3 p);
/* The origin for world bounds [lo, hi], axis by axis: 0 on an axis whose
 * bounds lie within FRAME_NEAR of 0, else their centre on it rounded to
 * whole metres (exact in double). Per axis, so a scene moved far along x
 * alone keeps its local y and z, and a scene centred on 0 moved by whole
 * metres runs on the same local numbers. */
v3 frame_pick(v3 lo, v3 hi);
/* Refuses (BANYAN_E_RANGE) bounds reaching farther than FRAME_KEEP from
 * origin: `what` names the input ("hosts", "points", "the path"). */
banyan_status frame_check(v3 lo, v3 hi, v3 origin, const char *what, banyan_error *err);
/* Sets a finished mesh's origin. */
static inline void frame_set(banyan_mesh *m, v3 origin) {
    m->origin[0] = origin.x, m->origin[1] = origin.y, m->origin[2] = origin.z;
}

#endif

/* The local frame of a generator's output (frame.h). */
#include "frame.h"

#include <math.h>

#include "error.h"

void frame_empty(v3 *lo, v3 *hi) {
    *lo = v3_make(HUGE_VAL, HUGE_VAL, HUGE_VAL);
    *hi = v3_neg(*lo);
}

void frame_add(v3 *lo, v3 *hi, v3 p) {
    *lo = v3_make(fmin(lo->x, p.x), fmin(lo->y, p.y), fmin(lo->z, p.z));
    *hi = v3_make(fmax(hi->x, p.x), fmax(hi->y, p.y), fmax(hi->z, p.z));
}

/* One axis: 0 while the axis stays near, else its centre in whole metres. */
static double pick_axis(double lo, double hi) {
    if (!(fmax(fabs(lo), fabs(hi)) > FRAME_NEAR)) return 0.0; /* also empty bounds */
    return round(0.5 * (lo + hi));
}

v3 frame_pick(v3 lo, v3 hi) {
    return v3_make(pick_axis(lo.x, hi.x), pick_axis(lo.y, hi.y), pick_axis(lo.z, hi.z));
}

banyan_status frame_check(v3 lo, v3 hi, v3 origin, const char *what, banyan_error *err) {
    v3 a = v3_sub(lo, origin), b = v3_sub(hi, origin);
    double m = fmax(fmax(fmax(fabs(a.x), fabs(b.x)), fmax(fabs(a.y), fabs(b.y))), fmax(fabs(a.z), fabs(b.z)));
    if (m <= FRAME_KEEP) return BANYAN_OK;
    return banyan_fail(err, BANYAN_E_RANGE,
                       "%s span (%.1f .. %.1f, %.1f .. %.1f, %.1f .. %.1f) m: %.0f m from their local origin; one "
                       "mesh keeps 1 mm only within %.0f m of its origin: split the scene into parts under %.0f m",
                       what, lo.x, hi.x, lo.y, hi.y, lo.z, hi.z, m, FRAME_KEEP, 2 * FRAME_KEEP);
}

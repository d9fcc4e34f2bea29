/* The capsule of one root segment (capsule.h), flattened against the
 * hosts. */
#include "capsule.h"

static void flatten(const roots_net *net, const banyan_roots_params *p, capsule *c) {
    c->sq = 1.0;
    c->fn = v3_make(0, 0, 0);
    const double r = net->r, R = 0.5 * (c->ra + c->rb);
    v3 n, m = v3_lerp(c->a, c->b, 0.5);
    int which;
    double cl = world_clearance_in(&net->w, m, 0, R + r, &n, &which);
    if (which < 0 || cl >= R + r) return;
    double s = (R + r - cl) / r;
    s = s > 1 ? 1 : s;
    v3 ax = v3_norm_or(c->ba, v3_make(0, 0, 1));
    v3 across = v3_madd(n, ax, -v3_dot(n, ax));
    double l = v3_len(across);
    if (l < 0.5) return; /* along the normal: leaving the host */
    double ratio = 1.0 + (ROOTS_FLAT_LO - 1.0 + (ROOTS_FLAT_HI - ROOTS_FLAT_LO) * p->maturity) * s * l;
    c->sq = sqrt(ratio);
    c->fn = v3_scale(across, 1.0 / l);
}

void roots_capsule_set(capsule *c, const roots_net *net, const banyan_roots_params *p, uint32_t t, uint32_t at) {
    c->a = net->pts[at], c->b = net->pts[at + 1];
    c->ba = v3_sub(c->b, c->a), c->l2 = v3_len2(c->ba);
    c->ra = net->rad[at], c->rb = net->rad[at + 1];
    c->poly = t, c->at = at;
    flatten(net, p, c);
}

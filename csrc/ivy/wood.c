/* Stem wood of the ivy mesh (docs/ivy.md "Stems and trunks"). A stem is
 * as thick as the larger of two rules: the spec's age rule (r0 + k age,
 * capped at stem_radius_max; ivy_stem_radius, which the sag also reads)
 * and the pipe model, stem_pipe x sqrt(buds it carries): a stem's wood
 * carries every shoot beyond it, so the few leading stems that carry the
 * whole plant thicken into trunks while side shoots stay thin. A stem
 * thicker than its gap to the surface it lies on is moved out along that
 * surface's normal, so a trunk lies on the wall instead of in it. Only
 * the mesh reads these: the growth is the same with or without them. */
#include <math.h>
#include <stdlib.h>

#include "ivy_internal.h"

#define WOOD_PUSHES 3 /* pushes out of the surfaces: a corner takes two */

/* Old wood sheds its leaves (docs/ivy.md "Stems and trunks"): wood is old
 * when it is both thick, from OLD_R to OLD_R + OLD_R_RAMP times
 * stem_radius_max, and among the plant's first wood, its bud born in the
 * first (1 - OLD_LIFE) of the plant's steps, ramping over OLD_LIFE_RAMP. A
 * leaf within SPUR_REACH internodes of old wood grows on a spur of it and
 * sheds as it does: the trunks at the foot of an old wall show, while
 * the thick leading stems higher up, younger, keep their leaves. */
#define OLD_R 1.5
#define OLD_R_RAMP 1.5
#define OLD_LIFE 0.85
#define OLD_LIFE_RAMP 0.1
#define SPUR_REACH 4

static double smooth01(double x) { return x <= 0 ? 0 : x >= 1 ? 1 : x * x * (3 - 2 * x); }

void ivy_wood_leaf_shares(const banyan_ivy *iv, const double *r, double *share) {
    const banyan_ivy_params *p = &iv->p;
    const double cap = p->stem_radius_max, steps = iv->step > 0 ? iv->step : 1;
    for (int32_t i = 0; i < iv->n; i++) {
        double shed = 0;
        int32_t j = i;
        for (int k = 0; k <= SPUR_REACH && j >= 0; k++, j = iv->buds[j].parent) {
            double life = (double)(iv->step - iv->buds[j].step_c) / steps;
            double s = smooth01((r[j] - OLD_R * cap) / (OLD_R_RAMP * cap)) * smooth01((life - OLD_LIFE) / OLD_LIFE_RAMP);
            shed = s > shed ? s : shed;
        }
        share[i] = 1 - shed;
    }
}

banyan_status ivy_wood(const banyan_ivy *iv, double *r, v3 *P) {
    const banyan_ivy_params *p = &iv->p;
    const int32_t n = iv->n;
    int32_t *carried = malloc(sizeof(int32_t) * ((size_t)n + 1));
    if (!carried) return BANYAN_E_NOMEM;
    /* Buds come in creation order, a parent before its children: one
     * backward pass sums every bud's shoots. */
    for (int32_t i = n - 1; i >= 0; i--) {
        const ivy_bud *b = &iv->buds[i];
        int32_t c = 1;
        for (int k = 0; k < 2; k++)
            if (b->child[k] >= 0) c += carried[b->child[k]];
        carried[i] = c;
    }
    for (int32_t i = 0; i < n; i++) {
        const ivy_bud *b = &iv->buds[i];
        double age = ivy_stem_radius(iv, b), pipe = p->stem_pipe * sqrt((double)carried[i]);
        r[i] = pipe > age ? pipe : age;
        P[i] = b->P;
        /* Thicker than its gap to the surface: out along the normal; in a
         * corner (the wall's foot) once more for the other surface. */
        if (ivy_grip_distance(iv, b->P, r[i]) >= r[i] && (!p->ground || b->P.z - p->ground_z >= r[i])) continue;
        for (int k = 0; k < WOOD_PUSHES; k++) {
            ivy_near nr = ivy_nearest_any(iv, P[i]);
            if (!(nr.dist < r[i])) break;
            P[i] = v3_madd(P[i], nr.normal, r[i] - nr.dist);
        }
    }
    free(carried);
    return BANYAN_OK;
}

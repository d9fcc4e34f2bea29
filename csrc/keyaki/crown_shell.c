/* crown_shell.c - the clusters on the keyaki crown's outer shell (see
 * shell in crown_internal.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crown_internal.h"

#define SHELL_FROM 0.25
#define SHELL_OUTER 0.3
#define SHELL_BAND 1.0 /* m: height bands of the skeleton's reach */
#define SHELL_FAN_DEG 150.0 /* a shell cluster heads 15 deg .. this far round its branch from the outward direction */
#define SHELL_SPACING 0.25 /* x twig_spacing: a shell cluster's spacing along its branch */
#define SHELL_LENGTH 1.4  /* x twig_length: a shell cluster's (a leafy shoot's) length */
#define SHELL_LOW_LENGTH 2.2 /* x twig_length: in the crown's lower half (its skirt) */


static double reach_of(const shell *sh, v3 q) { return sqrt((q.x - sh->x0) * (q.x - sh->x0) + (q.y - sh->y0) * (q.y - sh->y0)); }

static int32_t band_of(const shell *sh, double z) {
    int32_t b = (int32_t)floor((z - sh->z0) / SHELL_BAND);
    return b < 0 ? 0 : b >= sh->bands ? sh->bands - 1 : b;
}

int crown_shell_of(shell *sh, const keyaki_node *n, int32_t count) {
    memset(sh, 0, sizeof *sh);
    if (count <= 0) return 0;
    sh->x0 = n[0].start.x, sh->y0 = n[0].start.y, sh->z0 = n[0].start.z;
    double top = sh->z0;
    for (int32_t i = 0; i < count; i++) top = fmax(top, n[i].start.z + n[i].dir.z * n[i].length);
    sh->height = top - sh->z0;
    sh->bands = (int32_t)clampd(ceil(sh->height / SHELL_BAND), 0, 100000) + 1;
    double *raw = calloc(2 * (size_t)sh->bands, sizeof(double));
    if (!raw) return 1;
    for (int32_t i = 0; i < count; i++) {
        v3 e = v3_madd(n[i].start, n[i].dir, n[i].length);
        int32_t b = band_of(sh, e.z);
        raw[b] = fmax(raw[b], reach_of(sh, e));
    }
    double *env = raw + sh->bands;
    for (int32_t b = 0; b < sh->bands; b++)
        env[b] = fmax(raw[b], fmax(b > 0 ? raw[b - 1] : 0.0, b + 1 < sh->bands ? raw[b + 1] : 0.0));
    memmove(raw, env, sizeof(double) * (size_t)sh->bands);
    sh->env = raw;
    return 0;
}

/* Appends the shell clusters of deep branch i (see shell) to *cs; 1 on a
 * failure (sh->why). */
int crown_shell_clusters(shell *sh, const banyan_keyaki_params *p, const keyaki_node *n, int32_t i, pcg32 *plan,
                          double path, cand **cs, int32_t *nc, int32_t *cap, int count_only) {
    const keyaki_node *b = &n[i];
    /* Shoots of spray cards: nothing to carry without leaves (winter keeps
     * its twigs as they were). */
    if (!sh->env || sh->height <= 0 || !p->leaves || p->leaf_density <= 0) return 0;
    double zlo = sh->z0 + SHELL_FROM * sh->height;
    v3 e = v3_madd(b->start, b->dir, b->length);
    if (fmax(b->start.z, e.z) < zlo) return 0;
    int side = rng_uniform(plan) < 0.5 ? 1 : -1;
    const double step = SHELL_SPACING * p->twig_spacing;
    double s = step * rng_uniform(plan);
    int32_t k = (int32_t)((b->length - s) / step) + 1;
    if (k <= 0) return 0;
    if (8.0 * ((double)*nc + k) > (double)crown_budget(p, count_only)) {
        sh->why = 2;
        return 1;
    }
    if (crown_grow_array((void **)cs, cap, *nc + k, sizeof(cand))) {
        sh->why = 1;
        return 1;
    }
    for (; s < b->length; s += step, side = -side) {
        v3 at = v3_madd(b->start, b->dir, s);
        double fan = rng_range(plan, 15.0, SHELL_FAN_DEG), a = deg2rad(p->twig_angle * rng_range(plan, 0.85, 1.15));
        double len = p->twig_length * rng_range(plan, 0.75, 1.25);
        if (at.z < zlo) continue;
        len *= at.z < sh->z0 + 0.5 * sh->height ? SHELL_LOW_LENGTH : SHELL_LENGTH;
        double rho = reach_of(sh, at);
        if (rho < SHELL_OUTER * sh->env[band_of(sh, at.z)] || rho < 1e-6) continue;
        /* Outward: the radial direction square to the branch, fanned about it. */
        v3 rad = v3_make((at.x - sh->x0) / rho, (at.y - sh->y0) / rho, 0);
        v3 o = v3_sub(rad, v3_scale(b->dir, v3_dot(rad, b->dir)));
        if (v3_len2(o) < 1e-8) o = crown_horizontal_perp(b->dir);
        o = v3_rotate(v3_norm(o), b->dir, deg2rad(side * fan));
        cand *q = &(*cs)[*nc];
        double r = crown_branch_radius(p, n, b, s);
        q->d = v3_norm(v3_add(v3_scale(b->dir, dm_cos(a)), v3_scale(o, dm_sin(a))));
        q->h = crown_horizontal_perp(q->d);
        q->at = at;
        q->len = len;
        q->r_host = r;
        q->path = path + s;
        q->node = i;
        q->index = *nc;
        q->tip = 0;
        q->shell = 1;
        (*nc)++;
    }
    return 0;
}

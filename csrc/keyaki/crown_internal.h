/* crown_internal.h - what the stages of the keyaki's crown share: crown.c
 * grows the clusters (twigs, leaves, spray cards), crown_light.c holds the
 * plan-view light model and the crown's outline, crown_shell.c the outer
 * shell's clusters, crown_mesh.c meshes the grown twigs and leaves. */
#ifndef BANYAN_KEYAKI_CROWN_INTERNAL_H
#define BANYAN_KEYAKI_CROWN_INTERNAL_H

#include <stdlib.h>

#include "keyaki_internal.h"

#define CELL 0.2            /* m, the light grid's cell */
#define MAX_TWIG_PTS 64     /* points of one twig's polyline */

static inline double clampd(double x, double a, double b) { return x < a ? a : x > b ? b : x; }

/* A cluster waiting to grow: a first-order twig planned on the skeleton. */
typedef struct cand {
    v3 at, d, h;     /* start (on the branch's axis), direction, horizontal side vector */
    double len, r_host, z;
    double path;     /* m: path length from the trunk base to `at` */
    int32_t node, index;
    int tip;         /* a skeleton tip's continuation: never dropped */
    int shell;       /* on a branch below leaf_levels, on the crown's outer shell: a spur at worst */
} cand;

/* The plan-view shade grid. */
typedef struct grid {
    double x0, y0;
    int32_t nx, ny;
    int32_t *n;
    uint8_t *in; /* 1: the cell's centre lies inside the crown's planned outline */
    int32_t *sky; /* SKY_OBLIQUE more count layers, one per oblique sky direction (NULL: zenith only) */
    double zref;  /* m: the height whose plan the oblique layers share */
} grid;

/* The sky: light from the zenith (weight SKY_ZENITH_WEIGHT) and from
 * SKY_OBLIQUE directions SKY_ELEVATION_DEG above the horizon, evenly round
 * (the rest of the weight shared). A cluster seen along an oblique
 * direction is its plan rectangle shifted by (z - zref) cot(elevation)
 * away from that direction's light; a layer counts those shifted
 * rectangles. So a cluster on the crown's flank, under others but open
 * to the side, keeps the side's light, as on a real tree whose crown is
 * a leafy shell lit by the whole sky, not a cap lit from above. */
#define SKY_OBLIQUE 4
#define SKY_ELEVATION_DEG 45.0
#define SKY_ZENITH_WEIGHT 0.4

/* A cluster's plan rectangle: from o along unit a (2D) for `len`, half
 * width w either side. */
typedef struct rect {
    double ox, oy, ax, ay, len, w;
} rect;

/* The plan outline the crown is planned to fill: the convex hull
 * (monotone chain, counter-clockwise) of the clusters' planned starts and
 * ends. Extension into empty cells stays inside it, so growth fills holes
 * without pushing the crown's outline out. */
typedef struct hull {
    double *xy;
    int32_t n;
} hull;

/* The crown's outer shell: foliage also grows on branches deeper than
 * leaf_levels from a tip, from SHELL_FROM of the tree's height up, where
 * the branch lies in the outer part of the crown at its height (at least
 * SHELL_OUTER of the widest reach of the skeleton within a metre of that
 * height): clusters every twig_spacing, heading outward, fanned alternately
 * either side of the outward direction. So the crown is leafy from about a
 * third of its height, a dome from below rather than the limbs' star. */
typedef struct shell {
    double x0, y0, z0, height;
    double *env; /* per band: the widest reach round the trunk's foot within a band either side */
    int32_t bands;
    int why;     /* a failure: 1 out of memory, 2 past the budget */
} shell;

/* Helpers of every stage, inline so that no stage calls back into
 * another's file. */
/* Room for `more` items in a doubling array. */
static inline int crown_grow_array(void **a, int32_t *cap, int32_t need, size_t size) {
    if (need <= *cap) return 0;
    int64_t nc = *cap ? *cap : 256;
    while (nc < need) nc *= 2;
    if (nc > INT32_MAX / 2) return 1;
    void *p = realloc(*a, (size_t)nc * size);
    if (!p) return 1;
    *a = p;
    *cap = (int32_t)nc;
    return 0;
}

/* Stops the crown once its mesh would pass max_vertices (4 a leaf, at
 * most 6 a twig point): huge settings are refused before they fill
 * memory, as the body's plan refuses them before meshing. */
static inline int64_t crown_budget(const banyan_keyaki_params *p, int count_only) {
    /* Sizing stores no leaves and must give the exact count (an avenue
     * sums its trees' before refusing): only the mesh ceiling bounds it. */
    return count_only ? (int64_t)MB_VERTEX_CEILING : (int64_t)p->max_vertices;
}

/* Radius of branch x at arc length s (as body.c tapers it). */
static inline double crown_branch_radius(const banyan_keyaki_params *p, const keyaki_node *n, const keyaki_node *x,
                                         double s) {
    double r0 = x->parent >= 0 ? n[x->parent].radius : x->radius;
    int tip = x->child[0] < 0 && x->child[1] < 0;
    double r1 = tip ? x->radius * p->tip_taper : x->radius;
    double t = x->length > 0 ? clampd(s / x->length, 0, 1) : 1;
    return r0 + (r1 - r0) * t;
}

/* A unit vector level and square to d. */
static inline v3 crown_horizontal_perp(v3 d) {
    v3 h = v3_cross(d, v3_make(0, 0, 1));
    return v3_len2(h) > 1e-12 ? v3_norm(h) : v3_make(1, 0, 0);
}

/* The light model (crown_light.c). */
rect crown_cluster_rect(const banyan_keyaki_params *p, v3 at, v3 d, v3 h, double len, double wlen);
void crown_sky_shade(const grid *g, rect r, double z, double layers, double *fl, double *fr);
void crown_sky_stamp(grid *g, rect r, double z);
int crown_hole_at(const grid *g, double x, double y);
int crown_hull_of(double *pts, int32_t m, hull *h, keyaki_run *run);
void crown_hull_mask(const hull *h, grid *g);

/* The outer shell (crown_shell.c). */
int crown_shell_of(shell *sh, const keyaki_node *n, int32_t count);
int crown_shell_clusters(shell *sh, const banyan_keyaki_params *p, const keyaki_node *n, int32_t i, pcg32 *plan,
                         double path, cand **cs, int32_t *nc, int32_t *cap, int count_only);

#endif

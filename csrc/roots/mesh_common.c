/* What both roots surfaces (the tubes, mesh.c, and the fused surface,
 * fused.c) mesh alike: the builder with the roots' attributes and bark
 * material, and the skeleton of the net. */
#include <stdlib.h>

#include "textures/leaf_look.h"
#include "mesh/wind.h"
#include "roots_internal.h"

void roots_mesh_init(mesh_builder *mb, const banyan_roots_params *p, int *a_kind, int *a_id, wind_slots *ws) {
    mb_init(mb, (uint32_t)p->max_vertices, 1);
    *a_kind = mb_add_attr(mb, "root_kind");
    *a_id = mb_add_attr(mb, "root_id");
    wind_declare(mb, p->wind, ws);
    mb_set_color(mb, p->color);
    uint32_t mat = mb_add_material(mb, "roots", p->color, 0.9, 0);
    if (!mb->status) bark_material_set(&mb->mat[mat], BANYAN_TEX_FIG_BARK);
}

int roots_mesh_skeleton(mesh_builder *mb, const roots_net *net, const banyan_roots_params *p) {
    /* Skeleton: one point per polyline point, the junctions shared: a first
     * branch root's ends are its main roots' points, a second branch root's
     * ends are its first branch roots' middle points; a foot root's start
     * and an aerial root's is the net point it leaves; G is one point. */
    uint32_t *skel = malloc(sizeof(uint32_t) * (net->n_pts ? net->n_pts : 1));
    if (!skel) return -1;
    uint32_t g_index = UINT32_MAX;
    for (uint32_t t = 0; t < net->n_poly && !mb->status; t++) {
        const roots_poly *pl = &net->poly[t];
        for (uint32_t i = 0; i < pl->n; i++) {
            uint32_t src = pl->off + i, k;
            if (pl->kind == ROOT_MAIN && i == 0) {
                if (g_index == UINT32_MAX) g_index = mb_skel_point(mb, net->pts[src], net->rad[src], ROOT_MAIN);
                k = g_index;
            } else if (pl->kind == ROOT_FIRST && (i == 0 || i + 1 == pl->n)) {
                int b = i == 0 ? roots_branch_b(p, pl->k) : roots_branch_end_b(net, p, pl->a * net->nb + pl->k);
                int a = i == 0 ? pl->a : (pl->a + 1) % net->N;
                k = skel[net->M_at[(size_t)a * net->B + b]];
            } else if (i == 0 && pl->from != UINT32_MAX) { /* foot and aerial roots */
                k = skel[pl->from];
            } else if (pl->kind == ROOT_SECOND && (i == 0 || i + 1 == pl->n)) {
                int slot = pl->a * net->nb + pl->k + (i == 0 ? 0 : 1);
                k = skel[net->K_mid_at[slot]];
            } else {
                k = mb_skel_point(mb, net->pts[src], net->rad[src], pl->kind);
            }
            skel[src] = k;
            if (i && skel[src - 1] != k) mb_skel_edge(mb, skel[src - 1], k);
        }
    }
    free(skel);
    return 0;
}

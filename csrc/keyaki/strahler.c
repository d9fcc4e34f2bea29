/* strahler.c - Horton-Strahler ordering, stream counts and bifurcation
 * ratios on the final skeleton (spec/keyaki.md, "Topology measure"), and
 * the pipe-model radii (spec "Body and leaves", "Radius").
 *
 * Orders: a tip is 1; two children of equal order k give k + 1; unequal
 * orders give the higher; a single child (a run after breaks) passes its
 * order up unchanged, so a run is part of one stream. A stream is a
 * maximal chain of branches of one order: a branch starts a stream when it
 * is the trunk or its parent's order differs from its own. N_k counts the
 * streams of order k; R_k = N_k / N_{k+1}. Both passes run children first
 * over the parents-first array: O(n), no allocation. */
#include <math.h>

#include "keyaki_internal.h"

banyan_status keyaki_strahler(keyaki_node *n, int32_t count) {
    for (int32_t i = count - 1; i >= 0; i--) {
        int32_t a = n[i].child[0], b = n[i].child[1];
        if ((a >= 0 && (a <= i || a >= count)) || (b >= 0 && (b <= i || b >= count)) || (a >= 0 && a == b))
            return BANYAN_E_INTERNAL;
        if (a < 0 && b < 0) n[i].order = 1;
        else if (a < 0 || b < 0) n[i].order = n[a >= 0 ? a : b].order;
        else {
            int32_t oa = n[a].order, ob = n[b].order;
            n[i].order = oa == ob ? oa + 1 : (oa > ob ? oa : ob);
        }
    }
    return BANYAN_OK;
}

void keyaki_measure(const keyaki_node *n, int32_t count, v3 base, banyan_keyaki_stats *st) {
    banyan_keyaki_stats z = {0};
    *st = z;
    st->node_count = count;
    double max_h2 = 0, max_z = 0;
    int64_t run_sum = 0, runs = 0;
    for (int32_t i = 0; i < count; i++) {
        const keyaki_node *x = &n[i];
        int kids = (x->child[0] >= 0) + (x->child[1] >= 0);
        if (kids == 0) st->tip_count++;
        if (kids == 2) st->fork_count++;
        if (x->flags & KN_BROKEN) st->break_count++;
        if (x->level > st->max_level) st->max_level = x->level;
        int32_t o = x->order;
        if (o >= 1 && o <= BANYAN_KEYAKI_MAX_ORDER && (x->parent < 0 || n[x->parent].order != o))
            st->stream_count[o - 1]++;
        if (o > st->max_order) st->max_order = o;
        v3 e = v3_madd(x->start, x->dir, x->length);
        double dx = e.x - base.x, dy = e.y - base.y, h2 = dx * dx + dy * dy;
        if (h2 > max_h2) max_h2 = h2;
        if (e.z - base.z > max_z) max_z = e.z - base.z;
        /* A run between two real forks: starts at a child of a two-child
         * fork, follows single children, ends at a two-child fork. */
        if (x->parent >= 0 && n[x->parent].child[1] >= 0) {
            int32_t len = 1, j = i;
            while (n[j].child[0] >= 0 && n[j].child[1] < 0) {
                j = n[j].child[0];
                len++;
            }
            if (n[j].child[1] >= 0) {
                run_sum += len;
                runs++;
            }
        }
    }
    if (st->max_order > BANYAN_KEYAKI_MAX_ORDER) st->max_order = BANYAN_KEYAKI_MAX_ORDER;
    int K = st->max_order;
    double sum = 0;
    for (int k = 1; k < K; k++) {
        double r = st->stream_count[k] ? (double)st->stream_count[k - 1] / st->stream_count[k] : 0.0;
        st->bifurcation_ratio[k - 1] = r;
        sum += r;
    }
    st->mean_bifurcation_ratio = K > 1 ? sum / (K - 1) : 0.0;
    st->height = max_z;
    st->crown_width = 2.0 * sqrt(max_h2);
    st->mean_run_length = runs ? (double)run_sum / (double)runs : 0.0;
}

void keyaki_radii(keyaki_node *n, int32_t count, double tip_radius, double p) {
    for (int32_t i = count - 1; i >= 0; i--) {
        int32_t a = n[i].child[0], b = n[i].child[1];
        if (a < 0 && b < 0) n[i].radius = tip_radius;
        else if (a < 0 || b < 0) n[i].radius = n[a >= 0 ? a : b].radius;
        else n[i].radius = dm_pow(dm_pow(n[a].radius, p) + dm_pow(n[b].radius, p), 1.0 / p);
    }
}

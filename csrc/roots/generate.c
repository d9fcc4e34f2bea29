/* Entry points of the roots generator: input checks, the germination point
 * G (spec roots.md, "Parameters": top centre of the first host, lifted by
 * r; for a mesh host the highest surface point above the centre of its
 * bounds), the stages in order (main roots, first branch roots,
 * correction, second branch roots, final paths, mesh, soil line) and the
 * stats. Box input becomes a box-only host set, so boxes and meshes share
 * one path.
 * Refusals: bad params, no or bad hosts, G inside a host or below the
 * ground, G beyond the roots' reach of every host, a mesh past
 * max_vertices. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/frame.h"
#include "roots_internal.h"

void roots_net_free(roots_net *net) {
    if (!net) return;
    banyan_hosts_free(net->own_hosts);
    free(net->w.hint);
    free(net->M);
    free(net->M_grown);
    free(net->K);
    free(net->K_valid);
    free(net->K_end);
    free(net->K_ok);
    free(net->Q);
    free(net->Q_valid);
    free(net->ground_hit);
    free(net->soil_b);
    free(net->soil_pts);
    free(net->pts);
    free(net->rad);
    free(net->poly);
    free(net->M_at);
    free(net->K_mid_at);
    memset(net, 0, sizeof *net);
}

banyan_status roots_params_check(const banyan_roots_params *p, banyan_error *err) {
    if (!p) return banyan_fail(err, BANYAN_E_INVALID_ARG, "params is NULL");
    /* radius and sides first, with messages of their own. */
    if (isnan(p->radius) || !(p->radius > 0))
        return banyan_fail(err, BANYAN_E_RANGE, "radius = %g must be > 0 (root radius r in units; valid [0.001, 100])",
                           p->radius);
    if (p->sides < 4 || p->sides > 256 || p->sides % 2)
        return banyan_fail(err, BANYAN_E_RANGE,
                           "sides = %d must be even and within [4, 256] (each junction ring splits into two halves)",
                           p->sides);
    banyan_status s = banyan_params_check(BANYAN_GEN_ROOTS, p, err);
    if (s) return s;
    if (p->forward_min > p->forward_max)
        return banyan_fail(err, BANYAN_E_RANGE, "forward_min = %g must not exceed forward_max = %g unit",
                           p->forward_min, p->forward_max);
    return BANYAN_OK;
}

/* Centre of the most upward face of a box, lifted by r along its normal. */
static v3 top_centre(const obb *o, double r) {
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(o->ax[i].z) > fabs(o->ax[k].z)) k = i;
    v3 n = o->ax[k].z >= 0 ? o->ax[k] : v3_neg(o->ax[k]);
    return v3_madd(o->c, n, o->h[k] + r);
}

static size_t tube_vertices(size_t n, int sides) { return n * (size_t)(sides + 1) + 2 * (size_t)(sides + 2); }

/* G for germination_auto on mesh host 0: the highest surface point on the
 * vertical line through the centre of its world bounds (a ray down from
 * above them), else the top of its bounds; lifted by r. */
static v3 mesh_top(const banyan_hosts *H, uint32_t h, double r) {
    v3 lo = H->lo[h], hi = H->hi[h];
    double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y), pad = 1.0 + (hi.z - lo.z);
    v3 a = v3_make(cx, cy, hi.z + pad), b = v3_make(cx, cy, lo.z - pad), n;
    double t;
    double z = hi.z;
    if (hmesh_segment_hit(&H->meshes[h - H->n_boxes], a, b, &t, &n)) z = a.z + (b.z - a.z) * t;
    return v3_make(cx, cy, z + r);
}

/* Signed distance from p to host h, exact where below cap. */
static double host_distance(const roots_world *w, uint32_t h, v3 p, double cap) {
    if (h < w->n_hosts) return obb_signed_distance(&w->hosts[h], p);
    double d = hmesh_distance(&w->meshes[h - w->n_hosts], p, cap);
    if (d <= -cap) d = hmesh_distance(&w->meshes[h - w->n_hosts], p, HUGE_VAL);
    return d;
}

/* roots_net_build's checks of a box array, then its box-only host set. */
static banyan_status box_hosts(const banyan_roots_params *p, const banyan_box *hosts, uint32_t n_hosts,
                               banyan_hosts **H, banyan_error *err) {
    banyan_status s = roots_params_check(p, err);
    if (s) return s;
    if (n_hosts == 0)
        return banyan_fail(err, BANYAN_E_NO_HOSTS,
                           "n_hosts = 0: strangler-fig roots need at least one host box to grow around");
    if (!hosts) return banyan_fail(err, BANYAN_E_INVALID_ARG, "hosts is NULL but n_hosts = %u", n_hosts);
    if (n_hosts > BANYAN_MAX_HOSTS)
        return banyan_fail(err, BANYAN_E_RANGE, "n_hosts = %u must be within [1, %d]", n_hosts, BANYAN_MAX_HOSTS);
    return banyan_hosts_create(hosts, n_hosts, NULL, 0, H, err);
}

banyan_status roots_net_build(const banyan_roots_params *p, const banyan_box *hosts, uint32_t n_hosts,
                              roots_net *net, banyan_error *err) {
    memset(net, 0, sizeof *net);
    banyan_hosts *H = NULL;
    banyan_status s = box_hosts(p, hosts, n_hosts, &H, err);
    if (s) return s;
    if ((s = roots_net_build_hosts(p, H, net, err))) {
        banyan_hosts_free(H);
        return s;
    }
    net->own_hosts = H;
    return BANYAN_OK;
}

static banyan_status build_hosts(const banyan_roots_params *p, const banyan_hosts *hosts, roots_net *net, prog *g,
                                 banyan_error *err);

banyan_status roots_net_build_hosts(const banyan_roots_params *p, const banyan_hosts *hosts, roots_net *net,
                                    banyan_error *err) {
    return build_hosts(p, hosts, net, NULL, err);
}

/* Progress of banyan_roots_generate at the end of each stage (the
 * mains by root: ROOTS_AT_MAINS). */
#define ROOTS_AT_FIRST 0.08
#define ROOTS_AT_SECOND 0.1
#define ROOTS_AT_PATHS 0.12

/* The germination point G in the set's frame: the given one, or the top
 * of the first box or mesh. Refused when it lies inside a host or below
 * the ground, or farther from every host than a main root can reach. */
static banyan_status germination(const banyan_roots_params *p, const banyan_hosts *hosts, const roots_net *net,
                                 v3 *G_out, banyan_error *err) {
    const v3 O = hosts->origin;
    const uint32_t n_hosts = hosts->n_boxes + hosts->n_meshes;
    v3 G = !p->germination_auto  ? v3_sub(v3_load(p->germination), O)
           : hosts->n_boxes      ? top_centre(&hosts->boxes[0], net->r)
                                 : mesh_top(hosts, 0, net->r);
    for (uint32_t i = 0; i < n_hosts; i++) {
        if (host_distance(&net->w, i, G, net->r) <= 0) { /* inside or on its surface */
            return banyan_fail(err, BANYAN_E_START_INSIDE,
                               "germination point G = (%g, %g, %g) m is inside hosts[%u]; G must lie outside every "
                               "host%s",
                               G.x + O.x, G.y + O.y, G.z + O.z, i,
                               p->germination_auto ? " (G is the top of hosts[0]: list the topmost host first, or "
                                                     "set germination_auto = false and germination)"
                                                   : "");
        }
    }
    if (p->ground && G.z < net->w.ground_z) {
        return banyan_fail(err, BANYAN_E_START_INSIDE,
                           "germination point G = (%g, %g, %g) m is below the ground plane z = %g m", G.x + O.x, G.y + O.y,
                           G.z + O.z, p->ground_z);
    }
    /* A main root moves at most `moves` steps of length sqrt(forward_max^2
     * + lateral^2) per growth point from its start circle (pushes out of a
     * host and the pull back to a face each move it by at most r): a G
     * farther than that from every host grows roots that touch none. */
    double step = dm_hypot(p->forward_max, p->lateral) * net->u;
    double reach = p->start_radius * net->u + (double)(p->growth_points - 1) * p->moves * step + 4.0 * net->r;
    double nearest = 1e300;
    uint32_t nearest_i = 0;
    for (uint32_t i = 0; i < n_hosts; i++) {
        double d = host_distance(&net->w, i, G, HUGE_VAL);
        if (d < nearest) nearest = d, nearest_i = i;
    }
    if (nearest > reach) {
        return banyan_fail(err, BANYAN_E_START_FAR,
                           "germination point G = (%g, %g, %g) m is %g m from the nearest host (hosts[%u]); the roots "
                           "reach at most %g m (start_radius + (growth_points - 1) x moves x step), so none would "
                           "touch a host: move G within %g m of a host",
                           G.x + O.x, G.y + O.y, G.z + O.z, nearest, nearest_i, reach, reach);
    }
    *G_out = G;
    return BANYAN_OK;
}

/* The net's sizes from the parameters and its arrays, refused when the
 * vertex estimate is over max_vertices before anything big is allocated.
 * The caller frees the net on a refusal. */
static banyan_status size_net(const banyan_roots_params *p, roots_net *net, banyan_error *err) {
    net->N = p->main_roots;
    net->B = p->growth_points;
    net->S1 = p->branch_samples;
    net->S2 = p->second_samples;
    net->nb = p->branch_start > p->growth_points ? 0 : (p->growth_points - p->branch_start) / p->branch_spacing + 1;
    size_t N = (size_t)net->N, B = (size_t)net->B, nb = (size_t)net->nb;
    size_t firsts = p->first_branches && net->N >= 2 ? N * nb : 0;
    size_t seconds = firsts && p->second_branches && nb > 1 ? N * (nb - 1) : 0;
    size_t est = N * tube_vertices(B + 1, p->sides) + firsts * tube_vertices((size_t)net->S1, p->sides) +
                 seconds * tube_vertices((size_t)net->S2, p->sides);
    if (est > (size_t)p->max_vertices) {
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "the roots mesh would need about %zu vertices, more than max_vertices = %d; raise "
                           "max_vertices or lower sides, growth_points, main_roots or branch_samples",
                           est, p->max_vertices);
    }
    size_t slots = N * (nb ? nb : 1);
    net->M = malloc(sizeof(v3) * N * B);
    net->M_grown = malloc(sizeof(v3) * N * B);
    net->K = malloc(sizeof(v3) * slots * (size_t)net->S1);
    net->K_valid = calloc(slots, sizeof(int32_t));
    net->K_end = calloc(slots, sizeof(int32_t));
    net->K_ok = calloc(slots * (size_t)net->S1, 1);
    net->Q = malloc(sizeof(v3) * slots * (size_t)net->S2);
    net->Q_valid = calloc(slots, sizeof(int32_t));
    net->ground_hit = calloc(N, sizeof(int32_t));
    net->soil_b = malloc(sizeof(int32_t) * N);
    net->soil_pts = malloc(sizeof(v3) * N * ROOTS_SOIL_PTS);
    net->M_at = malloc(sizeof(uint32_t) * N * B);
    net->K_mid_at = calloc(slots, sizeof(uint32_t));
    if (!net->M || !net->M_grown || !net->K || !net->K_valid || !net->K_end || !net->K_ok || !net->Q || !net->Q_valid || !net->ground_hit ||
        !net->soil_b || !net->soil_pts || !net->M_at || !net->K_mid_at) {
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the roots net");
    }
    return BANYAN_OK;
}

/* Stats over the finished net: the main points, the radius, the least
 * clearance of any skeleton point from the hosts, the mains that reach
 * the ground and the first branches that reach both their ends. Returns
 * 1 when stopped (cancel or budget), else 0. */
static int net_stats(roots_net *net, const banyan_roots_params *p) {
    const size_t N = (size_t)net->N, B = (size_t)net->B;
    banyan_roots_stats *st = &net->stats;
    st->main_points = (uint32_t)(N * B);
    st->radius = net->r;
    st->min_clearance = 1e300;
    roots_world soil_w = roots_soil_world(&net->w);
    for (uint32_t t = 0; t < net->n_poly; t++) {
        if (roots_stop(net)) return 1;
        const roots_poly *pl = &net->poly[t];
        for (uint32_t i = 0; i < pl->n; i++) {
            /* Only values below the least so far count (keeps mesh queries
             * short). Every skeleton point passed a free test or a push-out,
             * so it is outside every mesh: unsigned mesh distances (an inside
             * test costs rays). The underground ends of soil-entering roots
             * keep clear of the hosts only. */
            double c = world_clearance_outside(i >= pl->soil_from ? &soil_w : &net->w, net->pts[pl->off + i],
                                               st->min_clearance < 1e300 ? st->min_clearance : HUGE_VAL);
            if (c < st->min_clearance) st->min_clearance = c;
        }
    }
    for (int a = 0; a < net->N; a++) st->mains_on_ground += net->ground_hit[a] ? 1u : 0u;
    for (uint32_t t = 0; t < net->n_poly; t++) {
        const roots_poly *pl = &net->poly[t];
        if (pl->kind != ROOT_FIRST) continue;
        int b = roots_branch_b(p, pl->k), be = roots_branch_end_b(net, p, pl->a * net->nb + pl->k);
        v3 start = net->M[(size_t)pl->a * B + b], end = net->M[(size_t)((pl->a + 1) % net->N) * B + be];
        const v3 *P = net->pts + pl->off;
        if (pl->n >= 2 && memcmp(&P[0], &start, sizeof(v3)) == 0 && memcmp(&P[pl->n - 1], &end, sizeof(v3)) == 0)
            st->first_reached++;
    }
    return 0;
}

static banyan_status build_hosts(const banyan_roots_params *p, const banyan_hosts *hosts, roots_net *net, prog *g,
                                 banyan_error *err) {
    memset(net, 0, sizeof *net);
    banyan_status s = roots_params_check(p, err);
    if (s) return s;
    if (!hosts)
        return banyan_fail(err, BANYAN_E_NO_HOSTS,
                           "hosts is NULL: strangler-fig roots need a host set (banyan_hosts_create) to grow around");
    uint32_t n_hosts = hosts->n_boxes + hosts->n_meshes;
    if (n_hosts == 0)
        return banyan_fail(err, BANYAN_E_NO_HOSTS, "the host set is empty: strangler-fig roots need a host");
    net->hosts = hosts;
    net->prog = g;
    if (g) prog_budget(g, p->max_seconds, p->max_memory_mb);
    net->u = p->unit;
    net->r = p->radius * p->unit;
    net->w.hosts = hosts->boxes;
    net->w.n_hosts = hosts->n_boxes;
    net->w.meshes = hosts->meshes;
    net->w.n_meshes = hosts->n_meshes;
    net->w.set = hosts;
    if (hosts->n_meshes) {
        net->w.hint = malloc(sizeof(uint32_t) * hosts->n_meshes);
        if (!net->w.hint) return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for %u mesh hosts", hosts->n_meshes);
        memset(net->w.hint, 0xff, sizeof(uint32_t) * hosts->n_meshes);
    }
    net->w.ground = p->ground;
    const v3 O = hosts->origin; /* the set's frame: G and ground_z move into it */
    net->w.ground_z = p->ground_z - O.z;
    net->w.r = net->r;
    net->w.eps = 1e-9 * net->r;

    v3 G;
    if ((s = germination(p, hosts, net, &G, err))) {
        roots_net_free(net);
        return s;
    }
    /* Roots grow near G: G beyond the frame would lose millimetres. */
    if (fmax(fmax(fabs(G.x), fabs(G.y)), fabs(G.z)) > FRAME_KEEP) {
        v3 lo, hi;
        frame_empty(&lo, &hi);
        frame_add(&lo, &hi, v3_add(G, O));
        for (uint32_t i = 0; i < n_hosts; i++)
            frame_add(&lo, &hi, v3_add(hosts->lo[i], O)), frame_add(&lo, &hi, v3_add(hosts->hi[i], O));
        s = frame_check(lo, hi, O, "the hosts and germination point G", err);
        roots_net_free(net);
        return s;
    }
    world_push_out(&net->w, &G); /* closer than r to a host: out to r */
    net->G = G;

    if ((s = size_net(p, net, err))) {
        roots_net_free(net);
        return s;
    }
    size_t N = (size_t)net->N, B = (size_t)net->B, nb = (size_t)net->nb;
    size_t slots = N * (nb ? nb : 1);

    for (size_t t = 0; t < slots; t++) net->K_end[t] = (int32_t)(t % (nb ? nb : 1)); /* level */
    roots_grow_mains(net, p);
    if (prog_stopped(g)) goto cancelled;
    memcpy(net->M, net->M_grown, sizeof(v3) * N * B);
    roots_grow_first(net, p);
    if (prog_stopped(g)) goto cancelled;
    roots_correct_mains(net, p);
    if (prog_stopped(g)) goto cancelled;
    roots_press_first(net, p);
    if (prog_at(g, ROOTS_AT_FIRST)) goto cancelled;
    roots_grow_second(net, p);
    if (prog_at(g, ROOTS_AT_SECOND)) goto cancelled;
    if ((s = roots_make_paths(net, p)) || (!prog_stopped(g) && (s = roots_grow_foot(net, p))) ||
        (!prog_stopped(g) && (s = roots_grow_aerial(net, p)))) {
        roots_net_free(net);
        return banyan_fail(err, s, "out of memory for the roots paths");
    }
    if (prog_at(g, ROOTS_AT_PATHS)) goto cancelled;

    if (net_stats(net, p)) goto cancelled;
    if (prog_at(g, ROOTS_AT_MESH)) goto cancelled;
    return BANYAN_OK;
cancelled:
    roots_net_free(net);
    return prog_fail(g, err, "roots");
}

static banyan_status finish(roots_net *net, banyan_status s, const banyan_roots_params *params, banyan_mesh **out,
                            banyan_roots_stats *stats, banyan_error *err) {
    if (s) return s;
    banyan_roots_stats st = net->stats;
    s = roots_net_mesh(net, params, out, &st, err);
    if (!s) {
        roots_soil_line(net, params, *out);
        frame_set(*out, net->hosts->origin);
    }
    roots_net_free(net);
    if (s == BANYAN_OK && stats) *stats = st;
    return s;
}

banyan_status banyan_roots_generate(const banyan_roots_params *params, const banyan_hosts *hosts, banyan_mesh **out,
                                    banyan_roots_stats *stats, const banyan_progress *progress, banyan_error *err) {
    if (stats) memset(stats, 0, sizeof *stats);
    BANYAN_CHECK_OUT(out, err);
    banyan_status s = prog_check(progress, err);
    if (s) return s;
    prog g; /* with or without a callback: it keeps the budget */
    prog_init(&g, progress);
    roots_net net;
    s = finish(&net, build_hosts(params, hosts, &net, &g, err), params, out, stats, err);
    if (!s && prog_finish(&g)) {
        banyan_mesh_free(*out);
        *out = NULL;
        if (stats) memset(stats, 0, sizeof *stats);
        s = prog_fail(&g, err, "roots");
    }
    return s;
}

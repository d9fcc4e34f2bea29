/* Caps over a closed mesh's holes, for its inside test (docs/hosts.md,
 * "Inside"). A solid with holes (Suzanne's open eye sockets, a sculpt with
 * pin holes) has no inside of its own; banyan takes the generalised
 * winding number's (Jacobson, Kavan and Sorkine-Hornung 2013): inside
 * where |w| > 1/2. With each hole's boundary loop closed by a fan from the
 * loop's centroid (the caps C), S + C has no boundary, so
 *   w_S(p) = w_{S+C}(p) - w_C(p),
 * the first an integer the rays count (exits minus entries, caps
 * included: host_queries.c), the second a sum of solid angles over the few
 * cap triangles. Exact up to rounding, and about as cheap as the rays. */
#include <math.h>
#include <stdlib.h>

#include "hosts.h"

typedef struct bedge {
    uint32_t from, to;
} bedge;

static int by_from(const void *pa, const void *pb) {
    const bedge *a = (const bedge *)pa, *b = (const bedge *)pb;
    if (a->from != b->from) return a->from < b->from ? -1 : 1;
    return a->to < b->to ? -1 : a->to > b->to;
}

/* The first edge leaving vertex v (E sorted by from), or nb. */
static size_t first_from(const bedge *E, size_t nb, uint32_t v) {
    size_t lo = 0, hi = nb;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (E[mid].from < v) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

static void put(float *f, v3 v) { f[0] = (float)v.x, f[1] = (float)v.y, f[2] = (float)v.z; }

int hmesh_build_caps(host_mesh *m) {
    const size_t ne = 3 * (size_t)m->nt;
    size_t nb = 0;
    for (size_t e = 0; e < ne; e++) nb += m->twin[e] == UINT32_MAX;
    if (nb == 0) return 1;
    bedge *E = malloc(sizeof *E * nb);
    size_t *loop = malloc(sizeof *loop * nb);
    unsigned char *used = calloc(nb, 1);
    float *capv = malloc(sizeof(float) * 9 * nb);
    if (!E || !loop || !used || !capv) {
        free(E), free(loop), free(used), free(capv);
        return 0;
    }
    nb = 0;
    for (size_t e = 0; e < ne; e++)
        if (m->twin[e] == UINT32_MAX) E[nb++] = (bedge){m->tri[e], m->tri[e % 3 == 2 ? e - 2 : e + 1]};
    qsort(E, nb, sizeof *E, by_from);
    /* Each vertex has as many boundary sides in as out (a consistently
     * wound, edge-manifold mesh), so a walk along unused sides ends only
     * where it began: the loops. */
    uint32_t nc = 0;
    for (size_t s = 0; s < nb; s++) {
        if (used[s]) continue;
        size_t n = 0;
        for (size_t e = s; e < nb;) {
            used[e] = 1;
            loop[n++] = e;
            uint32_t v = E[e].to;
            size_t k = first_from(E, nb, v);
            while (k < nb && E[k].from == v && used[k]) k++;
            e = k < nb && E[k].from == v ? k : nb;
        }
        v3 c = v3_make(0, 0, 0);
        for (size_t i = 0; i < n; i++) c = v3_add(c, vtx(m, E[loop[i]].from));
        c = v3_scale(c, 1.0 / (double)n);
        for (size_t i = 0; i < n; i++) { /* (c, to, from): the side runs the other way round the cap */
            float *f = capv + 9 * (size_t)nc++;
            put(f, c);
            put(f + 3, vtx(m, E[loop[i]].to));
            put(f + 6, vtx(m, E[loop[i]].from));
        }
    }
    free(E), free(loop), free(used);
    m->capv = capv;
    m->ncap = nc;
    return 1;
}

double hmesh_cap_winding(const host_mesh *m, v3 p) {
    double total = 0;
    for (uint32_t i = 0; i < m->ncap; i++) { /* the solid angle of each (Van Oosterom and Strackee 1983) */
        const float *f = m->capv + 9 * (size_t)i;
        v3 a = v3_sub(f3(f), p), b = v3_sub(f3(f + 3), p), c = v3_sub(f3(f + 6), p);
        double la = v3_len(a), lb = v3_len(b), lc = v3_len(c);
        double det = v3_dot(a, v3_cross(b, c));
        double div = la * lb * lc + v3_dot(a, b) * lc + v3_dot(a, c) * lb + v3_dot(b, c) * la;
        total += dm_atan2(det, div);
    }
    return total / (2.0 * 3.14159265358979323846);
}

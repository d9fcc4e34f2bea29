/* Ivy measures (spec/ivy.md, "Density measure"): branch points plus stem
 * crossings per square metre of covered host, seen along the host normal.
 *
 * Every bud belongs to the face of its nearest host (host, face; the
 * ground counts as a host here whatever its kind). A mesh host has no
 * faces of its own: its "faces" are a cube map, the world axis along
 * which the nearest triangle's normal is largest and its sign, and a bud
 * is projected along that axis (docs/ivy.md). An
 * internode belongs to the face of its end bud; both its ends are
 * projected onto that face's plane. Two internodes of the same face cross
 * when their projections properly intersect (internodes that share a bud
 * do not count). A 2D grid of 2 l cells keeps this near linear: each
 * internode goes into the cells its box touches, and a pair counts only in
 * the cell holding the crossing point, so it counts once.
 * Covered area: the number of distinct stats_cell x stats_cell cells of
 * the face grids that hold a bud, times the cell area. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "ivy_internal.h"

typedef struct seg2 {
    double a[2], b[2];
    int32_t face, child, parent;
} seg2;

typedef struct entry {
    uint64_t key;
    int32_t seg;
} entry;

static int cmp_entry(const void *x, const void *y) {
    const entry *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return (a->seg > b->seg) - (a->seg < b->seg);
}

static int cmp_u64(const void *x, const void *y) {
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* The 2D chart of a face: a box face's own axes about the box centre; a
 * mesh's cube-map face (world axis k) the world plane across k, the point
 * projected along k. */
static void face_uv(const banyan_ivy *iv, int32_t host, int face, v3 p, double uv[2]) {
    int k = face / 2, i = (k + 1) % 3, j = (k + 2) % 3;
    if ((uint32_t)host < iv->n_hosts) {
        const obb *o = &iv->hosts[host];
        v3 d = v3_sub(p, o->c);
        uv[0] = v3_dot(d, o->ax[i]);
        uv[1] = v3_dot(d, o->ax[j]);
    } else {
        const double c[3] = {p.x, p.y, p.z};
        uv[0] = c[i];
        uv[1] = c[j];
    }
}

static int64_t cell_of(double v, double inv) {
    double f = floor(v * inv);
    const double lim = (double)(1 << 25) - 1;
    if (!(f > -lim)) f = -lim;
    if (f > lim) f = lim;
    return (int64_t)f;
}

static uint64_t key_of(int32_t face, int64_t iu, int64_t iv) {
    return (uint64_t)face << 52 | (uint64_t)(iu + (1 << 25)) << 26 | (uint64_t)(iv + (1 << 25));
}

static double cross2(const double *o, const double *a, const double *b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

int32_t ivy_growth_check(const banyan_ivy *iv) {
    /* Per leading stem: five stems boxed in after one internode each have
     * not grown either. */
    int64_t need = (int64_t)(iv->step < BANYAN_IVY_MIN_INTERNODES ? iv->step : BANYAN_IVY_MIN_INTERNODES) * iv->roots;
    int32_t internodes = iv->n - iv->roots; /* every bud but the first buds ends one */
    if (internodes >= need) return BANYAN_IVY_GREW;
    return internodes == 0 ? BANYAN_IVY_BLOCKED : BANYAN_IVY_STUNTED;
}

const char *banyan_ivy_growth_text(int32_t cannot_grow) {
    switch (cannot_grow) {
    case BANYAN_IVY_GREW: return "the ivy grew";
    case BANYAN_IVY_BLOCKED:
        return "the ivy could not grow: every direction from its start is blocked by a host or the ground; "
               "move the start onto a free side of a host, above the ground";
    case BANYAN_IVY_STUNTED:
        return "the ivy could not grow: it is boxed in after a few internodes; move the start onto an open side "
               "of a host, above the ground";
    default: return "unknown ivy growth value";
    }
}

banyan_status banyan_ivy_get_stats(const banyan_ivy *iv, banyan_ivy_stats *out, banyan_error *err) {
    if (!iv || !out) return banyan_fail(err, BANYAN_E_INVALID_ARG, "ivy and out must not be NULL");
    memset(out, 0, sizeof *out);
    const banyan_ivy_params *p = &iv->p;
    const int32_t n = iv->n;
    out->steps = iv->step;
    out->buds = n;
    out->branch_points = iv->branch_points;
    out->step_seconds = iv->step_seconds;
    out->cannot_grow = ivy_growth_check(iv);
    for (int32_t i = 0; i < n; i++) {
        const ivy_bud *b = &iv->buds[i];
        out->by_state[b->state]++;
        out->attached += b->attached;
        if (b->parent >= 0) out->stem_length += v3_dist(b->P, iv->buds[b->parent].P);
    }
    out->attached_fraction = n ? (double)out->attached / n : 0.0;

    int32_t *face = malloc(sizeof(int32_t) * (size_t)n);
    uint64_t *cover = malloc(sizeof(uint64_t) * (size_t)n);
    seg2 *seg = malloc(sizeof(seg2) * (size_t)n);
    if (!face || !cover || !seg) {
        free(face); free(cover); free(seg);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the ivy measures");
    }

    /* Faces and covered cells. */
    const double inv_cover = 1.0 / p->stats_cell;
    for (int32_t i = 0; i < n; i++) {
        ivy_near nr = ivy_nearest_any(iv, iv->buds[i].P);
        face[i] = nr.host * 6 + nr.face;
        double uv[2];
        face_uv(iv, nr.host, nr.face, iv->buds[i].P, uv);
        cover[i] = key_of(face[i], cell_of(uv[0], inv_cover), cell_of(uv[1], inv_cover));
    }
    qsort(cover, (size_t)n, sizeof *cover, cmp_u64);
    int32_t cells = 0;
    for (int32_t i = 0; i < n; i++) cells += i == 0 || cover[i] != cover[i - 1];
    out->covered_area = cells * p->stats_cell * p->stats_cell;

    /* Internodes projected on their faces, and their grid entries. */
    int32_t ns = 0;
    size_t ne = 0, cap = (size_t)n * 4 + 16;
    entry *e = malloc(sizeof(entry) * cap);
    const double gcell = 2.0 * p->internode, ginv = 1.0 / gcell;
    for (int32_t i = 0; i < n && e; i++) {
        const ivy_bud *b = &iv->buds[i];
        if (b->parent < 0) continue;
        seg2 *s = &seg[ns];
        s->face = face[i];
        s->child = i;
        s->parent = b->parent;
        face_uv(iv, face[i] / 6, face[i] % 6, b->P, s->a);
        face_uv(iv, face[i] / 6, face[i] % 6, iv->buds[b->parent].P, s->b);
        int64_t u0 = cell_of(fmin(s->a[0], s->b[0]), ginv), u1 = cell_of(fmax(s->a[0], s->b[0]), ginv);
        int64_t v0 = cell_of(fmin(s->a[1], s->b[1]), ginv), v1 = cell_of(fmax(s->a[1], s->b[1]), ginv);
        for (int64_t u = u0; u <= u1 && e; u++)
            for (int64_t v = v0; v <= v1; v++) {
                if (ne == cap) {
                    entry *g = realloc(e, sizeof(entry) * cap * 2);
                    if (!g) { free(e); e = NULL; break; }
                    e = g;
                    cap *= 2;
                }
                e[ne].key = key_of(s->face, u, v);
                e[ne++].seg = ns;
            }
        ns++;
    }
    if (!e) {
        free(face); free(cover); free(seg);
        return banyan_fail(err, BANYAN_E_NOMEM, "out of memory for the ivy crossing grid");
    }
    qsort(e, ne, sizeof *e, cmp_entry);
    int32_t crossings = 0;
    for (size_t g = 0; g < ne;) {
        size_t h = g;
        while (h < ne && e[h].key == e[g].key) h++;
        for (size_t x = g; x < h; x++)
            for (size_t y = x + 1; y < h; y++) {
                const seg2 *s = &seg[e[x].seg], *t = &seg[e[y].seg];
                if (s->parent == t->parent || s->parent == t->child || t->parent == s->child) continue;
                double d1 = cross2(s->a, s->b, t->a), d2 = cross2(s->a, s->b, t->b);
                double d3 = cross2(t->a, t->b, s->a), d4 = cross2(t->a, t->b, s->b);
                if (!((d1 > 0) != (d2 > 0) && d1 != 0 && d2 != 0 && (d3 > 0) != (d4 > 0) && d3 != 0 && d4 != 0)) continue;
                double k = d3 / (d3 - d4); /* along s */
                double X[2] = {s->a[0] + k * (s->b[0] - s->a[0]), s->a[1] + k * (s->b[1] - s->a[1])};
                if (key_of(s->face, cell_of(X[0], ginv), cell_of(X[1], ginv)) == e[g].key) crossings++;
            }
        g = h;
    }
    out->crossings = crossings;
    out->density = out->covered_area > 0 ? (out->branch_points + crossings) / out->covered_area : 0.0;
    free(e); free(face); free(cover); free(seg);
    banyan_error_clear(err);
    return BANYAN_OK;
}

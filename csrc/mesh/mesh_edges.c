/* banyan_triangle_edges: the unique edges of a triangle list and each
 * corner's edge, for hosts that store meshes by edges (Blender's loops and
 * edges), which would otherwise derive them with a hash table of their own. */
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "base/error.h"

/* One corner's edge, filed under its lower vertex. */
typedef struct edge_ref {
    uint32_t hi, corner;
} edge_ref;

static int ref_cmp(const void *pa, const void *pb) {
    const edge_ref *a = pa, *b = pb;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->corner < b->corner ? -1 : a->corner > b->corner;
}

/* By (hi, corner). A vertex files a few edges, so insertion sort; qsort
 * for a crowded one (a fan's centre) keeps the worst case n log n. */
static void sort_refs(edge_ref *r, uint32_t n) {
    if (n > 32) {
        qsort(r, n, sizeof *r, ref_cmp);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        edge_ref x = r[i];
        uint32_t j = i;
        for (; j > 0 && ref_cmp(&r[j - 1], &x) > 0; j--) r[j] = r[j - 1];
        r[j] = x;
    }
}

/* The corner after k in its triangle. */
static uint32_t next_corner(uint32_t k) { return k % 3 == 2 ? k - 2 : k + 1; }

/* The edge of each corner, by first use: each lower vertex heads a list of
 * its edges, walked for the upper one. Meshes from the generators (rings,
 * cards) file a few edges per vertex, so a corner costs a few steps; a
 * crowded vertex (a fan's centre) makes walks quadratic, so past `budget`
 * steps in all this gives up (returns 1) for by_buckets. Returns 2 when
 * there are more than `cap` edges. */
static int by_lists(const uint32_t *indices, uint32_t n, uint32_t vertex_count, uint32_t *corner_edges,
                    uint32_t *edges, uint64_t cap, uint64_t *count, uint64_t budget, int *nomem) {
    uint32_t *head = malloc((size_t)vertex_count * sizeof *head + 1), *next = malloc((size_t)n * sizeof *next + 1);
    int rc = 0;
    *nomem = !head || !next;
    if (*nomem) goto out;
    memset(head, 0xff, (size_t)vertex_count * sizeof *head); /* UINT32_MAX: no edge */
    uint32_t ne = 0;
    uint64_t steps = 0;
    for (uint32_t k = 0; k < n && !rc; k++) {
        uint32_t a = indices[k], b = indices[next_corner(k)];
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a, e = head[lo];
        for (; e != UINT32_MAX && edges[2 * (size_t)e + 1] != hi; e = next[e]) steps++;
        if (steps > budget) rc = 1;
        else if (e == UINT32_MAX && ne == cap) rc = 2;
        else if (e == UINT32_MAX) {
            e = ne++;
            edges[2 * (size_t)e] = lo;
            edges[2 * (size_t)e + 1] = hi;
            next[e] = head[lo];
            head[lo] = e;
        }
        corner_edges[k] = e;
    }
    *count = ne;
out:
    free(head);
    free(next);
    return rc;
}

/* The same by sorting: the corners bucketed by lower vertex (a counting
 * sort, corners in order within a bucket); a run of equal upper vertices
 * in a sorted bucket is one edge, first used by the run's first corner.
 * n log n at worst, two to three times slower than by_lists on a mesh. */
static int by_buckets(const uint32_t *indices, uint32_t n, uint32_t vertex_count, uint32_t *corner_edges,
                      uint32_t *edges, uint64_t cap, uint64_t *count, int *nomem) {
    uint32_t *end = calloc((size_t)vertex_count + 1, sizeof *end);
    edge_ref *refs = malloc((size_t)n * sizeof *refs + 1);
    *nomem = !end || !refs;
    if (*nomem) {
        free(end);
        free(refs);
        return 0;
    }
    for (uint32_t k = 0; k < n; k++) {
        uint32_t a = indices[k], b = indices[next_corner(k)];
        end[(a < b ? a : b) + 1]++;
    }
    for (uint32_t v = 0; v < vertex_count; v++) end[v + 1] += end[v];
    for (uint32_t k = 0; k < n; k++) { /* end[v] moves from v's start to its end */
        uint32_t a = indices[k], b = indices[next_corner(k)];
        edge_ref r = {a < b ? b : a, k};
        refs[end[a < b ? a : b]++] = r;
    }
    /* corner_edges[k] = the first corner of k's edge, for now */
    for (uint32_t v = 0, lo = 0; v < vertex_count; lo = end[v++]) {
        edge_ref *r = refs + lo;
        uint32_t m = end[v] - lo;
        sort_refs(r, m);
        for (uint32_t i = 0, first = 0; i < m; i++) {
            if (r[i].hi != r[first].hi) first = i;
            corner_edges[r[i].corner] = r[first].corner;
        }
    }
    free(end);
    free(refs);
    /* Number the edges by first use; a corner's first corner is never later. */
    uint64_t ne = 0;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t first = corner_edges[k];
        if (first != k) {
            corner_edges[k] = corner_edges[first];
            continue;
        }
        if (ne == cap) return 2;
        uint32_t a = indices[k], b = indices[next_corner(k)];
        edges[2 * ne] = a < b ? a : b;
        edges[2 * ne + 1] = a < b ? b : a;
        corner_edges[k] = (uint32_t)ne++;
    }
    *count = ne;
    return 0;
}

static int u32_cmp(const void *pa, const void *pb) {
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* The vertices the n corners use, in order, into *ids (*m of them) and
 * each corner's rank among them into *ranked: for a vertex_count far
 * above the corners (one triangle of a 1e9-vertex mesh), which the
 * per-vertex tables of by_lists and by_buckets would be sized by. The
 * ranks keep the vertices' order, so lower stays lower and the edges come
 * out the same. 0 when there is no memory. */
static int compact(const uint32_t *indices, uint32_t n, uint32_t **ranked, uint32_t **ids, uint32_t *m) {
    *ranked = malloc((size_t)n * sizeof **ranked + 1);
    *ids = malloc((size_t)n * sizeof **ids + 1);
    if (!*ranked || !*ids) return 0;
    memcpy(*ids, indices, (size_t)n * sizeof **ids);
    qsort(*ids, n, sizeof **ids, u32_cmp);
    uint32_t u = 0;
    for (uint32_t k = 0; k < n; k++)
        if (u == 0 || (*ids)[u - 1] != (*ids)[k]) (*ids)[u++] = (*ids)[k];
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t *hit = bsearch(&indices[k], *ids, u, sizeof **ids, u32_cmp);
        (*ranked)[k] = (uint32_t)(hit - *ids);
    }
    *m = u;
    return 1;
}

banyan_status banyan_triangle_edges(const uint32_t *indices, uint64_t index_count, uint32_t vertex_count,
                                    uint32_t *corner_edges, uint32_t *edges, uint64_t edge_capacity,
                                    uint64_t *edge_count, uint32_t *face_starts, banyan_error *err) {
    if (!edge_count || ((!indices || !corner_edges || !edges) && index_count))
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "indices, corner_edges, edges and edge_count must not be NULL");
    *edge_count = 0;
    if (index_count % 3)
        return banyan_fail(err, BANYAN_E_INVALID_ARG, "index_count = %llu is not a multiple of 3",
                           (unsigned long long)index_count);
    if (index_count > UINT32_MAX)
        return banyan_fail(err, BANYAN_E_RANGE, "index_count = %llu must be at most %u",
                           (unsigned long long)index_count, UINT32_MAX);
    uint32_t n = (uint32_t)index_count;
    for (uint32_t k = 0; k < n; k++)
        if (indices[k] >= vertex_count)
            return banyan_fail(err, BANYAN_E_RANGE, "indices[%u] = %u is out of range [0, %u)", k, indices[k],
                               vertex_count);
    uint64_t ne = 0;
    int nomem = 0;
    /* Tables per vertex cost 4 to 8 bytes a vertex: past twice the corners
     * (plus some slack for small meshes) number the used vertices instead,
     * so memory follows index_count whatever vertex_count says. */
    uint32_t *ranked = NULL, *ids = NULL, used = vertex_count;
    const uint32_t *idx = indices;
    if ((uint64_t)vertex_count > 2 * (uint64_t)n + 4096) {
        nomem = !compact(indices, n, &ranked, &ids, &used);
        idx = ranked;
    }
    int rc = 0;
    if (!nomem) {
        rc = by_lists(idx, n, used, corner_edges, edges, edge_capacity, &ne, 16 * (uint64_t)n + 4096, &nomem);
        if (rc == 1 || nomem) rc = by_buckets(idx, n, used, corner_edges, edges, edge_capacity, &ne, &nomem);
    }
    if (ids && !nomem && rc == 0)
        for (uint64_t e = 0; e < 2 * ne; e++) edges[e] = ids[edges[e]];
    free(ranked);
    free(ids);
    if (nomem) return banyan_fail(err, BANYAN_E_NOMEM, "no memory for the edges of %u corners", n);
    if (rc == 2)
        return banyan_fail(err, BANYAN_E_RANGE, "the triangles have more than edge_capacity = %llu edges",
                           (unsigned long long)edge_capacity);
    if (face_starts)
        for (uint32_t t = 0; t < n / 3; t++) face_starts[t] = 3 * t;
    *edge_count = ne;
    banyan_error_clear(err);
    return BANYAN_OK;
}

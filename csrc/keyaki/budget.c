/* budget.c - a keyaki run's budget inside the tree's loops (keyaki_run in
 * keyaki_internal.h; docs/keyaki.md "Budget"): the caller's prog keeps time
 * and memory, a shared flag carries its stop to an avenue's other threads,
 * and lower bounds of the vertices refuse a tree (or an avenue) that
 * cannot fit max_vertices before it is grown in full. */
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "keyaki_internal.h"

int keyaki_stopped(keyaki_run *r) {
    if (!r) return 0;
    if (r->stop && atomic_load_explicit(r->stop, memory_order_relaxed)) return 1;
    if (r->g && prog_at(r->g, r->g->last)) {
        if (r->stop) atomic_store(r->stop, 1);
        return 1;
    }
    return 0;
}

int keyaki_stage(keyaki_run *r, double done) {
    if (!r || !r->stages || !r->g) return 0;
    return prog_at(r->g, done);
}

banyan_status keyaki_stop_status(banyan_error *err) {
    return banyan_fail(err, BANYAN_E_CANCELLED, "stopped: the run's budget is spent or it was cancelled");
}

banyan_status keyaki_promise(keyaki_run *r, uint64_t vertices, const char *what, const char *lower,
                             banyan_error *err) {
    if (!r || r->max_vertices == UINT64_MAX || vertices <= r->promised) return BANYAN_OK;
    uint64_t more = vertices - r->promised, total = vertices;
    if (r->tally) total = atomic_fetch_add(r->tally, more) + more;
    r->promised = vertices;
    if (total <= r->max_vertices) return BANYAN_OK;
    if (r->tally)
        return banyan_fail(err, BANYAN_E_LIMIT,
                           "%s need at least %" PRIu64 " vertices, and with the other trees the avenue at least %"
                           PRIu64 ", more than max_vertices = %" PRIu64 "; raise max_vertices or lower %s",
                           what, vertices, total, r->max_vertices, lower);
    return banyan_fail(err, BANYAN_E_LIMIT,
                       "%s need at least %" PRIu64 " vertices, more than max_vertices = %" PRIu64
                       "; raise max_vertices or lower %s",
                       what, vertices, r->max_vertices, lower);
}

int keyaki_reserve_bytes(keyaki_run *r, double bytes) {
    if (!r || !r->g) return 0;
    if (prog_reserve(r->g, bytes)) {
        if (r->stop) atomic_store(r->stop, 1);
        return 1;
    }
    return 0;
}

/* Bottom-up merge sort, checking the run every KEYAKI_SORT_CHECK elements
 * moved; runs below KEYAKI_SORT_SMALL elements go to qsort (cmp is a total
 * order, so both give the same array). */
#define KEYAKI_SORT_SMALL 65536
#define KEYAKI_SORT_CHECK 65536

int keyaki_sort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *), keyaki_run *r) {
    if (n < KEYAKI_SORT_SMALL || !r) {
        qsort(base, n, size, cmp);
        return 0;
    }
    unsigned char *a = base, *b = malloc(n * size), *tmp = b;
    if (!b) { /* no room to merge: unchecked, as before */
        qsort(base, n, size, cmp);
        return 0;
    }
    /* Runs of 32 by qsort, then merges of doubling width from a into b. */
    size_t w = 32;
    for (size_t i = 0; i < n; i += w) qsort(a + i * size, n - i < w ? n - i : w, size, cmp);
    size_t moved = 0;
    for (; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid || j < hi) {
                /* Ties take the left run: stable, as a total order needs no more. */
                int left = j >= hi || (i < mid && cmp(a + i * size, a + j * size) <= 0);
                memcpy(b + k * size, a + (left ? i++ : j++) * size, size);
                k++;
                if (++moved % KEYAKI_SORT_CHECK == 0 && keyaki_stopped(r)) {
                    free(tmp); /* the array is left part sorted: the run is over */
                    return 1;
                }
            }
        }
        unsigned char *t = a;
        a = b;
        b = t;
    }
    if (a != base) memcpy(base, a, n * size);
    free(tmp);
    return 0;
}

/* Ivy look-ups (spec/ivy.md, "Light" and "Placement"): the spatial hash
 * over bud positions that makes the light query cost the same at 100 buds
 * and at 100,000, the light sum H0 / V_l itself, and the host queries of
 * the random walk (nearest surface, collision, push-out) on boxes and on
 * the triangle meshes of a host set.
 *
 * The hash has cells of leaf_max, the look-up radius, so a query reads
 * the 27 cells around a point. Each cell (an open addressing table keyed
 * by its coordinates) keeps a copy of its buds (position, birth step,
 * index) in one run of a pool, so a query reads 27 table slots and a few
 * short runs. A chain of buds linked by index, as before, jumped over the
 * whole plant at every link: past ~50k buds each was a cache miss and the
 * cost per bud doubled by 250k. The runs are read in the order
 * the chains were, so the light sums are the same to the bit. A query
 * asks for all its slots, then all its runs, before reading any: misses
 * overlap instead of coming one after another (docs/ivy.md, "At scale").
 *
 * Shade at a point never falls while buds stay put (leaves only grow, buds
 * are only added), and a test that finds a bud too shaded rests only on
 * the buds it counted before passing t0: the others could only add shade.
 * So the bud sleeps until one of those moves (the sag correction), or it
 * or one of its H1 buds moves. Each sleep leaves an edge at every bud the
 * test counted; a move walks the mover's edges and wakes their sleepers.
 * Waiting buds then cost nothing, and a move costs its own edges, not a
 * walk of the neighbourhood. This changes no result: a bud that sleeps
 * would test too shaded, and a bud woken needlessly tests so again. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ivy_internal.h"

/* ------------------------------------------------------------ hosts */

/* Boxes keep their exact obb queries, in the order they always had (so a
 * box-only plant is the same to the byte); the meshes of a host set come
 * after them in every query, through hosts/hosts.h. A mesh query is asked
 * with a cap (exact below it, +-cap beyond): the farthest that matters to
 * the caller. */

/* The face of o whose plane p (in o's frame) is farthest outside of, or
 * least inside. */
static int face_of(const obb *o, v3 l) {
    double c[3] = {l.x, l.y, l.z};
    int best = 0;
    double q = fabs(c[0]) - o->h[0];
    for (int k = 1; k < 3; k++) {
        double t = fabs(c[k]) - o->h[k];
        if (t > q) { q = t; best = k; }
    }
    return 2 * best + (c[best] >= 0 ? 1 : 0);
}

/* A mesh triangle's cube-map face: the world axis of its normal's largest
 * component, and that component's sign (0..5 as face_of). */
static int mesh_face(const host_mesh *m, uint32_t prim) {
    const float *n = m->fnrm + 3 * (size_t)prim;
    int k = fabsf(n[1]) > fabsf(n[0]) ? 1 : 0;
    if (fabsf(n[2]) > fabsf(n[k])) k = 2;
    return 2 * k + (n[k] >= 0 ? 1 : 0);
}

void ivy_host_boxes(banyan_ivy *iv) {
    const double c = iv->p.clearance; /* the same sums as ivy_far_from(..., clearance) */
    for (uint32_t h = 0; h < iv->n_hosts; h++) {
        const obb *o = &iv->hosts[h];
        v3 e = v3_make(0, 0, 0);
        for (int k = 0; k < 3; k++) {
            e.x += fabs(o->ax[k].x) * o->h[k];
            e.y += fabs(o->ax[k].y) * o->h[k];
            e.z += fabs(o->ax[k].z) * o->h[k];
        }
        iv->box_lo[h] = v3_sub(o->c, e);
        iv->box_hi[h] = v3_add(o->c, e);
        iv->clear_lo[h] = v3_make(iv->box_lo[h].x - c, iv->box_lo[h].y - c, iv->box_lo[h].z - c);
        iv->clear_hi[h] = v3_make(iv->box_hi[h].x + c, iv->box_hi[h].y + c, iv->box_hi[h].z + c);
    }
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        uint32_t h = iv->mesh0 + m;
        iv->box_lo[h] = iv->meshes[m].lo;
        iv->box_hi[h] = iv->meshes[m].hi;
        iv->clear_lo[h] = v3_make(iv->box_lo[h].x - c, iv->box_lo[h].y - c, iv->box_lo[h].z - c);
        iv->clear_hi[h] = v3_make(iv->box_hi[h].x + c, iv->box_hi[h].y + c, iv->box_hi[h].z + c);
    }
}

/* A cap for the mesh queries: they refuse 0. */
static inline double mesh_cap(double cap) { return cap > 1e-9 ? cap : 1e-9; }

double ivy_grip_distance(const banyan_ivy *iv, v3 p, double cap) {
    double best = HUGE_VAL;
    for (uint32_t h = 0; h < iv->n_grip; h++) {
        if (ivy_far_from(iv, h, p, cap)) continue;
        double d = obb_signed_distance(&iv->hosts[h], p);
        if (d < best) best = d;
    }
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        if (ivy_far_from(iv, iv->mesh0 + m, p, cap)) continue;
        const double q = mesh_cap(cap);
        double d = hmesh_distance(&iv->meshes[m], p, q);
        /* +q means "q or farther" (out of reach); -q (deep inside) is a bound that still reads as inside. */
        if (d < q && d < best) best = d;
    }
    return best;
}

/* The box part of ivy_nearest_of, as it always was; then the meshes, each
 * looked for within the nearest so far (and within cap). */
static ivy_near nearest(const banyan_ivy *iv, v3 p, uint32_t n, double cap) {
    ivy_near r = {HUGE_VAL, {0, 0, 1}, {0, 0, 0}, 0, 5};
    r.point = p;
    for (uint32_t h = 0; h < n; h++) {
        double d = obb_signed_distance(&iv->hosts[h], p);
        if (d < r.dist) { r.dist = d; r.host = (int32_t)h; }
    }
    int32_t best_mesh = -1;
    mesh_near mn, best_mn;
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        /* Only a surface nearer than the best so far can win. A point
         * outside the mesh's bounds grown by that is farther from it. */
        double lim = r.dist < cap ? r.dist : cap;
        if (lim > 0 && lim < HUGE_VAL && ivy_far_from(iv, iv->mesh0 + m, p, lim)) continue;
        if (!hmesh_nearest(&iv->meshes[m], p, lim > 0 ? mesh_cap(lim) : HUGE_VAL, &mn)) continue;
        if (mn.dist < r.dist) {
            r.dist = mn.dist;
            best_mesh = (int32_t)m;
            best_mn = mn;
        }
    }
    if (best_mesh >= 0) {
        r.host = (int32_t)(iv->mesh0 + (uint32_t)best_mesh);
        r.normal = best_mn.normal;
        r.point = best_mn.point;
        r.face = mesh_face(&iv->meshes[best_mesh], best_mn.prim);
    } else if (n && r.dist < HUGE_VAL) {
        const obb *o = &iv->hosts[r.host];
        v3 l = obb_to_local(o, p);
        r.point = obb_closest_surface_local(o, p, l, &r.normal);
        r.face = face_of(o, l);
    }
    return r;
}

ivy_near ivy_nearest_of(const banyan_ivy *iv, v3 p, uint32_t n) { return nearest(iv, p, n, HUGE_VAL); }

ivy_near ivy_nearest_within(const banyan_ivy *iv, v3 p, double cap) { return nearest(iv, p, iv->n_grip, cap); }

int ivy_blocked(const banyan_ivy *iv, v3 a, v3 b, double cap, double *grip) {
    const double c = iv->p.clearance;
    /* The segment's bounding box (positions are finite: plain compares). */
    const v3 mn = v3_make(a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z);
    const v3 mx = v3_make(a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z);
    const uint32_t n_grip = grip ? iv->n_grip : 0;
    double best = HUGE_VAL;
    for (uint32_t h = 0; h < iv->n_hosts; h++) {
        v3 lo = iv->clear_lo[h], hi = iv->clear_hi[h];
        int seg = !(mn.z > hi.z || mx.z < lo.z || mx.x < lo.x || mn.x > hi.x || mx.y < lo.y || mn.y > hi.y);
        int reach = h < n_grip && !ivy_far_from(iv, h, b, cap);
        if (!seg && !reach) continue;
        /* One distance of b serves both questions. */
        double d = obb_signed_distance(&iv->hosts[h], b);
        if (seg && (d < c || obb_segment_hit(&iv->hosts[h], a, b, NULL))) return 1;
        if (reach && d < best) best = d;
    }
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        const uint32_t h = iv->mesh0 + m;
        v3 lo = iv->clear_lo[h], hi = iv->clear_hi[h];
        int seg = !(mn.z > hi.z || mx.z < lo.z || mx.x < lo.x || mn.x > hi.x || mx.y < lo.y || mn.y > hi.y);
        int reach = grip && !ivy_far_from(iv, h, b, cap);
        if (!seg && !reach) continue;
        /* One distance of b, capped at the farthest that matters, answers
         * all three: ends within clearance; can the segment reach a
         * surface at all (not when b is farther from every surface than
         * the segment is long: the ball round b holds the segment); how
         * far is the grip. */
        const double len = v3_dist(a, b);
        double q = seg ? (len > c ? len : c) : 0;
        if (reach && cap > q) q = cap;
        q = mesh_cap(q);
        double d = hmesh_distance(&iv->meshes[m], b, q);
        if (seg) {
            double t;
            v3 nrm;
            if (d < c || (d < len && hmesh_segment_hit(&iv->meshes[m], a, b, &t, &nrm))) return 1;
        }
        if (reach && d < q && d < best) best = d;
    }
    if (grip) *grip = best;
    return 0;
}

/* Mesh m pushes p out to `clearance` off its surface when p is nearer;
 * returns 1 when it moved p. */
static int push_out_mesh(const banyan_ivy *iv, uint32_t m, v3 *p) {
    const double c = iv->p.clearance;
    mesh_near r;
    if (!hmesh_nearest(&iv->meshes[m], *p, mesh_cap(c), &r)) {
        if (r.dist > 0) return 0;
        hmesh_nearest(&iv->meshes[m], *p, HUGE_VAL, &r); /* deep inside: out by the nearest way */
    }
    if (r.dist >= c) return 0;
    *p = v3_madd(r.point, r.normal, ivy_clear_hair(iv)); /* the mesh is float */
    return 1;
}

v3 ivy_push_out_near(const banyan_ivy *iv, v3 p) {
    const double c = iv->p.clearance;
    /* Rounds: leaving one box may enter a neighbour; in the narrow wedge
     * between a leaning wall and the ground the pushes alternate and close
     * in slowly (4 rounds left a point 3.8 mm off the wall, clearance 4). */
    for (int round = 0; round < 16; round++) {
        int moved = 0;
        for (uint32_t h = 0; h < iv->n_hosts; h++) {
            if (ivy_far_by_clearance(iv, h, p)) continue;
            const obb *o = &iv->hosts[h];
            /* Quick accept: clear of the box by c along one of its axes. */
            v3 l = obb_to_local(o, p);
            if (fabs(l.x) - o->h[0] >= c || fabs(l.y) - o->h[1] >= c || fabs(l.z) - o->h[2] >= c) continue;
            if (obb_signed_distance(o, p) >= c) continue;
            v3 n;
            v3 s = obb_closest_surface(o, p, &n);
            p = v3_madd(s, n, c);
            moved = 1;
        }
        for (uint32_t m = 0; m < iv->n_mesh; m++) {
            if (ivy_far_by_clearance(iv, iv->mesh0 + m, p)) continue;
            moved |= push_out_mesh(iv, m, &p);
        }
        if (!moved) break;
    }
    return p;
}

/* Both ends beyond one face of the box lo..hi: the segment misses it. */
static inline int segment_off_box(v3 a, v3 b, v3 lo, v3 hi) {
    return (a.x < lo.x && b.x < lo.x) || (a.x > hi.x && b.x > hi.x) || (a.y < lo.y && b.y < lo.y) ||
           (a.y > hi.y && b.y > hi.y) || (a.z < lo.z && b.z < lo.z) || (a.z > hi.z && b.z > hi.z);
}

v3 ivy_stop_at_meshes(const banyan_ivy *iv, v3 from, v3 to) {
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        const uint32_t h = iv->mesh0 + m;
        if (segment_off_box(from, to, iv->clear_lo[h], iv->clear_hi[h])) continue;
        double t;
        v3 nrm;
        if (hmesh_segment_hit(&iv->meshes[m], from, to, &t, &nrm))
            to = v3_madd(v3_lerp(from, to, t), nrm, ivy_clear_hair(iv)); /* on the side it came from */
    }
    return to;
}

int ivy_segment_meets_mesh(const banyan_ivy *iv, v3 a, v3 b) {
    for (uint32_t m = 0; m < iv->n_mesh; m++) {
        const uint32_t h = iv->mesh0 + m;
        if (segment_off_box(a, b, iv->box_lo[h], iv->box_hi[h])) continue;
        double t;
        v3 nrm;
        if (hmesh_segment_hit(&iv->meshes[m], a, b, &t, &nrm)) return 1;
    }
    return 0;
}

ivy_near ivy_nearest(const banyan_ivy *iv, v3 p) { return ivy_nearest_of(iv, p, iv->n_grip); }
ivy_near ivy_nearest_any(const banyan_ivy *iv, v3 p) { return ivy_nearest_of(iv, p, iv->n_hosts); }

/* ------------------------------------------------------ spatial hash */

static int32_t cell_coord(double v, double inv) {
    double f = v * inv;
    if (!(f > -1e9)) f = -1e9; /* also catches NaN */
    if (f > 1e9) f = 1e9;
    int32_t i = (int32_t)f; /* floor, without a libm call */
    return i - (f < (double)i);
}

static inline uint32_t cell_hash(int32_t x, int32_t y, int32_t z) {
    uint32_t h = (uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return h;
}

/* The slot of cell (x, y, z): its own, or the empty one it would take. */
static inline ivy_cell *cell_slot(const banyan_ivy *iv, int32_t x, int32_t y, int32_t z) {
    uint32_t k = cell_hash(x, y, z) & iv->cmask;
    for (;;) {
        ivy_cell *c = &iv->cells[k];
        if (c->x == INT32_MIN || (c->x == x && c->y == y && c->z == z)) return c;
        k = (k + 1) & iv->cmask;
    }
}

/* A hint to the cache; nothing where the compiler has no such builtin. */
#if defined(__GNUC__) || defined(__clang__)
#define IVY_PREFETCH(p) __builtin_prefetch(p)
#else
#define IVY_PREFETCH(p) ((void)0)
#endif

/* The cells x0..x1, y0..y1, z0..z1 (at most 4 per axis) that hold buds,
 * in z, y, x order, into out (64 entries); returns how many. The slots
 * and then the runs are asked for in one batch each before any is read:
 * neighbouring cells lie anywhere in the table and the pool, and waiting
 * for each miss in turn was most of a look-up's time once the plant
 * outgrew the caches. An empty home slot settles most cells
 * by a bit test (the bitmap stays in cache; the slots do not). */
static int cells_around(const banyan_ivy *iv, int32_t x0, int32_t x1, int32_t y0, int32_t y1, int32_t z0, int32_t z1,
                        const ivy_cell **out) {
    uint32_t home[64];
    int32_t key[64][3];
    int m = 0;
    /* cell_hash's products, once per coordinate (at most 4 a side). */
    const int32_t nx = x1 - x0 < 3 ? x1 - x0 + 1 : 4, ny = y1 - y0 < 3 ? y1 - y0 + 1 : 4,
                  nz = z1 - z0 < 3 ? z1 - z0 + 1 : 4;
    uint32_t hx[4];
    for (int32_t a = 0; a < nx; a++) hx[a] = (uint32_t)(x0 + a) * 73856093u;
    const uint32_t mask = iv->cmask;
    const uint64_t *bits = iv->cbits;
    for (int32_t c = 0; c < nz; c++) {
        const uint32_t hz = (uint32_t)(z0 + c) * 83492791u;
        for (int32_t b = 0; b < ny; b++) {
            const uint32_t hyz = (uint32_t)(y0 + b) * 19349663u ^ hz;
            for (int32_t a = 0; a < nx; a++) {
                uint32_t h = hx[a] ^ hyz; /* = cell_hash(x0 + a, y0 + b, z0 + c) */
                h ^= h >> 15;
                h *= 0x2c1b3c6du;
                h ^= h >> 12;
                const uint32_t k = h & mask;
                if (!((bits[k >> 6] >> (k & 63)) & 1)) continue;
                IVY_PREFETCH(&iv->cells[k]);
                home[m] = k;
                key[m][0] = x0 + a;
                key[m][1] = y0 + b;
                key[m++][2] = z0 + c;
            }
        }
    }
    int n = 0;
    for (int q = 0; q < m; q++) {
        for (uint32_t k = home[q];; k = (k + 1) & iv->cmask) {
            const ivy_cell *c = &iv->cells[k];
            if (c->x == key[q][0] && c->y == key[q][1] && c->z == key[q][2]) {
                if (c->n > 0) {
                    IVY_PREFETCH(iv->pool + c->at + c->n - 1); /* shade reads the run from its end */
                    IVY_PREFETCH(iv->pool + c->at);
                    out[n++] = c;
                }
                break;
            }
            if (c->x == INT32_MIN) break;
        }
    }
    return n;
}

/* The cells around cell (x, y, z), which exists: the list cells_around
 * gives for x - 1 .. x + 1, y - 1 .. y + 1, z - 1 .. z + 1, read from the
 * cell's row of neighbours instead of hashing 27 cells. */
static int cells_near(const banyan_ivy *iv, int32_t x, int32_t y, int32_t z, const ivy_cell **out) {
    const int32_t *row = iv->cnb[cell_slot(iv, x, y, z)->id];
    uint32_t slot[27];
    int m = 0;
    for (int o = 0; o < 27; o++)
        if (row[o] >= 0) {
            slot[m] = iv->cslot[row[o]];
            IVY_PREFETCH(&iv->cells[slot[m++]]);
        }
    int n = 0;
    for (int q = 0; q < m; q++) {
        const ivy_cell *c = &iv->cells[slot[q]];
        if (c->n > 0) {
            IVY_PREFETCH(iv->pool + c->at + c->n - 1);
            IVY_PREFETCH(iv->pool + c->at);
            out[n++] = c;
        }
    }
    return n;
}

/* Fills the row of neighbours of the new cell c and enters it in theirs. */
static void cell_row(banyan_ivy *iv, const ivy_cell *c) {
    int32_t *row = iv->cnb[c->id];
    int o = 0;
    for (int32_t dz = -1; dz <= 1; dz++)
        for (int32_t dy = -1; dy <= 1; dy++)
            for (int32_t dx = -1; dx <= 1; dx++, o++) {
                const ivy_cell *e = cell_slot(iv, c->x + dx, c->y + dy, c->z + dz);
                row[o] = e->x == INT32_MIN ? -1 : e->id;
                if (row[o] >= 0) iv->cnb[e->id][26 - o] = c->id;
            }
}

static inline void cell_mark(banyan_ivy *iv, const ivy_cell *c) {
    uint32_t k = (uint32_t)(c - iv->cells);
    iv->cbits[k >> 6] |= (uint64_t)1 << (k & 63);
}

/* A table of `slots` (a power of 2) holding the cells of the old one. */
static int cells_resize(banyan_ivy *iv, uint32_t slots) {
    /* slots is at least 64: the bitmap of used slots follows the table */
    ivy_cell *t = malloc(sizeof(ivy_cell) * slots + sizeof(uint64_t) * (slots / 64)), *old = iv->cells;
    if (!t) return 0;
    for (uint32_t k = 0; k < slots; k++) t[k] = (ivy_cell){INT32_MIN, 0, 0, 0, 0, 0, 0};
    uint32_t old_slots = old ? iv->cmask + 1 : 0;
    iv->cells = t;
    iv->cbits = (uint64_t *)(void *)(t + slots);
    memset(iv->cbits, 0, sizeof(uint64_t) * (slots / 64));
    iv->cmask = slots - 1;
    for (uint32_t k = 0; k < old_slots; k++)
        if (old[k].x != INT32_MIN) {
            ivy_cell *c = cell_slot(iv, old[k].x, old[k].y, old[k].z);
            *c = old[k];
            cell_mark(iv, c);
            iv->cslot[c->id] = (uint32_t)(c - t);
        }
    free(old);
    return 1;
}

/* Cell (x, y, z) with room for one more bud; NULL when out of memory. */
static ivy_cell *cell_room(banyan_ivy *iv, int32_t x, int32_t y, int32_t z) {
    ivy_cell *c = cell_slot(iv, x, y, z);
    if (c->x == INT32_MIN) {
        /* A new cell: the table stays at most half full. */
        if ((uint32_t)(iv->n_cells + 1) * 2 > iv->cmask + 1) {
            if (iv->cmask >= (1u << 30) || !cells_resize(iv, 2 * (iv->cmask + 1))) return NULL;
            c = cell_slot(iv, x, y, z);
        }
        if (iv->n_cells == iv->cnb_cap) { /* rows and slots of cells by id */
            int32_t cap = iv->cnb_cap ? 2 * iv->cnb_cap : 256;
            int32_t(*r)[27] = iv->cnb_cap < (1 << 26) ? realloc(iv->cnb, sizeof *r * (size_t)cap) : NULL;
            if (!r) return NULL;
            iv->cnb = r;
            uint32_t *sl = realloc(iv->cslot, sizeof *sl * (size_t)cap);
            if (!sl) return NULL;
            iv->cslot = sl;
            iv->cnb_cap = cap;
        }
        *c = (ivy_cell){x, y, z, 0, 0, 0, iv->n_cells};
        cell_mark(iv, c);
        iv->cslot[iv->n_cells++] = (uint32_t)(c - iv->cells);
        cell_row(iv, c);
    }
    if (c->n == c->cap) {
        /* A run twice as long at the pool's end; the old run is left
         * (the runs a cell left behind are shorter than its own). */
        int32_t cap = c->cap ? 2 * c->cap : 8;
        if (iv->pool_n + cap > iv->pool_cap) {
            int64_t pc = iv->pool_cap ? 2 * iv->pool_cap : 4096;
            while (pc < iv->pool_n + cap) pc *= 2;
            if (pc > INT32_MAX) return NULL;
            ivy_gnode *g = realloc(iv->pool, sizeof(ivy_gnode) * (size_t)pc);
            if (!g) return NULL;
            iv->pool = g;
            iv->pool_cap = pc;
        }
        if (c->n) memcpy(iv->pool + iv->pool_n, iv->pool + c->at, sizeof(ivy_gnode) * (size_t)c->n);
        c->at = (int32_t)iv->pool_n;
        c->cap = cap;
        iv->pool_n += cap;
    }
    return c;
}

static void link_bud(banyan_ivy *iv, int32_t i) {
    const ivy_bud *b = &iv->buds[i];
    iv->grid_gen++;
    int32_t *bc = iv->bcell[i];
    bc[0] = cell_coord(b->P.x, iv->inv_cell);
    bc[1] = cell_coord(b->P.y, iv->inv_cell);
    bc[2] = cell_coord(b->P.z, iv->inv_cell);
    ivy_cell *c = cell_room(iv, bc[0], bc[1], bc[2]);
    if (!c) {
        iv->grid_oom = 1;
        bc[0] = INT32_MIN; /* in no cell */
        return;
    }
    iv->pool[c->at + c->n++] = (ivy_gnode){b->P, b->step_c | (b->follow > 0 ? IVY_GNODE_FOLLOW : 0), i};
}

static void unlink_bud(banyan_ivy *iv, int32_t i) {
    const int32_t *bc = iv->bcell[i];
    iv->grid_gen++;
    if (bc[0] == INT32_MIN) return;
    ivy_cell *c = cell_slot(iv, bc[0], bc[1], bc[2]);
    ivy_gnode *g = iv->pool + c->at;
    for (int32_t k = 0; k < c->n; k++)
        if (g[k].id == i) { /* the others keep their order */
            memmove(g + k, g + k + 1, sizeof(ivy_gnode) * (size_t)(c->n - k - 1));
            c->n--;
            break;
        }
}

banyan_status ivy_grid_init(banyan_ivy *iv, uint32_t buckets) {
    /* buckets is a power of 2, at least 64 */
    free(iv->cells);
    iv->cells = NULL;
    iv->n_cells = 0;
    iv->grid_gen++;
    iv->pool_n = 0;
    if (!cells_resize(iv, buckets)) return BANYAN_E_NOMEM;
    iv->vbuckets = buckets;
    for (int32_t i = 0; i < iv->n; i++) link_bud(iv, i);
    return iv->grid_oom ? BANYAN_E_NOMEM : BANYAN_OK;
}

static int cmp_gnode_id(const void *a, const void *b) {
    int32_t x = ((const ivy_gnode *)a)->id, y = ((const ivy_gnode *)b)->id;
    return (x > y) - (x < y);
}

void ivy_grid_insert(banyan_ivy *iv, int32_t i) {
    link_bud(iv, i);
    /* Where the bucket hash rehashed (at load 2), it relinked every bud
     * in index order: each cell's buds are read newest index first from
     * then on. */
    if ((uint32_t)iv->n > 2u * iv->vbuckets && iv->vbuckets - 1u < (1u << 26)) {
        iv->vbuckets *= 4;
        for (uint32_t k = 0; k <= iv->cmask; k++) {
            ivy_cell *c = &iv->cells[k];
            if (c->n > 1) qsort(iv->pool + c->at, (size_t)c->n, sizeof(ivy_gnode), cmp_gnode_id);
        }
    }
}

/* ------------------------------------------------ light cache upkeep */

/* Bud i and its descendants up to h1_buds generations (whose H1 reads
 * H0 at i) forget that they were too shaded, and wake up. */
static void forget(banyan_ivy *iv, int32_t i) {
    int32_t stack[2 * 64 + 2][2];
    int32_t top = 0;
    stack[top][0] = i;
    stack[top++][1] = 0;
    while (top > 0) {
        top--;
        int32_t j = stack[top][0], depth = stack[top][1];
        ivy_bud *b = &iv->buds[j];
        if (b->shaded && b->state != BANYAN_IVY_Z) iv->wake[iv->n_wake++] = j; /* it sleeps: wake it */
        b->shaded = 0;
        if (depth >= iv->p.h1_buds) continue;
        for (int k = 0; k < 2; k++) {
            int32_t c = iv->buds[j].child[k];
            if (c >= 0) {
                stack[top][0] = c;
                stack[top++][1] = depth + 1;
            }
        }
    }
}

/* Wakes the sleepers whose test counted bud i: it is moving. Its edges
 * are spent (a sleeper that falls asleep again leaves new ones). */
static void wake_counters(banyan_ivy *iv, int32_t i) {
    for (int32_t e = iv->dep_head[i]; e >= 0; e = iv->dep[e].next) {
        ivy_bud *s = &iv->buds[iv->dep[e].sleeper];
        if (s->shaded != iv->dep[e].serial) continue; /* woken since */
        s->shaded = 0;
        if (s->state != BANYAN_IVY_Z) iv->wake[iv->n_wake++] = iv->dep[e].sleeper;
    }
    iv->dep_head[i] = -1;
}

void ivy_grid_move_many(banyan_ivy *iv, const int32_t *set, const v3 *q, int32_t n) {
    /* Shade falls only where a bud was: for the buds whose test counted
     * it, and at its new place for itself and the buds whose H1 reads it. */
    for (int32_t k = 0; k < n; k++) {
        int32_t i = set[k];
        ivy_bud *b = &iv->buds[i];
        v3 o = b->P, p = q[k];
        if (p.x == o.x && p.y == o.y && p.z == o.z) continue;
        wake_counters(iv, i);
        unlink_bud(iv, i);
        b->P = p;
        link_bud(iv, i);
        forget(iv, i);
    }
}

/* Moves the live edges (sleepers not woken since) into a new pool of
 * `cap`; returns 0 when that cannot allocate (the old pool stays). */
static int collect_deps(banyan_ivy *iv, int32_t cap) {
    ivy_dep *d = malloc(sizeof(ivy_dep) * (size_t)cap);
    if (!d) return 0;
    int32_t m = 0;
    for (int32_t j = 0; j < iv->n; j++) {
        int32_t *at = &iv->dep_head[j];
        for (int32_t e = *at; e >= 0; e = iv->dep[e].next) {
            const ivy_dep *x = &iv->dep[e];
            if (iv->buds[x->sleeper].shaded != x->serial) continue;
            d[m] = *x;
            *at = m;
            at = &d[m++].next;
        }
        *at = -1;
    }
    free(iv->dep);
    iv->dep = d;
    iv->n_dep = m;
    iv->dep_cap = cap;
    return 1;
}

void ivy_test_begin(banyan_ivy *iv) {
    iv->n_counted = 0;
    if (iv->test_id == INT32_MAX) { /* the stamps start over */
        memset(iv->seen, 0, sizeof(int32_t) * (size_t)iv->cap);
        iv->test_id = 0;
    }
    iv->test_id++;
}

void ivy_sleep(banyan_ivy *iv, int32_t i) {
    if (iv->n_counted > iv->dep_cap - iv->n_dep) {
        /* Full: keep the live edges, in a pool at least twice their number
         * (so collections stay rare). When memory runs out the bud stays
         * awake: tested every step, only slower. */
        int64_t cap = iv->dep_cap > 4096 ? iv->dep_cap : 4096;
        if (iv->dep_cap && !collect_deps(iv, iv->dep_cap)) return;
        while (cap - iv->n_dep < iv->n_counted || cap < 2 * (int64_t)iv->n_dep) cap *= 2;
        if (cap > INT32_MAX) return;
        if (cap != iv->dep_cap) {
            ivy_dep *d = realloc(iv->dep, sizeof(ivy_dep) * (size_t)cap);
            if (!d) return;
            iv->dep = d;
            iv->dep_cap = (int32_t)cap;
        }
    }
    /* Never 0 (awake); a serial seen again after wrapping only wakes a
     * bud needlessly. */
    if (++iv->sleep_serial == INT32_MAX) iv->sleep_serial = 1;
    const int32_t serial = iv->sleep_serial;
    for (int32_t k = 0; k < iv->n_counted; k++) {
        int32_t j = iv->counted[k], e = iv->n_dep++;
        iv->dep[e].sleeper = i;
        iv->dep[e].serial = serial;
        iv->dep[e].next = iv->dep_head[j];
        iv->dep_head[j] = e;
    }
    iv->buds[i].shaded = serial;
}

double ivy_leaf_diameter(const banyan_ivy *iv, const ivy_bud *b) {
    double age = (double)(iv->step - b->step_c) + 1.0;
    double f = age / iv->p.leaf_growth_steps;
    return iv->p.leaf_max * (f < 1.0 ? f : 1.0);
}

double ivy_stem_radius(const banyan_ivy *iv, const ivy_bud *b) {
    double r = iv->p.stem_radius + iv->p.stem_radius_growth * (double)(iv->step - b->step_c);
    return r < iv->p.stem_radius_max ? r : iv->p.stem_radius_max;
}

static inline double shade(const banyan_ivy *iv, v3 p, int32_t self, double stop, v3 *vl, banyan_ivy *gather) {
    const double dmax = iv->p.leaf_max, dmax2 = dmax * dmax, inv_dmax = 1.0 / dmax;
    const double grow = iv->p.leaf_max / iv->p.leaf_growth_steps;
    const double ic = iv->inv_cell;
    int32_t x0 = cell_coord(p.x - dmax, ic), x1 = cell_coord(p.x + dmax, ic), y0 = cell_coord(p.y - dmax, ic),
            y1 = cell_coord(p.y + dmax, ic), z0 = cell_coord(p.z - dmax, ic), z1 = cell_coord(p.z + dmax, ic);
    /* The cells around p in z, y, x order, each cell's buds newest link
     * first (the order the sums have always been added in). */
    double H = 0.0;
    v3 acc = v3_make(0, 0, 0);
    const ivy_cell *cl_own[64], **cl = cl_own;
    if (gather && vl) { /* kept for gather_stems at this point */
        cl = gather->lc;
        gather->lc_valid = 1;
        gather->lc_p = p;
        gather->lc_gen = iv->grid_gen;
        int32_t *bx = gather->lc_box;
        bx[0] = x0, bx[1] = x1 <= x0 + 3 ? x1 : x0 + 3;
        bx[2] = y0, bx[3] = y1 <= y0 + 3 ? y1 : y0 + 3;
        bx[4] = z0, bx[5] = z1 <= z0 + 3 ? z1 : z0 + 3;
    }
    /* Around a bud's own cell (the usual case): its row of neighbours. */
    const int32_t *bc = self >= 0 && self < iv->n ? iv->bcell[self] : NULL;
    const int ncl = bc && bc[0] != INT32_MIN && x0 == bc[0] - 1 && x1 == bc[0] + 1 && y0 == bc[1] - 1 &&
                            y1 == bc[1] + 1 && z0 == bc[2] - 1 && z1 == bc[2] + 1
                        ? cells_near(iv, bc[0], bc[1], bc[2], cl)
                        : cells_around(iv, x0, x1, y0, y1, z0, z1, cl);
    if (cl != cl_own) gather->n_lc = ncl;
    for (int q = 0; q < ncl; q++) {
        const ivy_cell *c = cl[q];
        const ivy_gnode *g = iv->pool + c->at;
        for (int32_t k = c->n - 1; k >= 0; k--) {
            const ivy_gnode *b = &g[k];
            const int32_t j = b->id;
            v3 d = v3_sub(p, b->P);
            double d2 = v3_len2(d);
            if (d2 >= dmax2 || j == self) continue;
            double dist = sqrt(d2);
            double dl = grow * ((double)(iv->step - (b->step_c & ~IVY_GNODE_FOLLOW)) + 1.0);
            if (dl > dmax) dl = dmax;
            double h = dist < dl ? 1.0 : 1.0 - (dist - dl) * inv_dmax;
            if (h <= 0) continue;
            if (b->step_c & IVY_GNODE_FOLLOW) h *= IVY_FOLLOW_LEAF;
            H += h;
            if (gather && gather->seen[j] != gather->test_id) {
                gather->seen[j] = gather->test_id;
                gather->counted[gather->n_counted++] = j;
            }
            if (H > stop) return H; /* the caller will not grow: V_l unused */
            if (vl && dist > 1e-12) acc = v3_madd(acc, d, h / dist);
        }
    }
    if (vl) *vl = v3_add(*vl, acc);
    return H;
}

double ivy_shade(const banyan_ivy *iv, v3 p, int32_t self, double stop, v3 *vl) {
    return shade(iv, p, self, stop, vl, NULL);
}

double ivy_shade_watch(banyan_ivy *iv, v3 p, int32_t self, double stop, v3 *vl) {
    return shade(iv, p, self, stop, vl, iv);
}

/* Does the internode a-b cross a stem, seen along n? Only internodes
 * parent(j) -> j whose end bud j lies within `layer` of a across n (the
 * same surface's stems) count, and none that shares bud `self` (the bud
 * a-b grows from). An internode of length l that crosses a-b ends within
 * 1.5 l of its midpoint, so the cells around that ball are read. */
/* The crossing test of ivy_crosses; with `all`, every stem is tested and
 * the one crossed nearest a wins (ties within 1e-9 of a-b's length: the
 * lower bud), so the answer hangs neither on the order cells are read in
 * nor on rounding; else the first found. */
static inline int32_t crossed(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer, int all) {
    const double l = iv->p.internode, r = 1.5 * l, r2 = r * r, ic = iv->inv_cell;
    const v3 m = v3_scale(v3_add(a, b), 0.5);
    /* 2D frame of the surface: u, w across n. */
    const v3 u = v3_any_perp(n), w = v3_cross(n, u);
    const double ax = v3_dot(a, u), ay = v3_dot(a, w), bx = v3_dot(b, u), by = v3_dot(b, w);
    const double ex = bx - ax, ey = by - ay;
    int32_t x0 = cell_coord(m.x - r, ic), x1 = cell_coord(m.x + r, ic), y0 = cell_coord(m.y - r, ic),
            y1 = cell_coord(m.y + r, ic), z0 = cell_coord(m.z - r, ic), z1 = cell_coord(m.z + r, ic);
    const ivy_cell *cells[64];
    const int ncl = cells_around(iv, x0, x1, y0, y1, z0, z1, cells);
    int32_t best = -1;
    double best_t = HUGE_VAL;
    for (int q = 0; q < ncl; q++) {
        const ivy_cell *cl = cells[q];
        for (int32_t k = 0; k < cl->n; k++) {
            const ivy_gnode *g = &iv->pool[cl->at + k];
            const int32_t j = g->id;
            /* The bud's own copy first: most are out of reach, and
             * the bud array is read only for the rest. */
            if (v3_len2(v3_sub(g->P, m)) >= r2 || fabs(v3_dot(v3_sub(g->P, a), n)) > layer) continue;
            const int32_t pj = iv->buds[j].parent;
            if (pj < 0 || j == self || pj == self) continue;
            v3 c = iv->buds[pj].P;
            const double cx = v3_dot(c, u), cy = v3_dot(c, w), dx = v3_dot(g->P, u) - cx,
                         dy = v3_dot(g->P, w) - cy;
            /* Proper intersection: each segment's ends on opposite sides of the other. */
            double s1 = ex * (cy - ay) - ey * (cx - ax), s2 = ex * (cy + dy - ay) - ey * (cx + dx - ax);
            if ((s1 > 0) == (s2 > 0) || s1 == 0 || s2 == 0) continue;
            double s3 = dx * (ay - cy) - dy * (ax - cx), s4 = dx * (by - cy) - dy * (bx - cx);
            if (!((s3 > 0) != (s4 > 0) && s3 != 0 && s4 != 0)) continue;
            if (!all) return j;
            /* Where along a-b; two stems crossed at one point (a joint)
             * within rounding count as a tie. */
            const double t = s3 / (s3 - s4);
            if (t < best_t - 1e-9 || (!(t > best_t + 1e-9) && j < best)) best_t = t < best_t ? t : best_t, best = j;
        }
    }
    return best;
}

int ivy_crosses(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer) {
    return crossed(iv, a, b, n, self, layer, 0) >= 0;
}

int32_t ivy_crossed_stem(const banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer) {
    return crossed(iv, a, b, n, self, layer, 1);
}

/* The cells ivy_crosses reads for internode a-b: x0..x1, y0..y1, z0..z1,
 * at most 4 a side (as cells_around clips them). */
static void crossing_cells(const banyan_ivy *iv, v3 a, v3 b, int32_t box[6]) {
    const double r = 1.5 * iv->p.internode, ic = iv->inv_cell;
    const v3 m = v3_scale(v3_add(a, b), 0.5);
    const double lo[3] = {m.x - r, m.y - r, m.z - r}, hi[3] = {m.x + r, m.y + r, m.z + r};
    for (int k = 0; k < 3; k++) {
        box[2 * k] = cell_coord(lo[k], ic);
        int32_t e = cell_coord(hi[k], ic);
        box[2 * k + 1] = e <= box[2 * k] + 3 ? e : box[2 * k] + 3;
    }
}

/* Gathers the stems ivy_crosses could count for an internode from a: end
 * bud copies within 2 l of a (an internode's midpoint is l / 2 from a,
 * the query reaches 1.5 l from it; the margin covers rounding), within
 * `layer` across n, not sharing bud self. Each keeps the values
 * ivy_crosses finds for it, computed the same way. */
static void gather_stems(banyan_ivy *iv, v3 a, v3 n, int32_t self, double layer) {
    const double l = iv->p.internode, R = 2.0 * l * (1.0 + 1e-6) + 1e-9, R2 = R * R, ic = iv->inv_cell;
    iv->xs_valid = 1;
    iv->xs_ok = 0;
    iv->n_xs = 0;
    iv->xs_a = a;
    iv->xs_n = n;
    iv->xs_self = self;
    iv->xs_layer = layer;
    iv->xs_gen = iv->grid_gen;
    const v3 u = v3_any_perp(n), w = v3_cross(n, u);
    iv->xs_u = u;
    iv->xs_w = w;
    int32_t *bx = iv->xs_box;
    const double lo[3] = {a.x - R, a.y - R, a.z - R}, hi[3] = {a.x + R, a.y + R, a.z + R};
    for (int k = 0; k < 3; k++) {
        bx[2 * k] = cell_coord(lo[k], ic);
        bx[2 * k + 1] = cell_coord(hi[k], ic);
        if (bx[2 * k + 1] - bx[2 * k] > 3) return; /* cells_around would clip: not usable */
    }
    const ivy_cell *own[64], *const *cells = own;
    int ncl;
    const int32_t *lb = iv->lc_box;
    if (iv->lc_valid && iv->lc_gen == iv->grid_gen && iv->lc_p.x == a.x && iv->lc_p.y == a.y && iv->lc_p.z == a.z &&
        bx[0] >= lb[0] && bx[1] <= lb[1] && bx[2] >= lb[2] && bx[3] <= lb[3] && bx[4] >= lb[4] && bx[5] <= lb[5]) {
        cells = iv->lc; /* the light test's cells hold these (and a few more: the queries check cells) */
        ncl = iv->n_lc;
    } else {
        ncl = cells_around(iv, bx[0], bx[1], bx[2], bx[3], bx[4], bx[5], own);
    }
    for (int q = 0; q < ncl; q++) {
        const ivy_cell *cl = cells[q];
        for (int32_t k = 0; k < cl->n; k++) {
            const ivy_gnode *g = &iv->pool[cl->at + k];
            const int32_t j = g->id;
            if (v3_len2(v3_sub(g->P, a)) >= R2 || fabs(v3_dot(v3_sub(g->P, a), n)) > layer) continue;
            const int32_t pj = iv->buds[j].parent;
            if (pj < 0 || j == self || pj == self) continue;
            if (iv->n_xs == iv->xs_cap) {
                int32_t cap = iv->xs_cap ? 2 * iv->xs_cap : 64;
                ivy_xstem *x = realloc(iv->xs, sizeof(ivy_xstem) * (size_t)cap);
                if (!x) return; /* not usable: the queries go the long way */
                iv->xs = x;
                iv->xs_cap = cap;
            }
            ivy_xstem *e = &iv->xs[iv->n_xs++];
            v3 c = iv->buds[pj].P;
            e->P = g->P;
            e->cell[0] = cl->x;
            e->cell[1] = cl->y;
            e->cell[2] = cl->z;
            e->cx = v3_dot(c, u);
            e->cy = v3_dot(c, w);
            e->dx = v3_dot(g->P, u) - e->cx;
            e->dy = v3_dot(g->P, w) - e->cy;
        }
    }
    iv->xs_ok = 1;
}

int ivy_crosses_near(banyan_ivy *iv, v3 a, v3 b, v3 n, int32_t self, double layer) {
    if (!iv->xs_valid || iv->xs_gen != iv->grid_gen || iv->xs_self != self || iv->xs_layer != layer ||
        iv->xs_a.x != a.x || iv->xs_a.y != a.y || iv->xs_a.z != a.z || iv->xs_n.x != n.x || iv->xs_n.y != n.y ||
        iv->xs_n.z != n.z)
        gather_stems(iv, a, n, self, layer);
    int32_t box[6];
    crossing_cells(iv, a, b, box);
    const int32_t *g = iv->xs_box;
    /* The same copies as ivy_crosses reads (the cells it reads, within
     * those gathered), by the same tests. */
    if (!iv->xs_ok || box[0] < g[0] || box[1] > g[1] || box[2] < g[2] || box[3] > g[3] || box[4] < g[4] ||
        box[5] > g[5])
        return ivy_crosses(iv, a, b, n, self, layer);
    const double r = 1.5 * iv->p.internode, r2 = r * r;
    const v3 m = v3_scale(v3_add(a, b), 0.5), u = iv->xs_u, w = iv->xs_w;
    const double ax = v3_dot(a, u), ay = v3_dot(a, w), bx = v3_dot(b, u), by = v3_dot(b, w);
    const double ex = bx - ax, ey = by - ay;
    for (int32_t k = 0; k < iv->n_xs; k++) {
        const ivy_xstem *e = &iv->xs[k];
        if (v3_len2(v3_sub(e->P, m)) >= r2 || e->cell[0] < box[0] || e->cell[0] > box[1] || e->cell[1] < box[2] ||
            e->cell[1] > box[3] || e->cell[2] < box[4] || e->cell[2] > box[5])
            continue;
        const double cx = e->cx, cy = e->cy, dx = e->dx, dy = e->dy;
        double s1 = ex * (cy - ay) - ey * (cx - ax), s2 = ex * (cy + dy - ay) - ey * (cx + dx - ax);
        if ((s1 > 0) == (s2 > 0) || s1 == 0 || s2 == 0) continue;
        double s3 = dx * (ay - cy) - dy * (ax - cx), s4 = dx * (by - cy) - dy * (bx - cx);
        if ((s3 > 0) != (s4 > 0) && s3 != 0 && s4 != 0) return 1;
    }
    return 0;
}

/* Segment CPU reference (spec segments.md, "Steps"): no input, random or
 * adversarial, ever yields more than 128 vertices or writes past the
 * caller's arrays; bad inputs are refused with the field named; vertex
 * counts follow the closed form 2 + 2n + sum 4(2^(s+i-1) - 1) wherever it
 * is <= 128 and stop at the last fork that fits otherwise; the geometry
 * follows the spec's formulas (checked in double against the float
 * output); and the forks come in the spec's breadth-first order, checked
 * against an independent enumeration "level by level, twig order, then
 * parent order". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "banyan.h"
#include "check.h"
#include "base/rng.h"
#include "base/vec.h"

#define MAXV BANYAN_SEGMENT_MAX_VERTICES
#define GUARD 64
#define SENTINEL 12345.678f

/* Uncapped vertex count from the closed form, in double (exact here). */
static double closed_form(int n, int s) {
    double v = 2 + 2.0 * n;
    for (int i = 1; i <= n; i++) v += 4 * (ldexp(1.0, s + i - 1) - 1);
    return v;
}

static v3 vtx(const float *xyz, int i) { return v3_make(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]); }

static double rel_dist(v3 a, v3 b, double scale) { return v3_dist(a, b) / (scale > 1e-30 ? scale : 1e-30); }

/* Random valid input. */
static void random_input(pcg32 *r, banyan_segment_input *in) {
    for (int c = 0; c < 3; c++) in->S[c] = rng_range(r, -50, 50);
    double z = rng_range(r, -1, 1), a = rng_range(r, 0, 2 * BANYAN_PI), q = sqrt(1 - z * z);
    double len = pow(10, rng_range(r, -2, 2));
    in->A[0] = q * cos(a) * len;
    in->A[1] = q * sin(a) * len;
    in->A[2] = z * len;
    in->l = rng_range(r, 0, 40);
    in->n = (int32_t)rng_below(r, 64);
    in->s = (int32_t)rng_below(r, 11);
    if (rng_below(r, 2)) {
        in->n = (int32_t)rng_below(r, 8);
        in->s = (int32_t)rng_below(r, 4);
    }
}

/* Runs one input with guard zones after both arrays; returns the status
 * and checks the invariants every accepted output must keep. */
static int bad_guard, bad_bound, bad_finite, bad_zero_on_fail;
static banyan_status run_guarded(const banyan_segment_input *in, const banyan_segment_params *p, float *xyz,
                                 uint8_t *lev, int32_t *count) {
    for (int i = 0; i < 3 * (MAXV + GUARD); i++) xyz[i] = SENTINEL;
    memset(lev, 0xAB, MAXV + GUARD);
    *count = -7;
    banyan_status s = banyan_segment_lines(in, p, xyz, lev, count, NULL);
    for (int i = 3 * MAXV; i < 3 * (MAXV + GUARD); i++)
        if (xyz[i] != SENTINEL) { bad_guard++; break; }
    for (int i = MAXV; i < MAXV + GUARD; i++)
        if (lev[i] != 0xAB) { bad_guard++; break; }
    if (s != BANYAN_OK) {
        if (*count != 0) bad_zero_on_fail++;
        return s;
    }
    if (*count < 2 || *count > MAXV || *count % 2) bad_bound++;
    for (int i = 0; i < 3 * *count && *count <= MAXV; i++)
        if (!isfinite(xyz[i])) { bad_finite++; break; }
    return s;
}

/* Spec step 3 in double: the two children of a parent direction L. */
static void children(v3 L, const banyan_segment_params *p, v3 *J1, v3 *J2) {
    *J1 = v3_rotate(v3_rotate_z(L, deg2rad(p->beta_deg)), L, deg2rad(p->gamma_deg));
    *J2 = v3_rotate(v3_rotate_z(L, -deg2rad(p->beta_deg)), L, deg2rad(p->omega_deg));
}

typedef struct node { int twig, depth, index; } node;

/* Checks geometry and order of one accepted segment; returns failures. */
static int check_structure(const banyan_segment_input *in, const banyan_segment_params *p, const float *xyz,
                           const uint8_t *lev, int count, char *why, size_t why_len) {
    int n = in->n, s = in->s, lines = count / 2;
    double m = p->m;
    v3 S = v3_make((float)in->S[0], (float)in->S[1], (float)in->S[2]);
    v3 A = v3_norm(v3_make((float)in->A[0], (float)in->A[1], (float)in->A[2]));
    double l = (float)in->l;
    double scale = fmax(fmax(v3_len(S), l), m) + m * 8;
    const double tol = 2e-5;
    /* 1. Axis. */
    if (lev[0] != 0 || lev[1] != 0) return snprintf(why, why_len, "axis level %d", lev[0]), 1;
    if (rel_dist(vtx(xyz, 0), S, scale) > tol || rel_dist(vtx(xyz, 1), v3_madd(S, A, l), scale) > tol)
        return snprintf(why, why_len, "axis end points"), 1;
    if (lines < 1 + n) return snprintf(why, why_len, "%d lines for %d twigs", lines, n), 1;
    /* 2. Twigs. */
    v3 *dir = malloc(sizeof(v3) * lines);
    node *nd = malloc(sizeof(node) * lines);
    int fails = 0;
    for (int i = 1; i <= n && !fails; i++) {
        v3 D = v3_madd(S, A, l * i / (n + 1));
        v3 F = v3_rotate_z(A, deg2rad(i % 2 ? p->alpha_deg : -p->alpha_deg));
        if (lev[2 * i] != 1 || lev[2 * i + 1] != 1) fails = snprintf(why, why_len, "twig %d level %d", i, lev[2 * i]);
        else if (rel_dist(vtx(xyz, 2 * i), D, scale) > tol || rel_dist(vtx(xyz, 2 * i + 1), v3_madd(D, F, m), scale) > tol)
            fails = snprintf(why, why_len, "twig %d end points", i);
        dir[i] = F;
        nd[i] = (node){i, 0, 0};
    }
    /* 3. Forks: pairs of lines after the twigs. Find each pair's parent
     * among earlier lines (G1 at 0.3, G2 at 0.7 of it), check the children,
     * and record which node of the binary tree below its twig it is. */
    int forks = (lines - 1 - n) / 2;
    if ((lines - 1 - n) % 2) fails = snprintf(why, why_len, "odd fork line count");
    int prev_parent = 0;
    node *order = malloc(sizeof(node) * (forks + 1));
    for (int f = 0; f < forks && !fails; f++) {
        int c1 = 1 + n + 2 * f, c2 = c1 + 1, parent = -1;
        v3 G1 = vtx(xyz, 2 * c1), G2 = vtx(xyz, 2 * c2);
        /* Breadth-first: parents come in list order, so look after the
         * previous parent (this also keeps coincident twigs apart). */
        for (int q = prev_parent + 1; q < c1 && parent < 0; q++) {
            v3 I1 = vtx(xyz, 2 * q), I2 = vtx(xyz, 2 * q + 1);
            if (rel_dist(G1, v3_lerp(I1, I2, 0.3), scale) < tol && rel_dist(G2, v3_lerp(I1, I2, 0.7), scale) < tol &&
                lev[2 * q] + 1 == lev[2 * c1])
                parent = q;
        }
        if (parent < 0) { fails = snprintf(why, why_len, "fork %d has no parent", f); break; }
        prev_parent = parent;
        v3 J1, J2;
        children(dir[parent], p, &J1, &J2);
        if (rel_dist(vtx(xyz, 2 * c1 + 1), v3_madd(G1, J1, m), scale) > tol ||
            rel_dist(vtx(xyz, 2 * c2 + 1), v3_madd(G2, J2, m), scale) > tol) {
            fails = snprintf(why, why_len, "fork %d children directions", f);
            break;
        }
        if (lev[2 * c1] != lev[2 * c2] || lev[2 * c1] != lev[2 * c1 + 1] || lev[2 * c2] != lev[2 * c2 + 1])
            fails = snprintf(why, why_len, "fork %d levels", f);
        dir[c1] = J1;
        dir[c2] = J2;
        node pn = nd[parent];
        nd[c1] = (node){pn.twig, pn.depth + 1, 2 * pn.index};
        nd[c2] = (node){pn.twig, pn.depth + 1, 2 * pn.index + 1};
        if (lev[2 * c1] != 1 + pn.depth + 1) fails = snprintf(why, why_len, "fork %d level vs depth", f);
        order[f] = (node){pn.twig, pn.depth + 1, pn.index};
    }
    /* The spec's order, enumerated literally: level d = 1, 2, ...; twigs
     * reaching d in order; parents of level d - 1 in order. The reference's
     * forks must be exactly its first `forks` entries, and stop only when
     * the next fork would pass 128 vertices. */
    int e = 0, done = 0;
    for (int d = 1; !fails && !done; d++) {
        int any = 0;
        for (int i = 1; i <= n && !fails; i++) {
            if (s + i - 1 < d) continue;
            any = 1;
            for (int k = 0; k < (1 << (d - 1)); k++) {
                if (e < forks) {
                    if (order[e].twig != i || order[e].depth != d || order[e].index != k)
                        fails = snprintf(why, why_len, "fork %d is (twig %d, level %d, #%d), the spec's order has "
                                         "(twig %d, level %d, #%d)", e, order[e].twig, order[e].depth, order[e].index,
                                         i, d, k);
                    e++;
                } else {
                    /* First fork not made: it must not have fitted. */
                    if (count + 4 <= MAXV) fails = snprintf(why, why_len, "stopped at %d vertices with room", count);
                    done = 1;
                    break;
                }
            }
            if (done) break;
        }
        if (!any) done = 1;
    }
    if (!fails && e != forks) fails = snprintf(why, why_len, "%d forks, the spec enumerates %d", forks, e);
    free(order);
    free(dir);
    free(nd);
    return fails ? 1 : 0;
}

int main(void) {
    banyan_segment_params p;
    banyan_segment_params_init(&p);
    CHECK(p.alpha_deg == 40 && p.beta_deg == 30 && p.gamma_deg == -30 && p.omega_deg == 10 && p.m == 10,
          "paper defaults");
    float xyz[3 * (MAXV + GUARD)];
    uint8_t lev[MAXV + GUARD];
    int32_t count;
    banyan_error err;
    pcg32 r;
    pcg32_seed(&r, 6, 0);

    /* --- Budget: random and adversarial inputs never pass 128. */
    int accepted = 0, refused = 0, at_budget = 0;
    for (int t = 0; t < 40000; t++) {
        banyan_segment_input in;
        random_input(&r, &in);
        switch (rng_below(&r, 12)) {
        case 0: in.n = (int32_t)rng_below(&r, 64); in.s = (int32_t)rng_below(&r, 65); break;
        case 1: in.l = 0; break;
        case 2: in.l = rng_below(&r, 2) ? 1e12 : 1e30; break; /* huge: accepted or refused */
        case 3: in.A[0] = in.A[1] = 0; break;                  /* vertical (or zero if A[2] is tiny) */
        case 4: in.A[0] = in.A[1] = in.A[2] = pow(10, rng_range(&r, -320, -5)); break; /* tiny / denormal */
        case 5: in.A[rng_below(&r, 3)] = pow(10, rng_range(&r, 5, 300)); break;      /* huge */
        case 6: in.S[rng_below(&r, 3)] = pow(10, rng_range(&r, 5, 14)); break;
        case 7: in.n = 63; break;
        case 8: in.A[rng_below(&r, 3)] = rng_below(&r, 2) ? NAN : INFINITY; break;
        case 9: in.n = (int32_t)rng_below(&r, 200) - 50; in.s = (int32_t)rng_below(&r, 200) - 50; break;
        case 10: in.A[0] = 1e-12; in.A[1] = in.A[2] = 0; break;
        default: break;
        }
        banyan_status s = run_guarded(&in, &p, xyz, lev, &count);
        if (s == BANYAN_OK) {
            accepted++;
            at_budget += count + 4 > MAXV && closed_form(in.n, in.s) > MAXV;
        } else refused++;
    }
    CHECK(bad_guard == 0, "%d runs wrote past the 128-vertex arrays", bad_guard);
    CHECK(bad_bound == 0, "%d runs returned a count outside 2..128 or odd", bad_bound);
    CHECK(bad_finite == 0, "%d accepted runs produced a non-finite coordinate", bad_finite);
    CHECK(bad_zero_on_fail == 0, "%d refused runs left *out_count != 0", bad_zero_on_fail);
    CHECK(accepted > 20000 && refused > 1000 && at_budget > 2000, "coverage: %d accepted, %d refused, %d at the budget",
          accepted, refused, at_budget);

    /* --- Bad inputs are refused with the field named. */
    banyan_segment_input ok = {{1, 2, 3}, {0, 1, 0}, 5, 4, 2};
    CHECK(banyan_segment_lines(&ok, &p, xyz, lev, &count, &err) == BANYAN_OK && count > 0, "valid input: %s",
          err.message);
    struct { const char *field; banyan_segment_input in; } bad[] = {
        {"n = 64", {{0, 0, 0}, {1, 0, 0}, 1, 64, 0}},
        {"n = -1", {{0, 0, 0}, {1, 0, 0}, 1, -1, 0}},
        {"s = -1", {{0, 0, 0}, {1, 0, 0}, 1, 3, -1}},
        {"s = 65", {{0, 0, 0}, {1, 0, 0}, 1, 3, 65}},
        {"S[1] = nan", {{0, NAN, 0}, {1, 0, 0}, 1, 3, 1}},
        {"S[0] = inf", {{INFINITY, 0, 0}, {1, 0, 0}, 1, 3, 1}},
        {"A[2] = nan", {{0, 0, 0}, {1, 0, NAN}, 1, 3, 1}},
        {"A = (0, 0, 0)", {{0, 0, 0}, {0, 0, 0}, 1, 3, 1}},
        {"A = (1e-13", {{0, 0, 0}, {1e-13, 0, 0}, 1, 3, 1}},
        {"A = (1e+300", {{0, 0, 0}, {1e300, 1e300, 0}, 1, 3, 1}},
        {"l = nan", {{0, 0, 0}, {1, 0, 0}, NAN, 3, 1}},
        {"l = -1", {{0, 0, 0}, {1, 0, 0}, -1, 3, 1}},
        {"l = 1e+30", {{0, 0, 0}, {1, 0, 0}, 1e30, 3, 1}},
        {"S[2] = 1e+13", {{0, 0, 1e13}, {1, 0, 0}, 1, 3, 1}},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        count = 99;
        banyan_status s = banyan_segment_lines(&bad[i].in, &p, xyz, lev, &count, &err);
        CHECK(s == BANYAN_E_RANGE && count == 0 && strstr(err.message, bad[i].field), "%s: status %d, message '%s'",
              bad[i].field, s, err.message);
        CHECK(banyan_segment_check(&bad[i].in, &p, &err) == BANYAN_E_RANGE, "check accepts %s", bad[i].field);
    }
    banyan_segment_params bp = p;
    bp.alpha_deg = NAN;
    CHECK(banyan_segment_lines(&ok, &bp, xyz, lev, &count, &err) == BANYAN_E_RANGE && strstr(err.message, "alpha_deg"),
          "alpha NaN: %s", err.message);
    bp = p;
    bp.m = 0;
    CHECK(banyan_segment_lines(&ok, &bp, xyz, lev, &count, &err) == BANYAN_E_RANGE && strstr(err.message, "m = 0"),
          "m 0: %s", err.message);
    bp = p;
    bp.omega_deg = 400;
    CHECK(banyan_segment_lines(&ok, &bp, xyz, lev, &count, &err) == BANYAN_E_RANGE && strstr(err.message, "omega_deg"),
          "omega 400: %s", err.message);
    CHECK(banyan_segment_lines(NULL, &p, xyz, lev, &count, &err) == BANYAN_E_INVALID_ARG, "NULL input accepted");
    CHECK(banyan_segment_lines(&ok, NULL, xyz, lev, &count, &err) == BANYAN_E_INVALID_ARG, "NULL params accepted");
    CHECK(banyan_segment_lines(&ok, &p, NULL, lev, &count, &err) == BANYAN_E_INVALID_ARG, "NULL xyz accepted");
    CHECK(banyan_segment_lines(&ok, &p, xyz, lev, NULL, &err) == BANYAN_E_INVALID_ARG, "NULL count accepted");
    CHECK(banyan_segment_lines(&ok, &p, xyz, NULL, &count, &err) == BANYAN_OK, "out_level may be NULL");

    /* --- Closed form for every n and s, and vertex_count agrees. */
    int bad_closed = 0, bad_cut = 0, bad_vc = 0, cases_fit = 0;
    for (int n = 0; n <= 63; n++)
        for (int s = 0; s <= 64; s++) {
            banyan_segment_input in = {{0, 0, 0}, {1, 1, 0}, 3, n, s};
            if (banyan_segment_lines(&in, &p, xyz, lev, &count, NULL)) { bad_closed++; continue; }
            double want = closed_form(n, s);
            if (want <= MAXV) {
                cases_fit++;
                if (count != (int)want) {
                    if (bad_closed++ < 5) fprintf(stderr, "n %d s %d: %d vertices, closed form %g\n", n, s, count, want);
                }
            } else if (count != MAXV - (MAXV - 2 - 2 * n) % 4) {
                /* Cut by the budget: every fork that fits is made. */
                if (bad_cut++ < 5) fprintf(stderr, "n %d s %d: %d vertices at the budget\n", n, s, count);
            }
            if (banyan_segment_vertex_count(n, s) != count) bad_vc++;
        }
    CHECK(bad_closed == 0, "%d (n, s) disagree with the closed form", bad_closed);
    CHECK(bad_cut == 0, "%d budget-cut (n, s) stop early or late", bad_cut);
    CHECK(bad_vc == 0, "%d banyan_segment_vertex_count mismatches", bad_vc);
    CHECK(cases_fit > 60, "only %d cases within the budget", cases_fit);
    CHECK(banyan_segment_vertex_count(64, 0) == -1 && banyan_segment_vertex_count(0, -1) == -1, "out of range counts");
    CHECK(banyan_segment_vertex_count(1, 5) == 128 && banyan_segment_vertex_count(1, 6) == 128 && banyan_segment_vertex_count(2, 4) == 126 &&
              banyan_segment_vertex_count(63, 0) == 128 && banyan_segment_vertex_count(0, 9) == 2,
          "known counts");

    /* --- Geometry and order against the spec, paper and random params. */
    int bad_struct = 0, structs = 0;
    for (int t = 0; t < 3000; t++) {
        banyan_segment_params q = p;
        if (t % 3) {
            q.alpha_deg = rng_range(&r, -90, 90);
            q.beta_deg = rng_range(&r, -90, 90);
            q.gamma_deg = rng_range(&r, -180, 180);
            q.omega_deg = rng_range(&r, -180, 180);
            q.m = pow(10, rng_range(&r, -1, 1.5));
        }
        banyan_segment_input in;
        random_input(&r, &in);
        if (banyan_segment_lines(&in, &q, xyz, lev, &count, &err)) { bad_struct++; continue; }
        char why[200] = "";
        structs++;
        if (check_structure(&in, &q, xyz, lev, count, why, sizeof why)) {
            if (bad_struct++ < 5)
                fprintf(stderr, "segment n %d s %d l %g: %s\n", in.n, in.s, in.l, why);
        }
    }
    CHECK(bad_struct == 0, "%d of %d segments break the spec's geometry or order", bad_struct, structs);

    /* --- Determinism and generate_many == single calls. */
    enum { MANY = 300 };
    banyan_segment_input many[MANY];
    for (int i = 0; i < MANY; i++) random_input(&r, &many[i]);
    float *mx = malloc(sizeof(float) * 3 * MAXV * MANY);
    uint8_t *ml = malloc((size_t)MAXV * MANY);
    int32_t mc[MANY];
    CHECK(banyan_segment_lines_many(many, MANY, &p, mx, ml, mc, &err) == BANYAN_OK, "many: %s", err.message);
    int bad_many = 0;
    for (int i = 0; i < MANY; i++) {
        banyan_segment_lines(&many[i], &p, xyz, lev, &count, NULL);
        if (count != mc[i] || memcmp(xyz, mx + (size_t)3 * MAXV * i, sizeof(float) * 3 * count) ||
            memcmp(lev, ml + (size_t)MAXV * i, (size_t)count))
            bad_many++;
    }
    CHECK(bad_many == 0, "%d of %d batch outputs differ from single calls", bad_many, MANY);
    many[17].n = 64;
    CHECK(banyan_segment_lines_many(many, MANY, &p, mx, ml, mc, &err) == BANYAN_E_RANGE &&
              strstr(err.message, "ins[17].n = 64"), "batch error: %s", err.message);
    CHECK(banyan_segment_lines_many(NULL, 0, &p, NULL, NULL, NULL, &err) == BANYAN_OK, "empty batch");
    free(mx);
    free(ml);

    /* --- Uniforms are the float cos/sin pairs. */
    float u[9];
    CHECK(banyan_segment_uniforms(&p, u, &err) == BANYAN_OK, "uniforms: %s", err.message);
    CHECK(u[0] == (float)cos(deg2rad(40)) && u[1] == (float)sin(deg2rad(40)) && u[5] == (float)sin(deg2rad(-30)) &&
              u[8] == 10.0f, "uniform values");

    /* --- Shader sources exist and declare the budget. */
    CHECK(banyan_segment_shader_source(0) && banyan_segment_shader_source(2) && !banyan_segment_shader_source(3) &&
              !banyan_segment_shader_source(-1), "shader stages");
    const char *g = banyan_segment_shader_source(1);
    CHECK(g && strstr(g, "max_vertices = 128") && strstr(g, "layout(points) in") && strstr(g, "line_strip"),
          "geometry shader layout");
    CHECK(banyan_sizeof_segment_input() == sizeof(banyan_segment_input) &&
              banyan_sizeof_segment_params() == sizeof(banyan_segment_params), "sizeof calls");
    return check_done("test_segments");
}

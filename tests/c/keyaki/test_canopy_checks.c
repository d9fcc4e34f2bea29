/* test_canopy_checks: canopy_checks.h's measures on a hand-made mesh whose
 * answers are known: an alpha-tested leaf quad at 3 m opaque only in its
 * top-left quarter (texture rows run down, banyan's v up), a wood quad at
 * 2.5 m under the bottom-left quarter, an opaque leaf quad at 1 m (under
 * the eye: it adds leaf area low in the tree, not cover), a vertical wood
 * trunk (edge-on from below) and a second group far away that a
 * measure of group 0 leaves out. */
#include <math.h>

#include "canopy_checks.h"
#include "check.h"

#define NEAR(a, b, tol) (fabs((a) - (b)) <= (tol))

/* A quad over [x0, x1] x [y0, y1] at height z, uvs the unit square. */
static void quad(float *pos, float *uv, uint32_t *idx, uint32_t base, double x0, double x1, double y0, double y1,
                 double z) {
    const double xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int i = 0; i < 4; i++) {
        pos[3 * i] = (float)xs[i], pos[3 * i + 1] = (float)ys[i], pos[3 * i + 2] = (float)z;
        uv[2 * i] = (float)(i == 1 || i == 2), uv[2 * i + 1] = (float)(i >= 2);
    }
    const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) idx[i] = base + t[i];
}

int main(void) {
    /* vertices: leaf top 0-3, wood 4-7, leaf low 8-11, trunk 12-15, far leaf 16-19 */
    float pos[3 * 20], uv[2 * 20];
    uint32_t idx[6 * 5];
    quad(pos, uv, idx, 0, 0, 1, 0, 1, 3.0);
    quad(pos + 12, uv + 8, idx + 6, 4, 0, 0.5, 0, 0.5, 2.5);
    quad(pos + 24, uv + 16, idx + 12, 8, 0, 1, 0, 1, 1.0);
    quad(pos + 36, uv + 24, idx + 18, 12, 0.5, 0.5, 0.4, 0.6, 0.0); /* flat in x: a vertical card */
    for (int i = 0; i < 4; i++) pos[36 + 3 * i + 2] = (i >= 2) ? 3.0f : 0.0f;
    quad(pos + 48, uv + 32, idx + 24, 16, 100, 110, 100, 110, 9.0);

    uint8_t half[8 * 8], full[8 * 8];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) half[y * 8 + x] = (x < 4 && y < 4) ? 255 : 0; /* image top-left */
    memset(full, 200, sizeof full);
    const canopy_alpha a_half = {8, 8, half}, a_full = {8, 8, full}, wood = {0, 0, NULL};
    const canopy_alpha *alpha[3] = {&a_half, &wood, &a_full};

    banyan_part parts[5] = {{0, 4, 0, 6, 0, 0}, {4, 4, 6, 6, 1, 0}, {8, 4, 12, 6, 2, 0}, {12, 4, 18, 6, 1, 0},
                            {16, 4, 24, 6, 2, 1}};
    banyan_mesh m;
    memset(&m, 0, sizeof m);
    m.vertex_count = 20, m.index_count = 30;
    m.positions = pos, m.uvs = uv, m.indices = idx;
    m.part_count = 5, m.parts = parts;

    canopy_figures f;
    CHECK(canopy_measure(&m, 0, alpha, 0.01, 1.6, &f), "group 0 holds leaves");
    CHECK(NEAR(f.outline_m2, 1.0, 1e-9), "outline %.6f m2, the unit square", f.outline_m2);
    CHECK(NEAR(f.leaf_m2, 1.25, 0.03), "leaf area %.4f m2: a quarter of the top quad and the whole low one", f.leaf_m2);
    CHECK(NEAR(f.lai, 1.25, 0.03), "LAI %.4f", f.lai);
    CHECK(NEAR(f.low_share, 1.0 / 1.25, 0.02), "low share %.4f: the low quad's area of the total", f.low_share);
    CHECK(NEAR(f.gap_below, 0.5, 0.02), "gap from below %.4f: the top-left leaf quarter and the wood block half "
          "(0.75 if the texture's rows ran up)", f.gap_below);
    CHECK(NEAR(f.height_m, 3.0, 1e-9) && f.triangles == 8, "height %.3f m, %lld triangles", f.height_m,
          (long long)f.triangles);
    CHECK(f.rays > 9000, "%lld rays in the unit square at 1 cm", (long long)f.rays);

    /* The eye above the top leaf: nothing blocks. */
    CHECK(canopy_measure(&m, 0, alpha, 0.01, 3.5, &f) && NEAR(f.gap_below, 1.0, 1e-9), "eye above the crown: gap %.4f",
          f.gap_below);
    /* Every group: the far quad widens the outline. */
    CHECK(canopy_measure(&m, -1, alpha, 0.5, 1.6, &f) && f.outline_m2 > 100.0, "all groups: outline %.1f m2",
          f.outline_m2);
    /* No leaves in the group: nothing measured. */
    const canopy_alpha *bare[3] = {&wood, &wood, &wood};
    CHECK(!canopy_measure(&m, 0, bare, 0.01, 1.6, &f), "no leaves: 0");
    return check_done("test_canopy_checks");
}

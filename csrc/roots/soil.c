/* soil.c - the soil line of the roots (docs/roots.md, "Soil line"). Where
 * a strangler fig's roots meet the ground they are darker and stained by
 * the soil: splashed by rain, wet longer, in a band some 10-30 cm high
 * that is irregular along the ground and darkest at the soil. The mesh's
 * vertex colours become a multiplier of the bark (glTF shows texture x
 * COLOR_0, the add-on's fig bark image x its Color attribute): white
 * above the band, towards the ground a darker, warmer soil tint.
 *
 * The band's top at a point of the ground is soil_line times 0.5 .. 1.5,
 * from a smooth value noise over world x, y (a 0.6 m cell, a 0.17 m one
 * for a ragged edge), so it rises and falls round the foot and never
 * reaches 2 soil_line. The stain is full in the band's lowest quarter
 * and fades with a smoothstep to nothing at its top, so the band reads
 * from a few metres yet has no edge; a second noise makes it patchy
 * (0.8 .. 1 of full). Faces
 * turned up are washed by the rain: there the stain falls off faster with
 * height (t x (1 - up + up t^3)), so a surface root lying on the ground
 * keeps a grey top over dark flanks, while everything at the soil itself
 * is stained. The noise runs on the position relative to the
 * germination point G: a plant moved (far from the origin too) keeps its
 * stain, as it keeps its roots. */
#include "roots_internal.h"

#include "base/noise.h"

/* The multiplier at full stain: darker and warmer (linear RGB). */
static const double SOIL_TINT[3] = {0.42, 0.35, 0.27};

void roots_soil_line(const roots_net *net, const banyan_roots_params *p, banyan_mesh *m) {
    if (!m || !m->colors) return;
    float *C = m->colors;
    const uint32_t n = m->vertex_count;
    for (uint32_t v = 0; v < n; v++) C[4 * (size_t)v] = C[4 * (size_t)v + 1] = C[4 * (size_t)v + 2] =
                                       C[4 * (size_t)v + 3] = 1.0f;
    if (!net->w.ground || !(p->soil_line > 0)) return;
    const v3 G = net->G;
    const uint64_t seed = noise_mix(p->seed ^ 0x5017113e50117ULL);
    const uint64_t k_top = noise_mix(seed + 1), k_edge = noise_mix(seed + 2), k_patch = noise_mix(seed + 3);
    const double top_max = 1.5 * p->soil_line;
    for (uint32_t v = 0; v < n; v++) {
        const float *P = m->positions + 3 * (size_t)v;
        double h = (double)P[2] - net->w.ground_z;
        if (h >= top_max) continue;
        double x = (double)P[0] - G.x, y = (double)P[1] - G.y;
        double wave = 0.75 * noise_value2(k_top, x, y, 0.6) + 0.25 * noise_value2(k_edge, x, y, 0.17);
        double top = p->soil_line * (0.5 + wave);
        double t = 1.0 - noise_smooth01((h - 0.25 * top) / (0.75 * top)); /* 1 low in the band, 0 at its top */
        if (t <= 0) continue;
        double up = m->normals ? (double)m->normals[3 * (size_t)v + 2] : 0.0;
        up = up > 0 ? up : 0;
        double stain = t * (1.0 - up + up * t * t * t);
        stain *= 0.8 + 0.2 * noise_value2(k_patch, x, y, 0.3);
        float *c = C + 4 * (size_t)v;
        for (int k = 0; k < 3; k++) c[k] = (float)(1.0 - stain * (1.0 - SOIL_TINT[k]));
    }
}

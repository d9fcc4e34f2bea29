/* wind.c - the wind and birth attributes' bookkeeping (wind.h). */
#include "wind.h"

#include <math.h>

#include "banyan.h"

void wind_declare(mesh_builder *mb, int wind, wind_slots *ws) {
    ws->on = wind != 0;
    ws->birth = mb_add_attr(mb, BANYAN_ATTR_BIRTH);
    for (int k = 0; k < 3; k++) ws->pivot[k] = -1;
    ws->level = ws->stiffness = ws->phase = ws->flutter = -1;
    if (!ws->on) return;
    ws->pivot[0] = mb_add_attr(mb, BANYAN_ATTR_WIND_PIVOT_X);
    ws->pivot[1] = mb_add_attr(mb, BANYAN_ATTR_WIND_PIVOT_Y);
    ws->pivot[2] = mb_add_attr(mb, BANYAN_ATTR_WIND_PIVOT_Z);
    ws->level = mb_add_attr(mb, BANYAN_ATTR_WIND_LEVEL);
    ws->stiffness = mb_add_attr(mb, BANYAN_ATTR_WIND_STIFFNESS);
    ws->phase = mb_add_attr(mb, BANYAN_ATTR_WIND_PHASE);
    ws->flutter = mb_add_attr(mb, BANYAN_ATTR_WIND_FLUTTER);
}

static double clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x == x ? x : 0; }

void wind_set(mesh_builder *mb, const wind_slots *ws, v3 pivot, double level, double stiffness, double phase,
              double flutter) {
    if (!ws->on || ws->level < 0) return;
    mb_set_attr(mb, ws->pivot[0], pivot.x);
    mb_set_attr(mb, ws->pivot[1], pivot.y);
    mb_set_attr(mb, ws->pivot[2], pivot.z);
    mb_set_attr(mb, ws->level, level);
    mb_set_attr(mb, ws->stiffness, clamp01(stiffness));
    double ph = phase - floor(phase);
    mb_set_attr(mb, ws->phase, ph >= 0 && ph < 1 ? ph : 0);
    mb_set_attr(mb, ws->flutter, clamp01(flutter));
}

void wind_birth(mesh_builder *mb, const wind_slots *ws, double birth) {
    if (ws->birth >= 0) mb_set_attr(mb, ws->birth, clamp01(birth));
}

double wind_phase_of(uint64_t seed, uint64_t branch) {
    /* splitmix64 of the pair: cheap, well mixed, no state. */
    uint64_t z = seed * 0x9E3779B97F4A7C15ull + branch + 0x632BE59BD9B4E019ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void wind_tube_rings(mesh_builder *mb, uint32_t first, uint32_t n, int sides, int cap_start, int cap_end, int slot,
                     const double *vals) {
    if (slot < 0 || (uint32_t)slot >= mb->n_attr || !vals || mb->status || n < 2) return;
    uint32_t ring = (uint32_t)sides + 1, caps = (cap_start ? 1u : 0u) + (cap_end ? 1u : 0u);
    uint64_t need = (uint64_t)n * ring + (uint64_t)caps * (ring + 1);
    if ((uint64_t)first + need > mb->nv) return;
    float *a = mb->attr[slot];
    for (uint32_t i = 0; i < n; i++) {
        float v = (float)vals[i];
        for (uint32_t j = 0; j < ring; j++) a[(size_t)first + (size_t)i * ring + j] = v;
    }
    size_t c = (size_t)first + (size_t)n * ring;
    if (cap_start) {
        for (uint32_t j = 0; j <= ring; j++) a[c + j] = (float)vals[0];
        c += ring + 1;
    }
    if (cap_end)
        for (uint32_t j = 0; j <= ring; j++) a[c + j] = (float)vals[n - 1];
}

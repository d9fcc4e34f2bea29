/* wind.h - the wind and birth attributes every generator writes (banyan.h,
 * BANYAN_ATTR_WIND_*; docs/game-engines.md).
 *
 * A generator declares the slots once (wind_declare), then before each
 * branch, twig or leaf sets the current values (wind_set, wind_birth),
 * which mesh_builder copies onto the vertices that follow. Along a swept
 * tube, values that change ring by ring (birth, stiffness) are written
 * after the sweep with wind_tube_rings. */
#ifndef BANYAN_WIND_H
#define BANYAN_WIND_H

#include "mesh_builder.h"

typedef struct wind_slots {
    int on;                   /* the wind attributes exist (params' wind) */
    int pivot[3], level, stiffness, phase, flutter;
    int birth;                /* always declared */
} wind_slots;

/* Declares birth, and the seven wind attributes when `wind` is nonzero.
 * Call before any vertex is added. */
void wind_declare(mesh_builder *mb, int wind, wind_slots *ws);

/* Current wind values for the vertices that follow (no-op when !ws->on).
 * stiffness and flutter are clamped to 0..1, phase wrapped into 0..1. */
void wind_set(mesh_builder *mb, const wind_slots *ws, v3 pivot, double level, double stiffness, double phase,
              double flutter);
/* Current birth (clamped to 0..1). */
void wind_birth(mesh_builder *mb, const wind_slots *ws, double birth);

/* A branch's phase in [0, 1), a hash of (seed, branch id): the same branch
 * keeps its phase whatever else changes. */
double wind_phase_of(uint64_t seed, uint64_t branch);

/* Per-ring values for the tube just swept from vertex `first` (mb->nv
 * before the sweep): ring i (sides + 1 vertices) takes vals[i] in
 * attribute `slot`; the caps (after the rings) take their ring's. A
 * negative slot, NULL vals or a failed builder: nothing. */
void wind_tube_rings(mesh_builder *mb, uint32_t first, uint32_t n, int sides, int cap_start, int cap_end, int slot,
                     const double *vals);

#endif

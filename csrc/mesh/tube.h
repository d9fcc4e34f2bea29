/* tube.h - the shared tube sweeper every generator meshes through.
 *
 * A polyline with a radius per point becomes rings of `sides` vertices
 * (plus one seam vertex so u runs 0..1), joined by quads split into two
 * triangles, wound counter-clockwise from outside. Frames are
 * rotation-minimising (double reflection, Wang et al. 2008), so rings do
 * not twist. u goes around the tube once (or u_tiles times), v along it:
 * the integral of arc length over the local circumference (times
 * u_tiles), so texels stay square where the tube tapers too (bark
 * textures keep their aspect). */
#ifndef BANYAN_TUBE_H
#define BANYAN_TUBE_H

#include "mesh_builder.h"

typedef struct tube_opts {
    int sides;        /* 3 .. 256 */
    int cap_start;    /* close the first ring with a flat cap */
    int cap_end;      /* close the last ring */
    v3 first_normal;  /* frame normal at point 0; (0,0,0) picks one */
    double v_offset;  /* v at point 0 (continues a parent's texture) */
    /* tube_sweep_rings only: unit normals per ring vertex (n * sides), for
     * rings that are not circles about their centre; NULL derives them. */
    const v3 *ring_normals;
    /* tube_sweep_rings only: u by arc length round each ring and v by
     * the rings' perimeters, so texels stay square on rings pressed flat
     * against a surface (the roots'); 0: u by vertex, v by radius. */
    int arc_uv;
    /* Bark tiles round the tube: u runs 0..u_tiles round every ring and v
     * gains u_tiles times as fast, so a texel stays square and one tile
     * is a circumference / u_tiles across (tube_bark_tiles picks it).
     * Keep it whole, or the seam shows; 0 or 1: once round (u 0..1). */
    int u_tiles;
} tube_opts;

/* Whole bark tiles round a tube of radius r (m) so that one tile is about
 * `tile` (m) across: max(1, round(2 pi r / tile)). Pick it once per tube,
 * from its thickest (first) ring, so the seam does not tear where the
 * radius changes along it. */
int tube_bark_tiles(double r, double tile);

/* Vertices and indices one tube of n points adds; for mb_reserve. */
void tube_counts(uint32_t n, int sides, int cap_start, int cap_end, uint32_t *verts, uint32_t *indices);

/* Rotation-minimising frames along pts[0..n-1]: unit tangents T and
 * normals N (N perpendicular to T). Coincident points reuse the previous
 * tangent. first_normal as in tube_opts. */
void tube_frames(const v3 *pts, uint32_t n, v3 first_normal, v3 *T, v3 *N);

/* Round rings on given frames: ring i holds `sides` vertices at angles
 * whose cosines and sines are cs[j], sn[j], radius radii[i], widened
 * across a bend by 1/cos(half angle) so the tube keeps its width through
 * corners; normals[i*sides+j] are the ring directions tilted by the taper
 * (tube_taper_slope). extent (optional) gets each ring's widest reach. */
void tube_round_rings(const v3 *pts, const double *radii, uint32_t n, const v3 *T, const v3 *N, const double *cs,
                      const double *sn, int sides, v3 *rings, v3 *normals, double *extent);

/* Sweeps a round tube. Needs n >= 2. */
void tube_sweep(mesh_builder *mb, const v3 *pts, const double *radii, uint32_t n, const tube_opts *o);

/* Sweeps given rings: ring i is rings[i*sides .. i*sides+sides-1] around
 * centres[i]; vertex j of each ring should sit at angle 2*pi*j/sides in the
 * same sense as tube_sweep's (counter-clockwise about the tangent). Used
 * where rings are not circles (the roots' junction smoothing). */
void tube_sweep_rings(mesh_builder *mb, const v3 *centres, const v3 *rings, uint32_t n, const tube_opts *o);

/* v (in bark tiles) gained over a segment of length l whose radius goes
 * linearly from r0 to r1, so that a texel stays as tall as it is wide. */
double tube_dv(double l, double r0, double r1, double r_mean);

/* Radius slope per metre at point i (central difference). A tapering
 * round tube's normal at ring direction d is (d - slope T) / sqrt(1 +
 * slope^2). */
static inline double tube_taper_slope(const v3 *pts, const double *radii, uint32_t n, uint32_t i) {
    uint32_t a = i ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
    double ds = v3_dist(pts[b], pts[a]);
    return ds > 1e-12 ? (radii[b] - radii[a]) / ds : 0.0;
}

/* Ring vertex j of a round ring: centre + r (cos a N + sin a (T x N)). */
static inline v3 tube_ring_point(v3 c, v3 T, v3 N, double r, int j, int sides) {
    double a = 6.283185307179586 * j / sides;
    v3 B = v3_cross(T, N);
    return v3_add(c, v3_add(v3_scale(N, r * dm_cos(a)), v3_scale(B, r * dm_sin(a))));
}

#endif

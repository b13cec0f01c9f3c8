/* equalarea.h - the equal-area map: rows uniform in cos theta, columns in phi, so every texel has
 * the same solid angle (slide 9 (Environment Map Representations), slide 22 (Sampling General 2D
 * Distributions): d(omega) = d(cos theta) d(phi)).
 *
 *     if (equalarea_dir_to_uv(d, &uv) == 0) ...     // any non-zero finite d
 *     rgb L = equalarea_lookup_bilinear(&img, d);    // wraps in phi, clamps at the poles
 *
 * Envmap frame, as latlong.h: u = phi / (2 pi) in [0, 1) (the seam is u = 0, the poles phi 0),
 * v = (1 - z) / 2.  Near the nadir v resolves the angle only to ~2e-8 rad.
 */
#ifndef ENVTEX_EQUALAREA_H
#define ENVTEX_EQUALAREA_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* d -> (u, v), exact near the zenith: 0, or -1 (uv untouched) for a zero or non-finite d. */
int equalarea_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit d, sin theta = 2 sqrt(v (1 - v)); u periodic, v clamped to [0, 1]. */
vec3 equalarea_uv_to_dir(uv2 uv);

/* Bilinear radiance at d, wrapped at the seam, clamped at the poles; black for a bad d.  map
 * non-empty; allocates nothing. */
rgb equalarea_lookup_bilinear(const image *map, vec3 d);

/* 4 pi / (w h), the solid angle of every texel; 0 if w or h is below 1. */
double equalarea_texel_solid_angle(int w, int h);

#endif

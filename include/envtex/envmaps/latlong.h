/* latlong.h - the latitude-longitude map (slide 9 (Environment Map Representations): "convert
 * direction to spherical coords, direct lookup").
 *
 *     if (latlong_dir_to_uv(d, &uv) == 0) ...      // any non-zero finite d
 *     rgb L = latlong_lookup_bilinear(&img, d);     // wraps in phi, clamps in theta
 *
 * Envmap frame, +z up: u = phi / (2 pi) in [0, 1), phi = atan2(y, x) (0 at the poles),
 * v = theta / pi, theta = acos z: row 0 is the zenith.  (The sampling slides' u, v are
 * cos theta and phi.)  docs/envmap-representations.md has every map's picture.
 */
#ifndef ENVTEX_LATLONG_H
#define ENVTEX_LATLONG_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* d -> (u, v), exact near the poles: 0, or -1 (uv untouched) for a zero or non-finite d. */
int latlong_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit (sin theta cos phi, sin theta sin phi, cos theta). */
vec3 latlong_uv_to_dir(uv2 uv);

/* Bilinear / nearest-texel ("direct lookup") radiance at d; black for a zero or NaN d. */
rgb latlong_lookup_bilinear(const image *map, vec3 d);
rgb latlong_lookup_nearest(const image *map, vec3 d);

/* Solid angle of a texel of row r of a w x h map: (cos theta_top - cos theta_bottom) 2 pi / w. */
double latlong_texel_solid_angle(int r, int w, int h);

#endif

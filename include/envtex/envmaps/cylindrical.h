/* cylindrical.h - the cylindrical panorama: the environment projected onto a vertical unit
 * cylinder, unrolled, cut at heights +-h = max_height (elevations +-atan h) (slides 6-9
 * (Environment Maps)).
 *
 *     if (cylindrical_dir_to_uv(d, 1.0, &uv) == 0) ...      // +-45 degrees of elevation
 *     rgb L = cylindrical_lookup_bilinear(&img, 1.0, d);     // black above and below
 *
 * Envmap frame: u = phi / (2 pi) in [0, 1) (the seam is u = 0), v = 1/2 - z_cyl / (2 h) with
 * z_cyl = z / sqrt(x^2 + y^2).  h = pi H / W gives square texels on the horizon.
 */
#ifndef ENVTEX_CYLINDRICAL_H
#define ENVTEX_CYLINDRICAL_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* d (any non-zero finite) -> (u, v): 0, or -1 (uv untouched) for a bad d, a pole,
 * |z_cyl| > max_height, or max_height not finite and > 0. */
int cylindrical_dir_to_uv(vec3 d, double max_height, uv2 *uv);

/* (u, v) -> unit normalize(cos phi, sin phi, z_cyl), u periodic: 0, or -1 (d untouched) for
 * v outside [0, 1], a non-finite u or v, or a bad max_height. */
int cylindrical_uv_to_dir(uv2 uv, double max_height, vec3 *d);

/* Bilinear radiance at d, wrapped at the seam, clamped in v; black where dir_to_uv fails.
 * map non-empty; allocates nothing. */
rgb cylindrical_lookup_bilinear(const image *map, double max_height, vec3 d);

#endif

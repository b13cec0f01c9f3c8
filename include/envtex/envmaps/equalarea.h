/* equalarea.h - the equal-area (cylindrical equal-area) environment map: rows uniform in
 * cos theta, columns uniform in phi, so every texel covers the same solid angle.  Lecture
 * "Environment, Texture Maps": the lat-long map of slides 11-12 wastes texels near the poles;
 * slide 22's parameterization, (u = cos theta, phi) with d(omega) = d(cos theta) d(phi), makes
 * every texel the same solid angle.
 *
 * Frame (the envmap frame, +z up, as latlong.h):  theta = acos(z) from the zenith,
 * phi = atan2(y, x) wrapped to [0, 2 pi).  Image coordinates (u to the right, v DOWN):
 *
 *     u = phi / (2 pi)                 v = (1 - cos theta) / 2 = (1 - z) / 2
 *
 *            u=0 (+x)      u=0.25 (+y)     u=0.5 (-x)     u=0.75 (-y)      u=1
 *     v=0    +-----------------------------------------------------------+  z = +1 zenith
 *            |                                                           |  z = 0.5 (theta 60)
 *     v=0.5  |                         horizon                           |  z = 0
 *            |                                                           |  z = -0.5
 *     v=1    +-----------------------------------------------------------+  z = -1 nadir
 *
 * Rows are evenly spaced in z, so the rows near the poles cover more theta than on a lat-long
 * map (the poles are squeezed vertically, stretched horizontally).  In a W x H map, texel
 * (c, r) covers phi in [2 pi c/W, 2 pi (c+1)/W) and z in (1 - 2(r+1)/H, 1 - 2r/H]: its solid
 * angle is (2 pi / W)(2 / H) = 4 pi / (W H) for every texel.
 *
 *     uv2 uv;
 *     if (equalarea_dir_to_uv(d, &uv) == 0) ...     // d need not be unit length
 *     rgb L = equalarea_lookup_bilinear(&img, d);    // wraps in phi, clamps at the poles
 *
 * Singular points: at the poles (x = y = 0) phi is undefined; we return phi = 0 (u = 0), as
 * latlong.h does.  The seam phi = 0 = 2 pi is u = 0 (never u = 1): y = -0 and y = -tiny give 0.
 * Precision: full near the zenith (v small); near the nadir v is within ulps of 1, so a double v
 * resolves the angle from the nadir only to about 2 sqrt(2^-53) ~ 2e-8 rad.
 */
#ifndef ENVTEX_EQUALAREA_H
#define ENVTEX_EQUALAREA_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Direction d (envmap frame, any non-zero finite length) -> (u, v) in [0,1) x [0,1].
 * Returns 0, or -1 (uv untouched) for a zero, infinite or NaN direction.
 * 1 - z is computed as (x^2 + y^2) / (1 + z) in the northern half, so v keeps full relative
 * precision near the zenith. */
int equalarea_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit direction: phi = 2 pi u, z = 1 - 2 v, sin theta = 2 sqrt(v (1 - v))
 * (= sqrt(1 - z^2) without the cancellation near the poles).  Any u (periodic); v is clamped
 * to [0, 1]. */
vec3 equalarea_uv_to_dir(uv2 uv);

/* Bilinear lookup in direction d (envmap frame): texel centres at ((c + 0.5)/W, (r + 0.5)/H),
 * wrapping across the phi seam, clamping at the poles.  A zero or non-finite direction returns
 * black.  map non-empty.  Allocates nothing. */
rgb equalarea_lookup_bilinear(const image *map, vec3 d);

/* Solid angle of every texel of a w x h equal-area map: 4 pi / (w h) steradians; 0 if w or h
 * is below 1. */
double equalarea_texel_solid_angle(int w, int h);

#endif

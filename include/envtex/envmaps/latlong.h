/* latlong.h - the latitude-longitude environment map (lecture slide 12: "convert direction to
 * spherical coords, direct lookup").
 *
 * Frame (the envmap frame, +z up):  theta = acos(z) in [0, pi] from the zenith,
 * phi = atan2(y, x) wrapped to [0, 2 pi).  Image coordinates: u = phi / (2 pi) to the right,
 * v = theta / pi downwards, so row 0 is the zenith and the middle row the horizon.  In a W x H
 * map, column c is centred at phi = 2 pi (c + 0.5) / W and row r at theta = pi (r + 0.5) / H.
 * These (u, v) are image coordinates; the lecture's sampling slides (16-23, envlight.h) name
 * other variables u and v: u = cos theta, v = phi.
 *
 *            u=0 (phi=0, +x)     u=0.25 (+y)      u=0.5 (-x)      u=0.75 (-y)     u=1
 *     v=0    +----------------------------------------------------------------+  zenith (+z)
 *     v=0.5  |                          horizon                               |
 *     v=1    +----------------------------------------------------------------+  nadir (-z)
 *
 *     uv2 uv;
 *     if (latlong_dir_to_uv(d, &uv) == 0) ...      // d need not be unit length
 *     rgb L = latlong_lookup_bilinear(&img, d);     // wraps in phi, clamps in theta
 *
 * Singular points: at the poles (x = y = 0) phi is undefined; we return phi = 0 there.
 */
#ifndef ENVTEX_LATLONG_H
#define ENVTEX_LATLONG_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Direction (any non-zero length) -> (u, v) in [0,1) x [0,1].  Returns -1 for a zero or
 * non-finite direction (uv untouched), else 0.  theta is computed as atan2(sqrt(x^2+y^2), z),
 * which keeps full precision near the poles where acos(z) loses it. */
int latlong_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit direction: theta = pi v, phi = 2 pi u,
 * d = (sin theta cos phi, sin theta sin phi, cos theta). */
vec3 latlong_uv_to_dir(uv2 uv);

/* Bilinear lookup of the map in direction d (envmap frame): texel centres at ((c + 0.5)/W,
 * (r + 0.5)/H), wrapping across the phi seam and clamping at the poles.  A zero or NaN
 * direction returns black. */
rgb latlong_lookup_bilinear(const image *map, vec3 d);

/* Nearest-texel lookup (the lecture's "direct lookup"). */
rgb latlong_lookup_nearest(const image *map, vec3 d);

/* Solid angle of row r of an H-row map's texels: (cos theta_top - cos theta_bottom) * 2 pi / W. */
double latlong_texel_solid_angle(int r, int w, int h);

#endif

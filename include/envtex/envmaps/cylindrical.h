/* cylindrical.h - the cylindrical (panorama) environment map: the environment projected from
 * the centre onto a vertical cylinder of radius 1 around the viewer, then unrolled.  Lecture
 * "Environment, Texture Maps", slides 6-9 (the representations of an environment: sphere,
 * cube, cylinder, lat-long...).  It cannot hold the poles: the top and bottom of the cylinder
 * are cut at a height +-h (`max_height`), i.e. at elevations +-atan(h).
 *
 * Frame (the envmap frame, +z up):  phi = atan2(y, x) wrapped to [0, 2 pi), the same columns
 * as latlong.h; height on the unit cylinder z_cyl = z / sqrt(x^2 + y^2) = cot theta.
 * Image coordinates (u to the right, v DOWN):
 *
 *     u = phi / (2 pi)                 v = 1/2 - z_cyl / (2 h)
 *
 *            u=0 (+x)      u=0.25 (+y)     u=0.5 (-x)     u=0.75 (-y)      u=1
 *     v=0    +-----------------------------------------------------------+  z_cyl = +h (elevation atan h)
 *            |                                                           |
 *     v=0.5  |                         horizon                           |  z_cyl = 0
 *            |                                                           |
 *     v=1    +-----------------------------------------------------------+  z_cyl = -h
 *
 *     side view:   z_cyl  ^        the ray from the centre through direction d meets the
 *                   +h ---|---     cylinder at height z_cyl = cot theta; rows are uniform in
 *                         | /d     that height (not in angle): seen from the centre a row at
 *                         |/ )theta   height z spans 1 / (1 + z^2) of the angle a horizon row
 *                   ------o------>  (x, y)    spans, so rows crowd towards the cuts at +-h
 *                   -h ---|---
 *
 * For square texels at the horizon, h = pi H / W (the image's vertical extent 2h in the same
 * units as its width 2 pi).
 *
 *     uv2 uv;
 *     if (cylindrical_dir_to_uv(d, 1.0, &uv) == 0) ...          // +-45 degrees of elevation
 *     rgb L = cylindrical_lookup_bilinear(&img, 1.0, d);         // black above and below
 *
 * Singular points: the poles (x = y = 0) are at infinite height: -1.  The seam phi = 0 = 2 pi
 * is u = 0 (never u = 1): y = -0 and y = -tiny give 0.
 */
#ifndef ENVTEX_CYLINDRICAL_H
#define ENVTEX_CYLINDRICAL_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Direction d (envmap frame, any non-zero finite length) -> (u, v) in [0,1) x [0,1] of a
 * cylinder cut at +-max_height.  Returns 0, or -1 (uv untouched) for a zero, infinite or NaN
 * direction, a pole (x = y = 0), a direction beyond the extent (|z_cyl| > max_height), or a
 * max_height that is not a finite positive number. */
int cylindrical_dir_to_uv(vec3 d, double max_height, uv2 *uv);

/* (u, v) -> unit direction: phi = 2 pi u, z_cyl = (1/2 - v) 2 h,
 * d = normalize(cos phi, sin phi, z_cyl).  Any finite u (periodic); v in [0, 1].  Returns 0, or
 * -1 (d untouched) for v outside [0, 1], a non-finite u or v, or a bad max_height. */
int cylindrical_uv_to_dir(uv2 uv, double max_height, vec3 *d);

/* Bilinear lookup in direction d (envmap frame): texel centres at ((c + 0.5)/W, (r + 0.5)/H),
 * wrapping across the phi seam, clamping at the top and bottom rows.  Black wherever
 * cylindrical_dir_to_uv fails (beyond the extent, the poles, bad input).  map non-empty.
 * Allocates nothing. */
rgb cylindrical_lookup_bilinear(const image *map, double max_height, vec3 d);

#endif

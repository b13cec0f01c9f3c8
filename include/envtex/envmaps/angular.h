/* angular.h - Debevec's angular map (the "light probe" format of his HDR probe gallery): the
 * mirror ball's image re-spaced so that the distance from the centre is proportional to the
 * angle from the forward axis, the whole sphere (360 degrees) across the disc.  Lecture
 * "Environment, Texture Maps", slides 6-9 (the representations of an environment).
 *
 * Frame: the same as mirrorball.h (envmap frame, +z up).  The camera is on +x looking along -x;
 * the image centre is the direction +x (back at the camera), up is +z, right is +y, and the rim
 * is -x (straight behind the probe):
 *
 *     image (u right, v DOWN)                    a = 2u - 1 (right, +y),  b = 1 - 2v (up, +z)
 *     +---------------------------+ v=0          rho = sqrt(a^2 + b^2) <= 1
 *     |        .-~~~~~~~-.        |
 *     |     .'     +z      '.     |              theta = pi rho           (angle from +x)
 *     |    /     (rho=1/2)   \    |              d = (cos theta, sin theta a/rho, sin theta b/rho)
 *     |   | -y      +x      +y |  |
 *     |    \                 /    |              inverse: theta = atan2(sqrt(y^2 + z^2), x),
 *     |     '.     -z      .'     |                       (a, b) = (y, z) / sqrt(y^2 + z^2) * theta / pi
 *     |        '-~~~~~~~-'        |
 *     +---------------------------+ v=1          rho = 1/2: 90 degrees, the plane x = 0
 *    u=0                         u=1             rho = 1:   180 degrees, -x
 *
 * Compared with the mirror ball (rho^2 = (1 - cos theta)/2), the angular map spends the disc
 * evenly on angle, so the back hemisphere is far better resolved.
 *
 * Singular point: the whole rim rho = 1 is the single direction -x.  uv -> direction gives -x
 * for every rim point (to about 1e-15: angular_uv_to_dir); direction -x (exactly: y = z = 0, x < 0) -> the top rim point
 * (u, v) = (1/2, 0), the limit approached from +z.  Direction +x -> the centre (1/2, 1/2).
 * Away from the rim point the map is well conditioned, right up to the rim.
 *
 *     uv2 uv;
 *     if (angular_dir_to_uv(d, &uv) == 0) ...     // d need not be unit length
 *     rgb L = angular_lookup_bilinear(&probe, d);
 */
#ifndef ENVTEX_ANGULAR_H
#define ENVTEX_ANGULAR_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Direction d (envmap frame, any non-zero finite length) -> image point (u, v) in the disc
 * (within [0,1]^2).  Returns 0, or -1 (uv untouched) for a zero, infinite or NaN direction.
 * d = -x returns the top rim point (1/2, 0). */
int angular_dir_to_uv(vec3 d, uv2 *uv);

/* Image point (u, v) -> unit direction.  Returns 0, or -1 (d untouched) for a point outside
 * the disc (rho > 1 + 1e-15, the slack absorbing rounding on the rim) or a NaN coordinate.
 * Every rim point gives -x up to rounding: y and z of about 1e-15 at most (theta is at best
 * the double nearest pi, whose sine is 1.2e-16, not 0). */
int angular_uv_to_dir(uv2 uv, vec3 *d);

/* Bilinear lookup of an angular map in direction d (envmap frame): texel centres at
 * ((c + 0.5)/W, (r + 0.5)/H), clamped at the image edges (next to the rim the four texels may
 * include some outside the disc).  A zero or non-finite direction returns black.  probe
 * non-empty.  Allocates nothing. */
rgb angular_lookup_bilinear(const image *probe, vec3 d);

#endif

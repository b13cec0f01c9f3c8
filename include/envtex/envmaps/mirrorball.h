/* mirrorball.h - the mirror-ball (light probe) environment map: the image of a perfectly
 * mirrored sphere seen from far away (orthographically), as photographed light probes are.
 * Lecture "Environment, Texture Maps", slides 6-9 ("sphere map": the environment as reflected
 * in a mirror ball) and 15 (light probes); the direction is the reflection of the viewing ray
 * about the ball's normal.
 *
 * Frame (the envmap frame, +z up).  The camera sits far out on +x and looks along -x at a ball
 * at the origin; its image has up = +z and right = +y.  The view vector (from the ball towards
 * the camera) is V = +x.
 *
 *      seen from above (+z):                 the image (u right, v DOWN); the ball fills it
 *                                            +---------------------------+ v=0
 *        -x   behind the ball                |        .-~~~~~~~-.        |
 *         ^                                  |     .'     +z      '.     |
 *         |         +y                       |    /    (rho=1/sqrt2)  \  |
 *       ( o ) ball   <--                     |   | -y      +x      +y |  |  centre: +x, back
 *         |                                  |    \                   /  |          at the camera
 *         v                                  |     '.     -z      .'     |  rim: -x, straight
 *      camera on +x, looking along -x        |        '-~~~~~~~-'        |       behind the ball
 *                                            +---------------------------+ v=1
 *                                           u=0                         u=1
 *
 * Image point (u, v) -> disc coordinates a = 2u - 1 (right, +y), b = 1 - 2v (up, +z); the ball
 * is the unit disc a^2 + b^2 <= 1 inscribed in [0,1]^2 (a square image is a circle touching
 * the four edges).  There the sphere's normal is n = (sqrt(1 - a^2 - b^2), a, b) and the
 * direction seen is the mirror reflection of V:
 *
 *     r = 2 (n.V) n - V = (1 - 2 rho^2, 2 n_x a, 2 n_x b),     rho^2 = a^2 + b^2
 *     inverse: n = normalize(r + V), (a, b) = (n_y, n_z)
 *
 * The front hemisphere (towards the camera) fills the inner disc rho < 1/sqrt 2, the back
 * hemisphere the outer ring; equal image areas hold equal solid angles (cos of the angle from +x
 * is 1 - 2 rho^2, uniform in rho^2), so the ring next to the rim is badly resolved.
 *
 * Singular point: the whole rim rho = 1 reflects the single direction -x.  uv -> direction
 * gives -x for every rim point; direction -x (exactly, r + V = 0) -> the top rim point
 * (u, v) = (1/2, 0), which is the limit approached from +z.  Round trips lose precision only
 * next to the rim: the angle error grows like 1e-16 / (angle from -x).
 *
 *     uv2 uv;
 *     if (mirrorball_dir_to_uv(d, &uv) == 0) ...      // d need not be unit length
 *     rgb L = mirrorball_lookup_bilinear(&probe, d);
 */
#ifndef ENVTEX_MIRRORBALL_H
#define ENVTEX_MIRRORBALL_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Direction d (envmap frame, any non-zero finite length) -> image point (u, v) in the disc
 * (within [0,1]^2).  Returns 0, or -1 (uv untouched) for a zero, infinite or NaN direction.
 * d = -x returns the top rim point (1/2, 0) (see the singular point above). */
int mirrorball_dir_to_uv(vec3 d, uv2 *uv);

/* Image point (u, v) -> unit direction reflected there.  Returns 0, or -1 (d untouched) for a
 * point outside the ball's disc (a^2 + b^2 > 1 + 1e-15, the slack absorbing the rounding of
 * points computed on the rim) or a NaN coordinate.  Every rim point gives -x. */
int mirrorball_uv_to_dir(uv2 uv, vec3 *d);

/* Bilinear lookup of a mirror-ball image in direction d (envmap frame): texel centres at
 * ((c + 0.5)/W, (r + 0.5)/H), clamped at the image edges.  Next to the rim the four texels may
 * include some outside the ball (crop probes tightly).  A zero or non-finite direction returns
 * black.  probe non-empty.  Allocates nothing. */
rgb mirrorball_lookup_bilinear(const image *probe, vec3 d);

#endif

/* angular.h - Debevec's angular map: a light probe whose radius is proportional to the angle
 * from +x, the whole sphere across the disc (slides 6-9 (Environment Maps)).
 *
 *     if (angular_dir_to_uv(d, &uv) == 0) ...     // any non-zero finite d
 *     rgb L = angular_lookup_bilinear(&probe, d);
 *
 * The frame of mirrorball.h (centre +x, right +y, up +z, rim -x).  a = 2u - 1, b = 1 - 2v,
 * rho = sqrt(a^2 + b^2) <= 1, theta = pi rho: d = (cos theta, sin theta (a, b) / rho).
 * -x maps to (1/2, 0).
 */
#ifndef ENVTEX_ANGULAR_H
#define ENVTEX_ANGULAR_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* d -> (u, v) in the disc: 0, or -1 (uv untouched) for a zero or non-finite d. */
int angular_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit d (rim: -x, y and z up to 1e-15): 0, or -1 (d untouched) for NaN or
 * rho > 1 + 1e-15. */
int angular_uv_to_dir(uv2 uv, vec3 *d);

/* Bilinear radiance at d, clamped at the image edges (blending texels outside the disc near
 * the rim); black for a bad d.  probe non-empty; allocates nothing. */
rgb angular_lookup_bilinear(const image *probe, vec3 d);

#endif

/* mirrorball.h - the mirror-ball (light probe) map: a mirrored sphere photographed from far away;
 * the direction is the view ray reflected about its normal (slides 6-9 (Environment Maps), slide 10
 * (High Dynamic Range)).
 *
 *     if (mirrorball_dir_to_uv(d, &uv) == 0) ...      // any non-zero finite d
 *     rgb L = mirrorball_lookup_bilinear(&probe, d);
 *
 * Envmap frame; camera on +x (V = +x), image right +y, up +z.  a = 2u - 1, b = 1 - 2v, the
 * disc rho^2 = a^2 + b^2 <= 1, n = (sqrt(1 - rho^2), a, b), r = 2 (n.V) n - V.  The centre is
 * +x, the whole rim -x; -x maps to (1/2, 0).
 */
#ifndef ENVTEX_MIRRORBALL_H
#define ENVTEX_MIRRORBALL_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* d -> (u, v) in the disc: 0, or -1 (uv untouched) for a zero or non-finite d. */
int mirrorball_dir_to_uv(vec3 d, uv2 *uv);

/* (u, v) -> unit r: 0, or -1 (d untouched) for NaN or rho^2 > 1 + 1e-15 (rim slack). */
int mirrorball_uv_to_dir(uv2 uv, vec3 *d);

/* Bilinear radiance at d, clamped at the image edges (blending texels outside the disc near
 * the rim); black for a bad d.  probe non-empty; allocates nothing. */
rgb mirrorball_lookup_bilinear(const image *probe, vec3 d);

#endif

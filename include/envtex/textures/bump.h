/* bump.h - bump mapping (Blinn 1978, slide 42 (Bump Mapping)): perturb the normal, not the
 * geometry.
 *
 *     bump_normal(hit.ns, hit.ng, dp_ds, dp_dt, dh_ds, dh_dt, strength, &ns);
 *
 * n' = dP/ds x dP/dt + k dh/ds (n x dP/dt) + k dh/dt (dP/ds x n), tangents projected normal
 * to n, normalized on n's side; one space for all (docs/texture-mapping.md, section 11).
 */
#ifndef ENVTEX_BUMP_H
#define ENVTEX_BUMP_H

#include "envtex/core/vec.h"

/* The smallest n'.ng allowed: n' never lies in or below the surface */
#define BUMP_MIN_COS 1e-3

/* The unit bumped normal into *out, tilted back along ng to n'.ng >= BUMP_MIN_COS.  n, ng: unit
 * shading and geometric normals, n.ng > 0; strength: k (0: n).  0, or -1 with *out = n when
 * the tangents span no plane or a value is not finite. */
int bump_normal(vec3 n, vec3 ng, vec3 dp_ds, vec3 dp_dt, double dh_ds, double dh_dt,
                double strength, vec3 *out);

#endif

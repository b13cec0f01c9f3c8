/* bump.h - bump mapping (Blinn 1978): the shading normal perturbed by a height texture's
 * derivatives, the surface unmoved.  Slide 42: "perturb the normal, not the geometry".
 *
 *     texture_height_derivs(tex, &q, &h, &dh_ds, &dh_dt);      // texture.h
 *     bump_normal(hit.ns, hit.ng, dp_ds, dp_dt, dh_ds, dh_dt, strength, &ns);
 *
 * n' = dP/ds x dP/dt + k dh/ds (n x dP/dt) + k dh/dt (dP/ds x n), normalized, on n's side, with
 * the tangents first projected perpendicular to n (derivation: docs/texture-mapping.md,
 * section 11).  One space for every vector (world); k in its units per unit of height.
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

/* bump.h - bump mapping: a shading normal perturbed by the derivatives of a height texture,
 * without moving the surface (Blinn 1978).  Lecture "Environment, Texture Maps", the bump-map
 * slide 42: "perturb the normal, not the geometry".
 *
 *     double h, dh_ds, dh_dt;
 *     texture_height_derivs(tex, &q, &h, &dh_ds, &dh_dt);      // texture.h
 *     vec3 ns;
 *     bump_normal(hit.ns, hit.ng, dp_ds, dp_dt, dh_ds, dh_dt, strength, &ns);
 *
 * Blinn's formulation.  The surface P(s, t) with unit normal n is displaced to
 * P'(s, t) = P + k h(s, t) n (k = strength).  Dropping the small terms k h dn/ds, k h dn/dt,
 *     dP'/ds = dP/ds + k dh/ds n,     dP'/dt = dP/dt + k dh/dt n,
 *     dP'/ds x dP'/dt = dP/ds x dP/dt + k dh/ds (n x dP/dt) + k dh/dt (dP/ds x n)
 * (the n x n term is 0), and n' is that, normalized and turned to n's side (a left-handed
 * (s, t) frame has dP/ds x dP/dt opposite n: the whole vector is then negated).  The tangents are
 * first projected onto the plane perpendicular to n (T - (T.n) n), so that a zero slope returns
 * n itself even where an interpolated shading normal differs from the tangents' cross product.
 * On a flat surface (n perpendicular to the tangents) the formula is exact.  All vectors share one space (world, normally); the strength is
 * in that space's units per unit of height.
 *
 * The result is kept on the geometric side: if n'.ng < BUMP_MIN_COS it is tilted back along ng
 * until n'.ng = BUMP_MIN_COS (a strong bump at a grazing angle must not make a shading normal
 * that points into the surface: lighting would leak through it).
 */
#ifndef ENVTEX_BUMP_H
#define ENVTEX_BUMP_H

#include "envtex/core/vec.h"

/* The smallest cosine allowed between the bumped normal and the geometric normal: a hair above
 * zero so n' never lies in or below the surface, without visibly limiting real bumps. */
#define BUMP_MIN_COS 1e-3

/* The bumped shading normal into *out (unit).  n: unit shading normal; ng: unit geometric
 * normal on n's side (n.ng > 0); dp_ds, dp_dt: surface tangents dP/ds, dP/dt; dh_ds, dh_dt: the
 * height's derivatives (texture_height_derivs); strength: k above (0 gives n).
 * Returns 0, or -1 when the tangents span no plane or a value is not finite: then *out = n. */
int bump_normal(vec3 n, vec3 ng, vec3 dp_ds, vec3 dp_dt, double dh_ds, double dh_dt,
                double strength, vec3 *out);

#endif

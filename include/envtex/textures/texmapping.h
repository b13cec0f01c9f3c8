/* texmapping.h - where (s, t) comes from (slides 28-37 (Parameterization)): vertex coordinates
 * interpolated with barycentric weights ("uv"), or a planar, cylindrical, spherical or cube mapping
 * of a point.
 *
 *     uv2 st = texmapping_point(TEXMAPPING_SPHERICAL, q);   // q in object space
 *     texmapping_differentials(TEXMAPPING_SPHERICAL, q, dq_dx, dq_dy, &dst_dx, &dst_dy);
 *
 * Frame: about the origin, +z up (the envmap's), phi = atan2(y, x) in [0, 2 pi), theta from +z;
 * a sphere maps q = (P_object - center) / radius.  (s, t) as texlookup.h.  s jumps 1 -> 0 at
 * phi = 0 (no crack under repeat); poles and q = 0 give finite s, t.  Pure, allocation free.
 */
#ifndef ENVTEX_TEXMAPPING_H
#define ENVTEX_TEXMAPPING_H

#include "envtex/core/vec.h"

typedef enum texmapping_kind {
    TEXMAPPING_UV, /* (s, t) given at the vertices, interpolated (triangles only) */
    TEXMAPPING_PLANAR,
    TEXMAPPING_CYLINDRICAL,
    TEXMAPPING_SPHERICAL,
    TEXMAPPING_CUBE
} texmapping_kind;

/* Tangents: central differences over this step times max(|q|, 1) */
#define TEXMAPPING_TANGENT_STEP 1e-6

/* |det| of the (s, t) Jacobian, per unit q^2, below which it is singular */
#define TEXMAPPING_SINGULAR_EPS 1e-12

/* "uv", "planar", "cylindrical", "spherical" or "cube" into *out: 0, or -1 if unknown. */
int texmapping_parse(const char *name, texmapping_kind *out);

/* The name of `k` (static). */
const char *texmapping_name(texmapping_kind k);

uv2 texmapping_planar(vec3 q);      /* (x, y) */
uv2 texmapping_cylindrical(vec3 q); /* (phi / 2 pi, z), s in [0, 1) */
uv2 texmapping_spherical(vec3 q);   /* (phi / 2 pi, 1 - theta / pi), s in [0, 1), t in [0, 1] */

/* Cube mapping: the face of the largest |component| (ties x, y, z) into *face (may be NULL),
 * (s, t) in [0, 1]^2 on it, each face the whole image (right, up seen from outside):
 *     0 +x: +y, +z   1 -x: -y, +z   2 +y: -x, +z   3 -y: +x, +z   4 +z: +x, +y   5 -z: +x, -y */
uv2 texmapping_cube(vec3 q, int *face);

/* q on face `face` (assert 0..5): ((1 + r / |a|) / 2, (1 + u / |a|) / 2), r, u, a: q's right,
 * up and axis components; a = 0: (0.5, 0.5). */
uv2 texmapping_cube_face(vec3 q, int face);

/* The mapping k (not TEXMAPPING_UV, assert) of q. */
uv2 texmapping_point(texmapping_kind k, vec3 q);

/* "uv": st = b0 st[0] + b1 st[1] + b2 st[2], b0 = 1 - b1 - b2 (barycentric interpolation). */
uv2 texmapping_uv_interpolate(const uv2 st[3], double b1, double b2);

/* d wrapped into (-0.5, 0.5] by whole turns (non-finite: 0): a seam-safe difference of s. */
double texmapping_wrap_delta(double d);

/* The change of (s, t) per pixel step for mapping k (not UV, assert): ds/dx = s(q + dq/dx) -
 * s(q), wrapped (cylindrical, spherical); exact on q's face (cube) and planar.  Zero dq: 0. */
void texmapping_differentials(texmapping_kind k, vec3 q, vec3 dq_dx, vec3 dq_dy, uv2 *dst_dx,
                              uv2 *dst_dy);

/* dq/ds, dq/dt of mapping k (not UV, assert) at q, unit normal n: in the tangent plane, dq/ds
 * raises s by 1.  0, or -1 where singular (a pole, edge-on, q = 0): then vec3_basis(n). */
int texmapping_tangents(texmapping_kind k, vec3 q, vec3 n, vec3 *dq_ds, vec3 *dq_dt);

/* [dp/ds dp/dt] = [p1-p0 p2-p0] [st1-st0 st2-st0]^-1.  0, or -1: degenerate st (relative |det|
 * <= TEXMAPPING_SINGULAR_EPS; an orthonormal basis of the plane) or zero area (zero). */
int texmapping_triangle_tangents(const vec3 p[3], const uv2 st[3], vec3 *dp_ds, vec3 *dp_dt);

/* A uv triangle's (s, t) differentials from dp/dx, dp/dy (p's space): dp = db1 (p1-p0) + db2
 * (p2-p0) by least squares, dst = db1 (st1-st0) + db2 (st2-st0).  0, or -1 (zero area: 0). */
int texmapping_triangle_differentials(const vec3 p[3], const uv2 st[3], vec3 dp_dx, vec3 dp_dy,
                                      uv2 *dst_dx, uv2 *dst_dy);

#endif

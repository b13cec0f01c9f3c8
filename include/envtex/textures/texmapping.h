/* texmapping.h - where texture coordinates come from: the lecture's parameterizations of a
 * surface point into (s, t).  Lecture "Environment, Texture Maps", slides 25-46: texture
 * coordinates given at the vertices and interpolated with barycentric weights ("uv"), and the
 * planar, cylindrical, spherical and cube mappings of an object-space point, with their seams and
 * poles.  Knows nothing of scenes: it maps points (and their differentials) to (s, t).
 *
 *     vec3 q = ...;                                      // object-space point (see below)
 *     uv2 st = texmapping_point(TEXMAPPING_SPHERICAL, q);
 *     uv2 dx, dy;                                        // footprint for mip-mapping
 *     texmapping_differentials(TEXMAPPING_SPHERICAL, q, dq_dx, dq_dy, &dx, &dy);
 *     uv2 st2 = texmapping_uv_interpolate(tri_st, b1, b2); // "uv": from the vertices
 *
 * Frame: the mappings are defined around the ORIGIN with +z up, the envmap's frame (FORMAT.md):
 * phi = atan2(y, x) wrapped to [0, 2 pi), theta = the angle from +z.  The caller chooses q: for a
 * sphere the unit direction (P_object - center) / radius, for a mesh its object-space point.
 * (s, t) follows texlookup.h: s to the right, t UP, [0, 1]^2 covers an image once; values outside
 * [0, 1] are left to the texture's wrap mode.
 *
 *   planar       s = x, t = y                 projection along z; one image per unit square
 *   cylindrical  s = phi / 2 pi, t = z        around the z axis; t is the height in object units
 *   spherical    s = phi / 2 pi, t = 1 - theta / pi     t = 1 at the north pole (+z), as the
 *                                             lat-long envmap puts the zenith on row 0 (the top)
 *   cube         the face of the largest |component| (ties: x before y before z); on it
 *                s = (1 + r / |a|) / 2, t = (1 + u / |a|) / 2 with a the face's axis component
 *                and (r, u) the face's right and up axes, seen from OUTSIDE the cube:
 *                  face 0 +x: right +y, up +z      face 1 -x: right -y, up +z
 *                  face 2 +y: right -x, up +z      face 3 -y: right +x, up +z
 *                  face 4 +z: right +x, up +y      face 5 -z: right +x, up -y
 *                every face shows the whole [0, 1]^2 image (per-face repeat, no atlas).
 *
 * Seams and poles.  s of the cylindrical and spherical mappings jumps from 1 to 0 at phi = 0
 * (the +x half of the xz-plane): the texture is continuous there under WRAP_REPEAT (no crack),
 * but a naive finite difference across it is ~1, which would pick the coarsest mip level (a
 * visible line of blur).  texmapping_differentials wraps every s difference into (-0.5, 0.5].
 * At a pole (x = y = 0) phi is undefined: atan2(0, 0) = 0 gives s = 0 (never NaN; s = 0.5 if x
 * is -0.0, as atan2(0, -0.0) = pi), and the wrapped differential stays bounded by 0.5.  The
 * cube's edges are seams of the mapping itself (the image changes there); its differentials use
 * the face of the point, analytically, so they never jump.  The zero point q = 0 maps to
 * (0, 0.5) (spherical; (0.5, 0.5) if x is -0.0, as at the poles) or face 0's centre (cube).
 *
 * Everything here is pure and allocation free.
 */
#ifndef ENVTEX_TEXMAPPING_H
#define ENVTEX_TEXMAPPING_H

#include "envtex/core/vec.h"

typedef enum texmapping_kind {
    TEXMAPPING_UV,          /* (s, t) given at the vertices, interpolated (triangles only) */
    TEXMAPPING_PLANAR,
    TEXMAPPING_CYLINDRICAL,
    TEXMAPPING_SPHERICAL,
    TEXMAPPING_CUBE
} texmapping_kind;

/* Tangents: central differences of the mapping over a step of this size times max(|q|, 1).
 * The mappings are smooth away from seams; 1e-6 keeps the truncation error ~1e-12 and the
 * rounding error ~1e-10, both far below what shading can see. */
#define TEXMAPPING_TANGENT_STEP 1e-6

/* |det| of the 2x2 (s, t) Jacobian below which it is treated as singular (per unit q squared):
 * at a pole of the spherical mapping, or a planar mapping seen edge-on. */
#define TEXMAPPING_SINGULAR_EPS 1e-12

/* "uv", "planar", "cylindrical", "spherical" or "cube" into *out: 0, or -1 if unknown. */
int texmapping_parse(const char *name, texmapping_kind *out);

/* The name texmapping_parse accepts for `k` (a static string). */
const char *texmapping_name(texmapping_kind k);

uv2 texmapping_planar(vec3 q);      /* (x, y) */
uv2 texmapping_cylindrical(vec3 q); /* (phi / 2 pi, z), s in [0, 1) */
uv2 texmapping_spherical(vec3 q);   /* (phi / 2 pi, 1 - theta / pi), s in [0, 1), t in [0, 1] */

/* Cube mapping: the face (0..5 as in the table above) into *face (may be NULL), (s, t) on it,
 * in [0, 1]^2. */
uv2 texmapping_cube(vec3 q, int *face);

/* The point projected onto the plane of face `face` (0..5, assert) from the origin:
 * (1 + r / |a|) / 2, (1 + u / |a|) / 2.  a = 0 (q on the face's own plane through the origin)
 * gives the face's centre (0.5, 0.5). */
uv2 texmapping_cube_face(vec3 q, int face);

/* The mapping `k` of q.  k must not be TEXMAPPING_UV (assert): uv needs the vertices. */
uv2 texmapping_point(texmapping_kind k, vec3 q);

/* "uv": st = b0 st[0] + b1 st[1] + b2 st[2], b0 = 1 - b1 - b2 (barycentric interpolation). */
uv2 texmapping_uv_interpolate(const uv2 st[3], double b1, double b2);

/* d wrapped into (-0.5, 0.5] by whole turns: the shortest signed difference of two s values
 * of a periodic mapping.  A non-finite d gives 0. */
double texmapping_wrap_delta(double d);

/* Screen-space differentials of (s, t) for mapping k (not UV, assert) from the point's:
 *     ds/dx = s(q + dq/dx) - s(q)     (forward difference, one pixel step)
 * with s differences wrapped by texmapping_wrap_delta for cylindrical and spherical, and the
 * cube evaluated on q's own face by its exact Jacobian (planar is exact too).  Zero dq gives
 * zero. */
void texmapping_differentials(texmapping_kind k, vec3 q, vec3 dq_dx, vec3 dq_dy, uv2 *dst_dx,
                              uv2 *dst_dy);

/* Tangents dq/ds, dq/dt of mapping k (not UV, assert) at q on a surface with unit normal n
 * (same space as q): the directions in the tangent plane along which s, t grow, scaled so
 * that moving by dq/ds raises s by 1 (the inverse of the 2x2 Jacobian of (s, t) over an
 * orthonormal tangent basis, by seam-aware central differences).  Returns 0, or -1 when the
 * Jacobian is singular (a pole, a planar mapping seen edge-on, zero q), leaving the outputs
 * the tangent basis vec3_basis(n): bump mapping then still has a frame. */
int texmapping_tangents(texmapping_kind k, vec3 q, vec3 n, vec3 *dq_ds, vec3 *dq_dt);

/* Tangents of a triangle with corners p[3] and texture coordinates st[3] (pbrt's dp/du, dp/dv):
 *     [dp/ds dp/dt] = [p1-p0 p2-p0] [st1-st0 st2-st0]^-1.
 * Returns 0, or -1 when the st triangle is degenerate (|det| <= TEXMAPPING_SINGULAR_EPS
 * relative to the st extents) or the triangle has no area: then the outputs are an orthonormal
 * basis of the triangle's plane (or zero for a zero-area triangle). */
int texmapping_triangle_tangents(const vec3 p[3], const uv2 st[3], vec3 *dp_ds, vec3 *dp_dt);

/* Screen-space (s, t) differentials of a uv-mapped triangle from the point's differentials
 * dp/dx, dp/dy (same space as p): each is written as db1 (p1-p0) + db2 (p2-p0) in the
 * triangle's plane (least squares: the part along the normal is dropped), then
 *     dst = db1 (st1 - st0) + db2 (st2 - st0).
 * Returns 0, or -1 for a zero-area triangle (outputs zero: "no differentials"). */
int texmapping_triangle_differentials(const vec3 p[3], const uv2 st[3], vec3 dp_dx, vec3 dp_dy,
                                      uv2 *dst_dx, uv2 *dst_dy);

#endif

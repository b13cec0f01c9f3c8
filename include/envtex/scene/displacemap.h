/* displacemap.h - `displacementmap NAME SCALE` applied to a scene before rendering: every sphere
 * and triangle whose material has a displacement map is tessellated and its vertices moved
 * along the normal by SCALE times the texture (displace.h), and the renderer traces the
 * resulting triangles instead.  Lecture "Environment, Texture Maps", slide 43 (displacement
 * mapping, docs/lecture-map.md): unlike a bump map, the silhouette and the shadows change.
 *
 *     scene work;
 *     if (displacemap_needed(sc)) {
 *         if (displacemap_apply(sc, 0, &mem, &work, &st, &err)) return -1;
 *         ... render `work` (build its BVH, integrate) ...
 *         displacemap_free(&work);
 *     }
 *
 * The caller's scene is NOT modified: the result is a shallow copy that owns only its new
 * sphere and triangle arrays and shares everything else (materials, textures, lights, envmap)
 * with the original, which must therefore outlive it and stay unchanged.  Free it with
 * displacemap_free, never scene_free.
 *
 * Rates (documented so a scene's cost is predictable):
 *   sphere    displace_sphere at DISPLACEMAP_SPHERE_RATE (N bands, 2N segments: 4 N (N - 1)
 *             triangles), in the sphere's object space: the unit sphere is mapped to
 *             center + radius p, then by the sphere's transform.  Heights are along the
 *             object-space normal, SCALE object units per unit of texture value (world units
 *             when the transform has no scale).  (s, t) is the spherical mapping of displace.h,
 *             or the material's texmapping of the unit direction; solid textures see the
 *             object-space point center + radius p.
 *   triangle  displace_triangle at DISPLACEMAP_TRIANGLE_RATE (N^2 triangles), in world space,
 *             along the vertex normals (trinormal); SCALE world units per unit of value.  A
 *             triangle without normals (tri) moves each corner along the angle-weighted mean of
 *             the unit geometric normals of all displaced triangles without normals that have a
 *             corner at exactly the same position, and interpolates those across its face:
 *             neighbours then move their shared edge alike, where their own geometric normals
 *             would tear it open by up to twice the displacement (a crack).  A lone or flat
 *             triangle keeps its geometric normal.  (s, t) is the corners' interpolated st
 *             (uv) or the material's point mapping of the object-space point, which solid
 *             textures also see; that point is the object corners interpolated with the world
 *             point's own weights (displace_triangle's q), so two triangles that share an
 *             edge read the same heights along it and their vertices there stay bit-equal.
 * If the whole scene would exceed max_tris (0: DISPLACEMAP_MAX_TRIS, never more than
 * SCENE_MAX_PRIMS), or more triangles than the memory budget still holds with their BVH
 * (sizeof(triangle) + bvh_bytes_per_prim() each), at those rates, both rates are halved
 * together until it fits (down to 2 and 1); if it still does not fit, an error.  The texture
 * is read with the material's filter and no footprint (texture.h's fallback: trilinear and EWA
 * read the full-resolution image bilinearly; nearest reads its nearest texel).
 * Output triangles keep the material (whose displacement map the renderer ignores from then
 * on), get has_normals = 1 (recomputed, area-weighted over every displaced triangle around the
 * vertex: a vertex on the edge between two displaced triangles' patches, with the same normal
 * before displacement on both sides, gets one normal from both patches, not a one-sided one
 * from each, so the shading has no crease along the original edges), has_st = 1 (the corner st of the
 * tessellation), and object-space corners q for point mappings and solid textures.  A sphere's
 * triangles also get st_mapped = 1: their corner st is the sphere's own mapping (its texmapping,
 * uv meaning spherical) of the undisplaced unit direction, which the renderer interpolates, so
 * the displaced copy shows its maps where the sphere did (texshade would otherwise map the
 * triangles' object points q, which know no centre or radius).  Under a mirroring transform
 * (det < 0) a sphere's corners are taken in the order 0, 2, 1, so that every output triangle
 * is counter-clockwise seen from outside, as scene.h's parsed triangles are.
 */
#ifndef ENVTEX_DISPLACEMAP_H
#define ENVTEX_DISPLACEMAP_H

#include "envtex/core/error.h"
#include "envtex/scene/scene.h"

#define DISPLACEMAP_SPHERE_RATE 96     /* 36480 triangles per sphere */
#define DISPLACEMAP_TRIANGLE_RATE 32   /* 1024 triangles per triangle */
#define DISPLACEMAP_MAX_TRIS 8000000L  /* default budget for the whole displaced scene */

typedef struct displacemap_stats {
    long spheres, triangles;   /* primitives that were displaced */
    long new_triangles;        /* triangles of the result (displaced and untouched) */
    int sphere_rate, triangle_rate; /* the rates used (lower than the defaults if halved) */
} displacemap_stats;

/* 1 if some sphere's or triangle's material has a displacement map. */
int displacemap_needed(const scene *sc);

/* The displaced scene into *out (see above; out shares all but its geometry with in).
 * max_tris: the triangle budget for the result (0: DISPLACEMAP_MAX_TRIS), capped at
 * SCENE_MAX_PRIMS.  mem: the run's memory budget (budget.h; NULL: none), charged the result's
 * triangles, which stay charged.  st may be NULL.  Returns 0, or -1 with *err set (the limit or
 * the memory budget cannot be met, out of memory); on failure *out owns nothing. */
int displacemap_apply(const scene *in, long max_tris, budget *mem, scene *out,
                      displacemap_stats *st, error *err);

/* Free what displacemap_apply allocated (the geometry arrays) and zero *out. */
void displacemap_free(scene *out);

#endif

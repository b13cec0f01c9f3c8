/* texshade.h - texture maps at a ray hit: where the hit is in texture space, how large the
 * pixel's footprint is there, and what the material's maps make of it.  Lecture "Environment,
 * Texture Maps", slides 25-46: (s, t) interpolated with barycentric weights or made by a
 * mapping of the object-space point; footprints from ray differentials for mip-mapping;
 * textures that drive BRDF parameters (diffuse, specular, roughness); light maps; bump maps.
 * This is where scene (materials, geometry) meets texture.h, texmapping.h, bump.h, raydiff.h;
 * every integrator calls texshade_surface at each hit.
 *
 *     surface s;  ... s.p, s.ng, s.n, s.entering set from the hit ...
 *     brdf_surface_from_material(&s, &sc->materials[h.material]);
 *     texshade_surface(sc, &h, &r, &rd, &s);     // differentials, then the maps
 *     ... s.kd, s.ks, s.roughness, s.emission, s.n are now the textured values ...
 *
 * What each map does (docs/scene-format.md): diffusemap replaces kd, specularmap ks,
 * roughnessmap the GGX alpha (the channel mean), emissionmap the emission (a light map),
 * bumpmap perturbs the shading normal (bump.h) by STRENGTH times the height's derivatives
 * (texture_height_derivs: differences scaled to the footprint).  displacementmap is NOT
 * evaluated here: it moved the geometry before rendering (displacemap.h).
 *
 * Where (s, t) and the object-space point come from:
 *   sphere    q = (P_object - center) / radius, the unit direction (P_object = inv P): the
 *             mapping is texmapping_point(kind, q), default spherical (`uv` means spherical);
 *             solid textures see P_object itself.
 *   triangle  uv (default): st = b0 st0 + b1 st1 + b2 st2 (the lecture's barycentric
 *             interpolation); a point mapping uses the object-space point
 *             P_object = b0 q0 + b1 q1 + b2 q2, which solid textures see too.  A triangle
 *             with st_mapped (a displaced sphere's) interpolates st whatever the mapping: its
 *             corners already hold the sphere's mapping.
 * Footprints: dp/dx, dp/dy from raydiff_at_hit; triangles turn them into barycentric
 * differentials db (least squares in the triangle's plane), so dst = db1 (st1 - st0) +
 * db2 (st2 - st0) and dP_object = db1 (q1 - q0) + db2 (q2 - q0); spheres take dP_object =
 * inv dp and the mapping's seam-aware differentials (texmapping_differentials).  Without ray
 * differentials every footprint is zero: the texture filters' documented fallback (texture.h).
 *
 * Cost: a material without maps does nothing beyond the hit's differentials (which a ray that
 * carries them needs at every hit, for the footprint of a map seen in a mirror later); a ray
 * without differentials computes none.  Nothing here allocates.
 */
#ifndef ENVTEX_TEXSHADE_H
#define ENVTEX_TEXSHADE_H

#include "envtex/integrators/brdf.h"
#include "envtex/geometry/ray.h"
#include "envtex/scene/scene.h"

/* A triangle whose edge Gram determinant |e1|^2 |e2|^2 - (e1.e2)^2 is below this fraction of
 * |e1|^2 |e2|^2 (a corner angle under ~1e-6 rad) has no usable barycentric differentials: its
 * footprint is taken as unknown (zero) rather than huge. */
#define TEXSHADE_DEGENERATE_EPS 1e-12

/* Where a hit is in texture space (exposed for tests and tools). */
typedef struct texshade_point {
    texmapping_kind mapping; /* the mapping used (never TEXMAPPING_UV for a sphere) */
    uv2 st, dst_dx, dst_dy;  /* texture coordinates and their change per pixel step */
    vec3 q, dq_dx, dq_dy;    /* object-space point (solid textures) and its change */
    vec3 dq_ds, dq_dt;       /* object-space tangents dP/ds, dP/dt (solid textures' bump) */
    vec3 dp_ds, dp_dt;       /* the same tangents in world space (bump_normal) */
} texshade_point;

/* 1 if material m has a map evaluated at hits (diffuse, specular, roughness, emission, bump;
 * not displacement, which is applied to the geometry before rendering). */
int texshade_material_has_maps(const material *m);

/* 1 if material m has a map whose value depends on the footprint: one filtered by `trilinear`
 * or `ewa` (image, checker and solid textures alike), or a bump map (its finite-difference
 * step is the footprint, whatever the filter).  `nearest` and `bilinear` maps read one point. */
int texshade_material_needs_footprint(const material *m);

/* 1 if some material of sc needs a footprint: only then are camera rays given differentials
 * (a scene of nearest or bilinear maps alone traces none; its images are the same bit for bit). */
int texshade_scene_needs_differentials(const scene *sc);

/* The hit's differentials into s: s->has_diff, dpdx, dpdy (raydiff_at_hit with the geometric
 * normal) and dndx, dndy (the change of the unbumped shading normal, oriented like s->n: the
 * sphere's normal field, or the interpolated vertex normals; zero for a flat triangle, and
 * zero where s->n is the geometric normal s->ng instead of +-ns, the integrators' fallback when
 * the interpolated normal faces away from the viewer).  rd may be NULL.  s->n, s->ng and
 * s->entering must be set (s->entering = 1 when s->n is the outward ns). */
void texshade_differentials(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                            surface *s);

/* Texture coordinates, object-space point and footprints of hit h (tp's tangents are left
 * zero), whose differentials (s->has_diff, s->dpdx, s->dpdy) are already in s
 * (texshade_differentials). */
void texshade_point_at(const scene *sc, const hit *h, const surface *s, texshade_point *tp);

/* The tangents dq_ds, dq_dt (object) and dp_ds, dp_dt (world) of tp, a point of hit h made
 * by texshade_point_at: the triangle's (texmapping_triangle_tangents) for uv, the mapping's
 * (texmapping_tangents) otherwise.  Where the mapping is singular (a pole, a degenerate (s, t)
 * triangle) they are an orthonormal basis of the tangent plane, so a bump map still has a
 * frame.  Only bump mapping needs them. */
void texshade_tangents(const scene *sc, const hit *h, texshade_point *tp);

/* texshade_differentials, then the material's maps applied to s (kd, ks, roughness, emission,
 * and a bumped s->n that stays on s->ng's side).  s must hold the hit's frame (p, ng, n,
 * entering) and the material's values (brdf_surface_from_material) on entry. */
void texshade_surface(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                      surface *s);

/* The differentials of the ray leaving surface s in direction wi by a perfect mirror
 * (wi on wo's side of the shading normal s->n: raydiff_reflect; a bumped s->n can send a
 * mirror direction below s->ng, and it is still a reflection) or refraction (wi on the other
 * side: raydiff_refract with eta = n_i / n_t
 * from s->ior and s->entering), about the shading normal s->n.  wo is the unit direction back
 * along the arriving ray, whose differentials were rd.  out->has = 0 when there are none to
 * carry (rd NULL or empty, or s reached without them). */
void texshade_delta_diff(const surface *s, const ray_diff *rd, vec3 wo, vec3 wi, ray_diff *out);

#endif

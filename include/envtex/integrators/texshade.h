/* texshade.h - texture maps at a ray hit: where the hit is in texture space, the pixel's
 * footprint there, and what the material's maps make of it (slides 25-46).  Every integrator
 * calls texshade_surface at each hit.
 *
 *     surface s;  ... s.p, s.ng, s.n, s.entering set from the hit ...
 *     brdf_surface_from_material(&s, &sc->materials[h.material]);
 *     texshade_surface(sc, &h, &r, &rd, &s);     // differentials, then the maps
 *
 * diffusemap -> kd, specularmap -> ks, roughnessmap -> GGX alpha (channel mean), emissionmap ->
 * emission, bumpmap -> n (bump.h; displacementmap acted before rendering).  (s, t): a sphere
 * maps q = (P_object - center) / radius (spherical by default); a triangle interpolates its st
 * (or maps P_object).  Footprints from raydiff_at_hit; none without differentials (texture.h's
 * fallback).  Nothing allocates.  Details: docs/texture-mapping.md, section 11.
 */
#ifndef ENVTEX_TEXSHADE_H
#define ENVTEX_TEXSHADE_H

#include "envtex/integrators/brdf.h"
#include "envtex/geometry/ray.h"
#include "envtex/scene/scene.h"

/* A triangle with |e1|^2 |e2|^2 - (e1.e2)^2 below this fraction of |e1|^2 |e2|^2 has no
 * footprint (zero, not huge) */
#define TEXSHADE_DEGENERATE_EPS 1e-12

/* Where a hit is in texture space. */
typedef struct texshade_point {
    texmapping_kind mapping; /* the mapping used (never TEXMAPPING_UV for a sphere) */
    uv2 st, dst_dx, dst_dy;  /* texture coordinates and their change per pixel step */
    vec3 q, dq_dx, dq_dy;    /* object-space point (solid textures) and its change */
    vec3 dq_ds, dq_dt;       /* object-space tangents dP/ds, dP/dt (solid textures' bump) */
    vec3 dp_ds, dp_dt;       /* the same tangents in world space (bump_normal) */
} texshade_point;

/* 1 if m has a map evaluated at hits (not displacement). */
int texshade_material_has_maps(const material *m);

/* 1 if m has a map filtered by `trilinear` or `ewa`, or a bump map (its step is the footprint). */
int texshade_material_needs_footprint(const material *m);

/* 1 if some material of sc needs a footprint: only then do camera rays get differentials. */
int texshade_scene_needs_differentials(const scene *sc);

/* The hit's s->has_diff, dpdx, dpdy (raydiff_at_hit) and dndx, dndy (the unbumped shading
 * normal's change, oriented as s->n; zero on a flat triangle or where s->n is s->ng).  rd may
 * be NULL; s->n, s->ng and s->entering set on entry. */
void texshade_differentials(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                            surface *s);

/* (s, t), object-space point and footprints of hit h (tangents zero); s has its differentials. */
void texshade_point_at(const scene *sc, const hit *h, const surface *s, texshade_point *tp);

/* tp's tangents, object dq_ds, dq_dt and world dp_ds, dp_dt (the triangle's for uv, else the
 * mapping's; where singular, an orthonormal basis of the tangent plane). */
void texshade_tangents(const scene *sc, const hit *h, texshade_point *tp);

/* texshade_differentials, then the maps applied to s (a bumped s->n stays on s->ng's side);
 * s holds the hit's frame and brdf_surface_from_material's values on entry. */
void texshade_surface(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                      surface *s);

/* The differentials of the ray leaving s along wi, about s->n: a mirror if wi is on wo's side
 * of s->n, else refraction (eta from s->ior, s->entering).  wo: unit, back along the ray that
 * had rd.  out->has = 0 when there are none (rd NULL or empty, s without them). */
void texshade_delta_diff(const surface *s, const ray_diff *rd, vec3 wo, vec3 wi, ray_diff *out);

#endif

/* texshade.h - texture maps at a ray hit (slides 26-46 (Texture Mapping)): the hit's (s, t) and
 * footprint, and what the material's maps make of the surface, for every integrator.
 *
 *     brdf_surface_from_material(&s, &sc->materials[h.material]);  // s's frame set from h
 *     texshade_surface(sc, &h, &r, &rd, &s);                       // differentials, maps
 *
 * A sphere maps q = (P_object - center) / radius; a triangle interpolates its st (or maps
 * P_object).  No differentials: no footprint.  No malloc.  docs/texture-mapping.md, section 11.
 */
#ifndef ENVTEX_TEXSHADE_H
#define ENVTEX_TEXSHADE_H

#include "envtex/integrators/brdf.h"
#include "envtex/geometry/ray.h"
#include "envtex/scene/scene.h"

/* Gram determinant of a triangle's edges, relative, below which it has no footprint */
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

/* 1 if m has a map filtered by `trilinear` or `ewa`, or a bump map. */
int texshade_material_needs_footprint(const material *m);

/* 1 if some material of sc needs a footprint (camera rays then get differentials). */
int texshade_scene_needs_differentials(const scene *sc);

/* s->has_diff, dpdx, dpdy (raydiff_at_hit) and dndx, dndy (the unbumped shading normal's
 * change, as s->n; zero where flat).  rd may be NULL; s->n, s->ng, s->entering set on entry. */
void texshade_differentials(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                            surface *s);

/* (s, t), object-space point and footprints of hit h (tangents zero); s has its differentials. */
void texshade_point_at(const scene *sc, const hit *h, const surface *s, texshade_point *tp);

/* tp's tangents dq_ds, dq_dt, dp_ds, dp_dt (the triangle's for uv, else the mapping's;
 * singular: an orthonormal basis of the tangent plane). */
void texshade_tangents(const scene *sc, const hit *h, texshade_point *tp);

/* texshade_differentials, then the maps: diffusemap -> kd, specularmap -> ks, roughnessmap ->
 * roughness, emissionmap -> emission, bumpmap -> s->n (kept on s->ng's side).  s holds the
 * hit's frame and the material's values on entry. */
void texshade_surface(const scene *sc, const hit *h, const ray *r, const ray_diff *rd, surface *s);

/* The differentials of the ray leaving s along wi: mirrored about s->n if wi is on wo's side,
 * else refracted (s->ior, s->entering).  wo: unit, back along rd's ray.  out->has = 0 when
 * there are none. */
void texshade_delta_diff(const surface *s, const ray_diff *rd, vec3 wo, vec3 wi, ray_diff *out);

#endif

/* brdf.h - the course's BRDFs (CSE 168 hw4, ../shared/FORMAT.md), their sampling and pdfs:
 *   Phong: f = kd / pi + ks (s + 2) / (2 pi) max(r . wi, 0)^s,  r = wo mirrored
 *   GGX:   f = kd / pi + F G D / (4 |n.wi| |n.wo|), Smith G, Schlick F, alpha clamped
 *   mirror and glass: deltas
 * Sampling picks the specular lobe with probability t = avg(ks) / (avg(ks) + avg(kd)) (GGX:
 * at least 0.25), else the cosine lobe.
 *
 *     if (brdf_sample(&s, wo, SAMPLING_BRDF, xi1, xi2, xi3, &r)) beta = rgb_mul(beta, r.weight);
 *
 * wo, wi: world unit vectors away from the surface; pdfs per steradian.
 */
#ifndef ENVTEX_BRDF_H
#define ENVTEX_BRDF_H

#include "envtex/scene/scene.h"

typedef struct surface {
    vec3 p;       /* world position */
    vec3 ng;      /* unit geometric normal, turned to the side wo is on */
    vec3 n;       /* unit shading normal, on the same side as ng */
    int entering; /* 1 if wo is on the outside of the object (glass: entering it) */
    brdf_kind kind;
    rgb kd, ks, emission;
    double shininess, roughness, ior;
    /* the hit's ray differentials (texshade_surface), has_diff = 0: none */
    int has_diff;
    vec3 dpdx, dpdy; /* change of p per pixel step (world) */
    vec3 dndx, dndy; /* change of the (unbumped) shading normal n per pixel step */
} surface;

/* The BRDF part of *s from a material (texshade_surface then applies its maps). */
void brdf_surface_from_material(surface *s, const material *m);

/* 1 for mirror and glass: no density, only brdf_sample can produce their directions. */
static inline int brdf_is_delta(const surface *s)
{
    return s->kind == BRDF_MIRROR || s->kind == BRDF_GLASS;
}

/* f(wo, wi); 0 below the surface and for delta BRDFs. */
rgb brdf_eval(const surface *s, vec3 wo, vec3 wi);

/* t above, in [0, 1]. */
double brdf_specular_probability(const surface *s);

/* pdf (per steradian) of brdf_sample producing wi with the given strategy; 0 for delta BRDFs. */
double brdf_pdf(const surface *s, vec3 wo, vec3 wi, sampling_kind strategy);

typedef struct brdf_sample_result {
    vec3 wi;
    double pdf; /* per steradian; 0 for a delta direction */
    rgb weight; /* f cos / pdf (delta: the reflectance picked, divided by its probability) */
    int is_delta;
} brdf_sample_result;

/* wi for wo by `strategy` (hemisphere, cosine, brdf), xi in [0, 1); 0 if it carries nothing. */
int brdf_sample(const surface *s, vec3 wo, sampling_kind strategy, double xi1, double xi2,
                double xi3, brdf_sample_result *out);

#endif

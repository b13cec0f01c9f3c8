/* sampling.h - warping uniform random numbers (xi1, xi2) in [0,1)^2 to directions with a known
 * pdf (lecture slides 16-23: "pdfs that cancel the lighting").  All directions are in a local
 * frame where the normal (or the lobe axis) is +z; sampling_to_world turns them into world
 * directions.  Every sampler has a matching pdf, in solid angle (per steradian); the unit tests
 * check each pair with a chi-square test.
 *
 *     vec3 l = sampling_cosine_hemisphere(xi1, xi2);   // pdf = cos(theta) / pi
 *     vec3 w = sampling_to_world(l, n);
 */
#ifndef ENVTEX_SAMPLING_H
#define ENVTEX_SAMPLING_H

#include "envtex/core/vec.h"

/* Uniform on the sphere: z = 1 - 2 xi1, phi = 2 pi xi2; pdf = 1 / (4 pi). */
vec3 sampling_uniform_sphere(double xi1, double xi2);
double sampling_uniform_sphere_pdf(void);

/* Uniform on the hemisphere z >= 0: z = xi1 (d(omega) = dz dphi); pdf = 1 / (2 pi). */
vec3 sampling_uniform_hemisphere(double xi1, double xi2);
double sampling_uniform_hemisphere_pdf(double cos_theta);

/* Cosine-weighted hemisphere: cos(theta) = sqrt(1 - xi1); pdf = cos(theta) / pi. */
vec3 sampling_cosine_hemisphere(double xi1, double xi2);
double sampling_cosine_hemisphere_pdf(double cos_theta);

/* Phong lobe around +z: cos(alpha) = (1 - xi1)^(1/(s+1)), xi1 = 0 on the axis;
 * pdf = (s + 1) / (2 pi) cos(alpha)^s (may point below a surface: the caller rejects those).
 * s >= 0, as the scene's `shininess` is (below -1 the lobe is no density and the direction not
 * a unit vector).  Every sampler here takes xi1, xi2 in [0, 1]; a NaN gives a NaN direction. */
vec3 sampling_phong_lobe(double s, double xi1, double xi2);
double sampling_phong_lobe_pdf(double s, double cos_alpha);

/* The GGX roughness alpha the GGX functions use (these two and brdf.c's G1): alpha is clamped
 * to [SAMPLING_GGX_ALPHA_MIN, SAMPLING_GGX_ALPHA_MAX], where the lobe has already reached its
 * limit in double precision.  alpha = 0 (the scene's default roughness, or a black roughness
 * map) is MIN too: the limit of GGX as alpha -> 0, a mirror with Schlick's Fresnel, which BRDF
 * sampling finds exactly.  (Before 2026-11-23 alpha = 0 stayed 0, a delta outside f and the
 * pdf, and a smooth GGX ball rendered black.)  So every alpha >= 0 gives finite D, G and half
 * vectors.
 *   MIN = 2^-27: at or below it alpha^2 - 1 rounds to -1, so sampling_ggx_half returns exactly
 *     +z for every xi: the lobe is already a mirror.  Smaller alphas only push D's peak
 *     1 / (pi alpha^2) (2^54 / pi here) towards overflow: computed as alpha^2 / (pi (alpha^2)^2)
 *     it is Inf below ~1e-81, where (alpha^2)^2 underflows to 0 (and 1 / alpha^2 overflows
 *     below 1e-154), and f / pdf becomes Inf / Inf.
 *   MAX = 2^64: the specular lobe has already vanished, below 2^-97 (1e-29) wherever both
 *     directions are more than 2^-40 from the horizon (measured; at normal incidence it is
 *     F / (4 pi alpha^2) = 2^-131 F).  alpha^4 = 2^256 keeps D's (alpha^2 cos^2 + sin^2)^2 and
 *     G1's alpha^2 tan^2 far from overflow, which alpha^2 alone reaches above 1e154. */
#define SAMPLING_GGX_ALPHA_MIN 0x1p-27
#define SAMPLING_GGX_ALPHA_MAX 0x1p64
static inline double sampling_ggx_alpha(double alpha)
{
    return alpha > SAMPLING_GGX_ALPHA_MIN ? fmin(alpha, SAMPLING_GGX_ALPHA_MAX) : SAMPLING_GGX_ALPHA_MIN;
}

/* GGX (Trowbridge-Reitz) half vector around +z: theta_h = atan(alpha sqrt(xi1 / (1 - xi1)));
 * pdf_h = D(h) cos(theta_h) with D from sampling_ggx_d.  alpha: sampling_ggx_alpha. */
vec3 sampling_ggx_half(double alpha, double xi1, double xi2);
/* D = alpha^2 / (pi cos^4(theta) (alpha^2 + tan^2(theta))^2) ; 0 for cos_theta <= 0;
 * alpha: sampling_ggx_alpha.  A cos_theta above 1 (n . h of two unit vectors can round to
 * 1 + 2^-52) is the axis, where D peaks at 1 / (pi alpha^2). */
double sampling_ggx_d(double alpha, double cos_theta);

/* Local direction (z along n) -> world, n unit. */
vec3 sampling_to_world(vec3 local, vec3 n);

#endif

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

#include "envtex/vec.h"

/* Uniform on the sphere: z = 1 - 2 xi1, phi = 2 pi xi2; pdf = 1 / (4 pi). */
vec3 sampling_uniform_sphere(double xi1, double xi2);
double sampling_uniform_sphere_pdf(void);

/* Uniform on the hemisphere z >= 0: z = xi1 (d(omega) = dz dphi); pdf = 1 / (2 pi). */
vec3 sampling_uniform_hemisphere(double xi1, double xi2);
double sampling_uniform_hemisphere_pdf(double cos_theta);

/* Cosine-weighted hemisphere: cos(theta) = sqrt(1 - xi1); pdf = cos(theta) / pi. */
vec3 sampling_cosine_hemisphere(double xi1, double xi2);
double sampling_cosine_hemisphere_pdf(double cos_theta);

/* Phong lobe around +z: cos(alpha) = xi1^(1/(s+1)); pdf = (s + 1) / (2 pi) cos(alpha)^s
 * (may point below a surface: the caller rejects those). */
vec3 sampling_phong_lobe(double s, double xi1, double xi2);
double sampling_phong_lobe_pdf(double s, double cos_alpha);

/* GGX (Trowbridge-Reitz) half vector around +z: theta_h = atan(alpha sqrt(xi1 / (1 - xi1)));
 * pdf_h = D(h) cos(theta_h) with D from sampling_ggx_d. */
vec3 sampling_ggx_half(double alpha, double xi1, double xi2);
/* D = alpha^2 / (pi cos^4(theta) (alpha^2 + tan^2(theta))^2) ; 0 for cos_theta <= 0 */
double sampling_ggx_d(double alpha, double cos_theta);

/* Local direction (z along n) -> world, n unit. */
vec3 sampling_to_world(vec3 local, vec3 n);

#endif

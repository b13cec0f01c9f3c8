/* sampling.h - uniform (xi1, xi2) in [0,1)^2 warped to directions with a known pdf (slides 16-23
 * (Environment Maps Generally): "pdfs that cancel the lighting").  Local frame, normal or lobe axis
 * +z; pdfs are per steradian.  Every sampler takes xi in [0, 1] (NaN gives NaN).
 *
 *     vec3 w = sampling_to_world(sampling_cosine_hemisphere(xi1, xi2), n);
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

/* Phong lobe around +z, s >= 0: cos(alpha) = (1 - xi1)^(1/(s+1)); pdf = (s + 1) / (2 pi)
 * cos(alpha)^s.  May point below a surface (the caller rejects it). */
vec3 sampling_phong_lobe(double s, double xi1, double xi2);
double sampling_phong_lobe_pdf(double s, double cos_alpha);

/* The alpha every GGX function uses, clamped to [MIN, MAX] where the lobe has reached its
 * limit in double (MIN: a mirror, MAX: gone): every alpha >= 0 gives finite D, G, h. */
#define SAMPLING_GGX_ALPHA_MIN 0x1p-27
#define SAMPLING_GGX_ALPHA_MAX 0x1p64
static inline double sampling_ggx_alpha(double alpha)
{
    return alpha > SAMPLING_GGX_ALPHA_MIN ? fmin(alpha, SAMPLING_GGX_ALPHA_MAX)
                                          : SAMPLING_GGX_ALPHA_MIN;
}

/* GGX half vector around +z: theta_h = atan(alpha sqrt(xi1 / (1 - xi1))); pdf_h = D
 * cos(theta_h). */
vec3 sampling_ggx_half(double alpha, double xi1, double xi2);
/* D = alpha^2 / (pi cos^4(theta) (alpha^2 + tan^2(theta))^2); 0 if cos_theta <= 0; above 1
 * is the axis. */
double sampling_ggx_d(double alpha, double cos_theta);

/* Local direction (z along n) -> world, n unit. */
vec3 sampling_to_world(vec3 local, vec3 n);

#endif

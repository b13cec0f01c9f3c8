/* sampling.c - direction samplers and their pdfs (see include/envtex/core/sampling.h). */
#include "envtex/core/sampling.h"

/* Largest double below 1: xi = 1 - 2^-53 must still give a valid direction. */
static double clamp01(double x)
{
    return x < 0 ? 0 : x > 0x1.fffffffffffffp-1 ? 0x1.fffffffffffffp-1 : x;
}

static vec3 from_cos(double cos_t, double phi)
{
    double sin_t = sqrt(fmax(0.0, 1 - cos_t * cos_t));
    return vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

vec3 sampling_uniform_sphere(double xi1, double xi2)
{
    return from_cos(1 - 2 * clamp01(xi1), 2 * M_PI * clamp01(xi2)); /* z = 1 - 2 xi1 */
}

double sampling_uniform_sphere_pdf(void) { return 1 / (4 * M_PI); }

vec3 sampling_uniform_hemisphere(double xi1, double xi2)
{
    return from_cos(clamp01(xi1), 2 * M_PI * clamp01(xi2)); /* z uniform in [0, 1) */
}

double sampling_uniform_hemisphere_pdf(double cos_theta)
{
    return cos_theta >= 0 ? 1 / (2 * M_PI) : 0;
}

vec3 sampling_cosine_hemisphere(double xi1, double xi2)
{
    /* cos^2 uniform: pdf cos/pi */
    return from_cos(sqrt(1 - clamp01(xi1)), 2 * M_PI * clamp01(xi2));
}

double sampling_cosine_hemisphere_pdf(double cos_theta)
{
    return cos_theta > 0 ? cos_theta / M_PI : 0;
}

vec3 sampling_phong_lobe(double s, double xi1, double xi2)
{
    /* CDF of cos(alpha) under pdf (s+1)/(2 pi) cos^s: P(cos >= c) = 1 - c^(s+1) = xi1 gives
     * c = (1 - xi1)^(1/(s+1)).  xi1 is clamped below 1, so the base is at least 2^-53 > 0. */
    return from_cos(pow(1 - clamp01(xi1), 1 / (s + 1)), 2 * M_PI * clamp01(xi2));
}

double sampling_phong_lobe_pdf(double s, double cos_alpha)
{
    /* cos_alpha in [0, 1]: a dot product of unit vectors can round to 1 + 2^-52, and
     * (1 + 2^-52)^s overflows for a huge s: clamp to the axis (the peak, (s + 1) / (2 pi)) */
    return cos_alpha > 0 ? (s + 1) / (2 * M_PI) * pow(fmin(cos_alpha, 1.0), s) : 0;
}

vec3 sampling_ggx_half(double alpha, double xi1, double xi2)
{
    xi1 = clamp01(xi1);
    alpha = sampling_ggx_alpha(alpha); /* alpha^2 finite and at least 2^-54 (or 0) */
    /* tan^2(theta_h) = alpha^2 xi1 / (1 - xi1)  ->  cos^2 = (1 - xi1) / (1 + (alpha^2 - 1) xi1) */
    double cos2 = (1 - xi1) / (1 + (alpha * alpha - 1) * xi1);
    return from_cos(sqrt(fmax(0.0, cos2)), 2 * M_PI * clamp01(xi2));
}

double sampling_ggx_d(double alpha, double cos_theta)
{
    if (!(cos_theta > 0)) return 0;
    alpha = sampling_ggx_alpha(alpha); /* the peak 1 / (pi alpha^2) and den^2 stay finite */
    /* n . h rounds up to 1 + 2^-52 at the axis: there 1 - c^2 < 0 would outweigh alpha^2 c^2
     * for alpha below ~2e-8, and a mirror-like lobe lose the samples that hit its peak */
    double c = fmin(cos_theta, 1.0);
    double c2 = c * c, a2 = alpha * alpha;
    /* alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2) */
    double den = a2 * c2 + (1 - c2); /* >= alpha^2 c^2 > 0 */
    return a2 / (M_PI * den * den);
}

vec3 sampling_to_world(vec3 l, vec3 n)
{
    vec3 t, b;
    vec3_basis(n, &t, &b);
    return vec3_add(vec3_add(vec3_scale(t, l.x), vec3_scale(b, l.y)), vec3_scale(n, l.z));
}

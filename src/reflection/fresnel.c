/* fresnel.c - dielectric Fresnel terms and Snell refraction (see
 * include/envtex/reflection/fresnel.h). */
#include "envtex/reflection/fresnel.h"

double fresnel_dielectric(double cos_i, double eta)
{
    cos_i = fmin(fmax(cos_i, 0.0), 1.0);
    /* STEP(fresnel): the fraction of light a smooth dielectric reflects: Snell's law for the
     * transmitted angle (total internal reflection when there is none), then the unpolarized
     * Fresnel reflectance (slide 5 (Using Environment for Reflection Map): "mirror reflections
     * (refraction)"; fresnel.h) */
    /* STUB: (void)eta; return 0.0; */
    double sin2_t = (1 - cos_i) * (1 + cos_i) / (eta * eta); /* Snell: sin_t = sin_i / eta */
    if (sin2_t >= 1) return 1.0;                       /* total internal reflection */
    double cos_t = sqrt(1 - sin2_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
    /* END STEP(fresnel) */
}

int fresnel_refract(vec3 d, vec3 n, double eta, vec3 *t)
{
    /* STEP(fresnel): the refracted direction by Snell's law, and 0 under total internal reflection
     * (slide 5 (Using Environment for Reflection Map); fresnel.h) */
    /* STUB: (void)d; (void)n; (void)eta; (void)t; return 0; */
    double cos_i = -vec3_dot(d, n);
    double k = 1 - (1 - cos_i) * (1 + cos_i) / (eta * eta); /* cos_t^2 */
    if (k < 0) return 0;
    /* t = d / eta + (cos_i / eta - cos_t) n */
    *t = vec3_normalize(vec3_add(vec3_scale(d, 1 / eta), vec3_scale(n, cos_i / eta - sqrt(k))));
    return 1;
    /* END STEP(fresnel) */
}

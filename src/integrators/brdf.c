/* brdf.c - the course's BRDFs, their sampling and pdfs (see include/envtex/integrators/brdf.h). */
#include "envtex/integrators/brdf.h"

#include "envtex/reflection/fresnel.h"
#include "envtex/core/sampling.h"

void brdf_surface_from_material(surface *s, const material *m)
{
    s->kind = m->brdf;
    s->kd = m->diffuse;
    s->ks = m->specular;
    s->emission = m->emission;
    s->shininess = m->shininess;
    s->roughness = m->roughness;
    s->ior = m->ior;
}

/* Smith G1 for GGX: 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)) */
static double ggx_g1(double alpha, double cos_t)
{
    if (cos_t <= 0) return 0;
    double tan2 = (1 - cos_t * cos_t) / (cos_t * cos_t);
    return 2 / (1 + sqrt(1 + alpha * alpha * tan2));
}

rgb brdf_eval(const surface *s, vec3 wo, vec3 wi)
{
    double cos_i = vec3_dot(s->n, wi), cos_o = vec3_dot(s->n, wo);
    if (cos_i <= 0 || cos_o <= 0 || brdf_is_delta(s)) return rgb_gray(0);
    rgb f = rgb_scale(s->kd, 1 / M_PI); /* kd / pi */
    if (s->kind == BRDF_PHONG) {
        if (rgb_is_black(s->ks)) return f; /* the lobe is ks times a finite number: exactly 0 */
        vec3 r = vec3_reflect(vec3_neg(wo), s->n); /* mirror direction of wo */
        /* cos = r . wi in [0, 1]: two unit vectors' dot product rounds up to 1 + 2^-52, and
         * (1 + 2^-52)^s is Inf for a huge s (1e18): clamp to the axis, where the lobe peaks */
        double c = fmin(vec3_dot(r, wi), 1.0);
        if (c > 0) f = rgb_madd(f, s->ks, (s->shininess + 2) / (2 * M_PI) * pow(c, s->shininess));
        return f;
    }
    /* GGX microfacet term F G D / (4 cos_i cos_o), even for ks = 0: Schlick's F is not 0 there */
    vec3 h = vec3_normalize(vec3_add(wi, wo));
    double a = sampling_ggx_alpha(s->roughness); /* clamped where the lobe is its limit */
    double D = sampling_ggx_d(a, vec3_dot(s->n, h));
    double G = ggx_g1(a, cos_i) * ggx_g1(a, cos_o);
    double m = pow(1 - fmax(0.0, vec3_dot(wi, h)), 5); /* Schlick: F = ks + (1 - ks) (1 - wi.h)^5 */
    rgb F = rgb_make(s->ks.r + (1 - s->ks.r) * m, s->ks.g + (1 - s->ks.g) * m,
                     s->ks.b + (1 - s->ks.b) * m);
    double den = 4 * cos_i * cos_o; /* underflows to 0 only at grazing (cosines ~1e-162), where */
    if (!(den > 0)) return f;       /* G is 0 too: the specular term's limit there is 0, not 0/0 */
    return rgb_madd(f, F, G * D / den);
}

double brdf_specular_probability(const surface *s)
{
    double ks = rgb_avg(s->ks), kd = rgb_avg(s->kd);
    /* ks = kd = 0, t = 0/0: GGX's Fresnel lobe is the only one that reflects; Phong's f is 0 */
    if (!(ks + kd > 0)) return s->kind == BRDF_GGX ? 1 : 0;
    double t = ks / (ks + kd); /* t = avg(ks) / (avg(ks) + avg(kd)) */
    /* the course's GGX scenes clamp t, ks = 0 too: that is how F's rim reflection is sampled */
    if (s->kind == BRDF_GGX && t < 0.25) t = 0.25;
    return t;
}

/* pdf of the mixture used by SAMPLING_BRDF */
static double mixture_pdf(const surface *s, vec3 wo, vec3 wi)
{
    double cos_i = vec3_dot(s->n, wi);
    if (cos_i <= 0) return 0;
    double t = brdf_specular_probability(s);
    double pdf = (1 - t) * sampling_cosine_hemisphere_pdf(cos_i);
    if (t > 0) {
        if (s->kind == BRDF_PHONG) {
            vec3 r = vec3_reflect(vec3_neg(wo), s->n);
            pdf += t * sampling_phong_lobe_pdf(s->shininess, vec3_dot(r, wi));
        } else {
            /* pdf(wi) = D(h) (n.h) / (4 |wi.h|) : the half-vector pdf through the reflection */
            vec3 h = vec3_normalize(vec3_add(wi, wo));
            double wih = fabs(vec3_dot(wi, h));
            if (wih > 0)
                pdf += t * sampling_ggx_d(s->roughness, vec3_dot(s->n, h)) * vec3_dot(s->n, h) /
                       (4 * wih);
        }
    }
    return pdf;
}

double brdf_pdf(const surface *s, vec3 wo, vec3 wi, sampling_kind strategy)
{
    if (brdf_is_delta(s)) return 0;
    double cos_i = vec3_dot(s->n, wi);
    switch (strategy) {
    case SAMPLING_HEMISPHERE: return sampling_uniform_hemisphere_pdf(cos_i) * (cos_i > 0);
    case SAMPLING_COSINE: return sampling_cosine_hemisphere_pdf(cos_i);
    default: return mixture_pdf(s, wo, wi);
    }
}

static int sample_delta(const surface *s, vec3 wo, double xi, brdf_sample_result *out)
{
    out->pdf = 0;
    out->is_delta = 1;
    if (s->kind == BRDF_MIRROR) {
        out->wi = vec3_reflect(vec3_neg(wo), s->n);
        out->weight = s->ks; /* perfect mirror weighted by `specular` */
        return !rgb_is_black(s->ks);
    }
    /* glass: reflect with probability F, refract with 1 - F; the weights F / F = 1 cancel */
    double eta = s->entering ? s->ior : 1 / s->ior;
    double F = fresnel_dielectric(vec3_dot(wo, s->n), eta);
    vec3 t;
    if (xi < F || !fresnel_refract(vec3_neg(wo), s->n, eta, &t)) {
        out->wi = vec3_reflect(vec3_neg(wo), s->n);
    } else {
        out->wi = t;
    }
    out->weight = rgb_gray(1);
    return 1;
}

int brdf_sample(const surface *s, vec3 wo, sampling_kind strategy, double xi1, double xi2,
                double xi3, brdf_sample_result *out)
{
    if (brdf_is_delta(s)) return sample_delta(s, wo, xi3, out);
    out->is_delta = 0;
    vec3 wi;
    if (strategy == SAMPLING_HEMISPHERE) {
        wi = sampling_to_world(sampling_uniform_hemisphere(xi1, xi2), s->n);
    } else if (strategy == SAMPLING_COSINE) {
        wi = sampling_to_world(sampling_cosine_hemisphere(xi1, xi2), s->n);
    } else {
        double t = brdf_specular_probability(s);
        if (xi3 >= t) {
            wi = sampling_to_world(sampling_cosine_hemisphere(xi1, xi2), s->n);
        } else if (s->kind == BRDF_PHONG) {
            vec3 r = vec3_reflect(vec3_neg(wo), s->n);
            wi = sampling_to_world(sampling_phong_lobe(s->shininess, xi1, xi2), r);
        } else {
            vec3 h = sampling_to_world(sampling_ggx_half(s->roughness, xi1, xi2), s->n);
            wi = vec3_reflect(vec3_neg(wo), h); /* wi = 2 (wo.h) h - wo */
        }
    }
    double cos_i = vec3_dot(s->n, wi);
    if (cos_i <= 0) return 0;
    double pdf = brdf_pdf(s, wo, wi, strategy);
    if (!(pdf > 0)) return 0;
    out->wi = wi;
    out->pdf = pdf;
    out->weight = rgb_scale(brdf_eval(s, wo, wi), cos_i / pdf); /* f cos / pdf */
    return 1;
}

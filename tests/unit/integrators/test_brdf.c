/* test_brdf.c - the course's BRDFs, their sampling and pdfs (include/envtex/integrators/brdf.h).
 *
 * brdf_sample is tested against brdf_pdf with a chi-square test over equal solid-angle bins
 * (sphchisq.h) plus one bin for "the sample failed" (a lobe sample below the surface), whose
 * probability is 1 minus the pdf's integral over the upper hemisphere: so the test catches a
 * sampler and a pdf that disagree, and a pdf that does not integrate to what is really sampled.
 * Also: the pdf returned with a sample is brdf_pdf at that direction and the weight is
 * f cos / pdf; f is reciprocal; reflectance stays below 1 when kd + ks <= 1; the delta BRDFs.
 */
#include "envtex/integrators/brdf.h"

#include <stddef.h>
#include <stdint.h>

#include "chisq.h"
#include "envtex/reflection/fresnel.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "sphchisq.h"
#include "unit.h"

#define N_SAMPLES   200000L /* per chi-square test */
#define N_U         16
#define N_PHI       32
#define GL_SUB      12    /* quadrature sub-intervals per bin (see test_sampling.c) */
#define PDF_REL_TOL 1e-5  /* the pdf returned with a sample against brdf_pdf (issue 4) */
#define RECIP_TOL   1e-12 /* f(wo, wi) = f(wi, wo): the same formulas, a few roundings */

typedef struct brdf_case {
    const char *name;
    brdf_kind kind;
    sampling_kind strategy;
    double kd, ks, shininess, roughness;
    double wo_theta_deg; /* viewer elevation from the normal */
} brdf_case;

static const brdf_case cases[] = {
    {"phong s=1", BRDF_PHONG, SAMPLING_BRDF, 0.3, 0.5, 1, 0, 40},
    {"phong s=10", BRDF_PHONG, SAMPLING_BRDF, 0.3, 0.5, 10, 0, 40},
    {"phong s=50", BRDF_PHONG, SAMPLING_BRDF, 0.2, 0.7, 50, 0, 60},
    {"phong s=200 specular only", BRDF_PHONG, SAMPLING_BRDF, 0.0, 0.9, 200, 0, 20},
    {"ggx alpha=0.1", BRDF_GGX, SAMPLING_BRDF, 0.3, 0.5, 0, 0.1, 40},
    {"ggx alpha=0.3", BRDF_GGX, SAMPLING_BRDF, 0.3, 0.5, 0, 0.3, 60},
    {"ggx alpha=0.7 (t clamped to 0.25)", BRDF_GGX, SAMPLING_BRDF, 0.8, 0.1, 0, 0.7, 30},
    {"ggx alpha=1 specular only", BRDF_GGX, SAMPLING_BRDF, 0.0, 0.9, 0, 1.0, 75},
    {"ggx ks=0 (Fresnel lobe, t = 0.25)", BRDF_GGX, SAMPLING_BRDF, 0.5, 0.0, 0, 0.2, 70},
    {"ggx kd=ks=0 (Fresnel lobe alone, t = 1)", BRDF_GGX, SAMPLING_BRDF, 0.0, 0.0, 0, 0.3, 80},
    {"hemisphere", BRDF_PHONG, SAMPLING_HEMISPHERE, 0.3, 0.5, 10, 0, 40},
    {"cosine", BRDF_GGX, SAMPLING_COSINE, 0.3, 0.5, 0, 0.3, 40},
};
#define N_CASES       ((int)(sizeof cases / sizeof cases[0]))
#define N_CHISQ_TESTS N_CASES

static surface make_surface(const brdf_case *c)
{
    surface s = {0};
    s.p = vec3_make(0, 0, 0);
    s.ng = s.n = vec3_make(0, 0, 1);
    s.entering = 1;
    s.kind = c->kind;
    s.kd = rgb_gray(c->kd);
    s.ks = rgb_gray(c->ks);
    s.shininess = c->shininess;
    s.roughness = c->roughness;
    s.ior = 1.5;
    return s;
}

static vec3 wo_of(double theta_deg)
{
    double t = theta_deg * M_PI / 180;
    return vec3_make(sin(t) * cos(0.7), sin(t) * sin(0.7), cos(t));
}

typedef struct pdf_ctx {
    const surface *s;
    vec3 wo;
    sampling_kind strategy;
} pdf_ctx;

static double pdf_of(void *ctx, vec3 w)
{
    const pdf_ctx *c = ctx;
    return brdf_pdf(c->s, c->wo, w, c->strategy);
}

START_TEST(test_brdf_samples_fit_brdf_pdf)
{
    static double prob[SPH_MAX_BINS + 1];
    static long obs[SPH_MAX_BINS + 1];
    const brdf_case *c = &cases[_i];
    surface s = make_surface(c);
    vec3 wo = wo_of(c->wo_theta_deg);
    pdf_ctx ctx = {&s, wo, c->strategy};
    sph_grid g = sph_grid_make(N_U, N_PHI);
    g.sub = GL_SUB;
    double total = sph_expected(&g, pdf_of, &ctx, prob);
    ck_assert_msg(total <= 1 + 1e-4, "%s: pdf integrates to %.9f > 1", c->name, total);
    int nb = sph_add_reject_bin(&g, prob, total), reject = sph_n_bins(&g);
    for (int k = 0; k < nb; k++) obs[k] = 0;
    rng r;
    rng_seed(&r, 100 + (uint64_t)_i, 3);
    long pdf_mismatch = 0, weight_mismatch = 0;
    for (long i = 0; i < N_SAMPLES; i++) {
        double xi1 = rng_uniform(&r), xi2 = rng_uniform(&r), xi3 = rng_uniform(&r);
        brdf_sample_result bs;
        if (!brdf_sample(&s, wo, c->strategy, xi1, xi2, xi3, &bs)) {
            obs[reject]++;
            continue;
        }
        obs[sph_bin(&g, bs.wi)]++;
        /* the pdf returned with the sample is brdf_pdf there; the weight is f cos / pdf */
        double p = brdf_pdf(&s, wo, bs.wi, c->strategy);
        pdf_mismatch += !(fabs(bs.pdf - p) <= PDF_REL_TOL * p);
        double w = brdf_eval(&s, wo, bs.wi).g * bs.wi.z / p;
        weight_mismatch += !(fabs(bs.weight.g - w) <= PDF_REL_TOL * w);
    }
    ck_assert_msg(pdf_mismatch == 0, "%s: %ld samples' pdf differs from brdf_pdf", c->name,
                  pdf_mismatch);
    ck_assert_msg(weight_mismatch == 0, "%s: %ld weights differ from f cos / pdf", c->name,
                  weight_mismatch);
    chisq_result res = chisq_test(obs, prob, nb, N_SAMPLES);
    ck_assert_msg(chisq_accept(&res, N_CHISQ_TESTS),
                  "%s: X^2 = %g, dof %d, p = %g, stray %ld (rejected %ld, expected %g)", c->name,
                  res.stat, res.dof, res.p, res.stray, obs[reject], prob[reject] * N_SAMPLES);
}
END_TEST

/* f(wo, wi) = f(wi, wo) for Phong (r(wo).wi = r(wi).wo) and GGX (h and G symmetric; Schlick
 * uses wi.h = wo.h) */
START_TEST(test_brdf_eval_is_reciprocal)
{
    rng r;
    rng_seed(&r, 7, 0);
    int bad = 0;
    for (int ci = 0; ci < N_CASES; ci++) {
        surface s = make_surface(&cases[ci]);
        for (int i = 0; i < 200; i++) {
            vec3 a = sampling_uniform_hemisphere(rng_uniform(&r), rng_uniform(&r));
            vec3 b = sampling_uniform_hemisphere(rng_uniform(&r), rng_uniform(&r));
            rgb f1 = brdf_eval(&s, a, b), f2 = brdf_eval(&s, b, a);
            bad += !(fabs(f1.r - f2.r) <= RECIP_TOL * fmax(1, f1.r));
        }
    }
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* directional albedo = integral of f cos over the hemisphere <= kd + ks <= 1 for Phong at every
 * viewing angle (the (s + 2) / (2 pi) normalization), estimated with cosine-weighted samples on
 * a fine stratified grid; and exactly kd for a diffuse surface */
START_TEST(test_brdf_phong_albedo_never_exceeds_kd_plus_ks)
{
    const double view[] = {0, 30, 60, 85};
    const double shin[] = {1, 10, 100};
    enum { G = 200 };
    for (int si = 0; si < 3; si++)
        for (int vi = 0; vi < 4; vi++) {
            brdf_case c = {"", BRDF_PHONG, SAMPLING_BRDF, 0.4, 0.6, shin[si], 0, view[vi]};
            surface s = make_surface(&c);
            vec3 wo = wo_of(view[vi]);
            double sum = 0; /* f cos / (cos / pi) = pi f over a G x G stratified grid */
            for (int i = 0; i < G; i++)
                for (int j = 0; j < G; j++) {
                    vec3 wi = sampling_cosine_hemisphere((i + 0.5) / G, (j + 0.5) / G);
                    sum += M_PI * brdf_eval(&s, wo, wi).r;
                }
            double albedo = sum / (G * G);
            ck_assert_msg(albedo <= 1.0 + 2e-3, "phong s=%g at %g deg: albedo %g > kd + ks",
                          shin[si], view[vi], albedo);
            ck_assert_msg(albedo >= 0.4 - 1e-3, "phong s=%g at %g deg: albedo %g < kd", shin[si],
                          view[vi], albedo);
        }
    brdf_case d = {"", BRDF_PHONG, SAMPLING_BRDF, 0.7, 0.0, 1, 0, 0};
    surface s = make_surface(&d);
    ck_assert_near(brdf_eval(&s, wo_of(10), wo_of(50)).r, 0.7 / M_PI, 1e-15);
}
END_TEST

/* t = avg(ks) / (avg(ks) + avg(kd)); GGX clamps t to 0.25, ks = 0 included (Schlick's F is not 0
 * there); ks = kd = 0 (0/0): GGX 1, the Fresnel lobe being all that reflects, Phong 0 (f = 0),
 * not NaN */
START_TEST(test_brdf_specular_probability_follows_the_course)
{
    brdf_case c = {"", BRDF_PHONG, SAMPLING_BRDF, 0.6, 0.2, 10, 0, 0};
    surface s = make_surface(&c);
    ck_assert_near(brdf_specular_probability(&s), 0.25, 1e-15);
    s.kd = rgb_make(0.9, 0.0, 0.3); /* averages: kd 0.4, ks 0.2 */
    ck_assert_near(brdf_specular_probability(&s), 0.2 / 0.6, 1e-15);
    s.ks = rgb_gray(0);
    ck_assert(brdf_specular_probability(&s) == 0); /* Phong: no specular lobe, never sampled */
    s.kd = rgb_gray(0);
    ck_assert(brdf_specular_probability(&s) == 0); /* Phong black: f = 0 */
    s.kind = BRDF_GGX;
    s.kd = rgb_gray(0.9);
    s.ks = rgb_gray(0.1);
    ck_assert_near(brdf_specular_probability(&s), 0.25, 1e-15); /* 0.1 clamped up */
    s.ks = rgb_gray(0);
    ck_assert_near(brdf_specular_probability(&s), 0.25, 1e-15); /* F = (1 - wi.h)^5 */
    s.kd = rgb_gray(0);
    ck_assert(brdf_specular_probability(&s) == 1); /* the Fresnel lobe alone */
}
END_TEST

/* A GGX surface of `specular 0` still reflects: Schlick's F = ks + (1 - ks)(1 - wi.h)^5 is
 * (1 - wi.h)^5 there, and at roughness 0.01 (hw4 ggx.test's fifth sphere) the directional albedo
 * of that lobe is F at the mirror direction times Smith's G: G1(wo)^2 (1 - cos_o)^5, black
 * facing the viewer, bright at the rim.  Estimated from BRDF samples (f cos / pdf) at five
 * viewing angles, with kd 0 (t = 1) and kd 0.5 (t = 0.25: albedo kd + that).  Catches the
 * specular term skipped when ks is black (albedo kd), and the lobe never sampled (t = 0: a
 * mirror-like lobe found by cosine samples alone, the estimate far off). */
START_TEST(test_brdf_ggx_with_ks_zero_reflects_schlicks_fresnel)
{
    const double view[] = {0, 40, 60, 75, 85}, kds[] = {0, 0.5}, a = 0.01;
    enum { N = 20000 };
    rng r;
    rng_seed(&r, 19, 0);
    for (int ki = 0; ki < 2; ki++)
        for (int vi = 0; vi < 5; vi++) {
            brdf_case c = {"", BRDF_GGX, SAMPLING_BRDF, kds[ki], 0.0, 0, a, view[vi]};
            surface s = make_surface(&c);
            vec3 wo = wo_of(view[vi]);
            double sum = 0, sum2 = 0;
            for (int i = 0; i < N; i++) {
                brdf_sample_result bs;
                double w = 0;
                if (brdf_sample(&s, wo, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r),
                                rng_uniform(&r), &bs))
                    w = bs.weight.g;
                sum += w;
                sum2 += w * w;
            }
            double mean = sum / N, se = sqrt(fmax(0, sum2 / N - mean * mean) / (N - 1));
            double co = wo.z, tan2 = (1 - co * co) / (co * co),
                   g1 = 2 / (1 + sqrt(1 + a * a * tan2));
            double want = kds[ki] + g1 * g1 * pow(1 - co, 5);
            /* within 3%: at 85 degrees some of the lobe falls below the horizon (-1.9%) */
            ck_assert_msg(fabs(mean - want) < 4 * se + 0.03 * want + 1e-4,
                          "kd %g at %g deg: albedo %.5f, want %.5f (SE %.5f)", kds[ki], view[vi],
                          mean, want, se);
        }
}
END_TEST

/* below the surface f and every pdf are 0; a sample never goes below */
START_TEST(test_brdf_is_zero_below_the_surface)
{
    for (int ci = 0; ci < N_CASES; ci++) {
        surface s = make_surface(&cases[ci]);
        vec3 wo = wo_of(cases[ci].wo_theta_deg), below = vec3_normalize(vec3_make(0.3, 0.2, -0.5));
        ck_assert(rgb_is_black(brdf_eval(&s, wo, below)));
        ck_assert(rgb_is_black(brdf_eval(&s, below, wo)));
        ck_assert(brdf_pdf(&s, wo, below, cases[ci].strategy) == 0);
    }
}
END_TEST

/* Modified Phong at the mirror direction wi = r with a huge shininess (1e18, which the parser
 * accepts): r.wi of two unit vectors rounds to 1 + 2^-52 for about a third of directions, and
 * (1 + 2^-52)^1e18 = Inf.  f and the pdf must be the lobe's peak, kd / pi + ks (s + 2) / (2 pi)
 * and (1 - t) cos / pi + t (s + 1) / (2 pi), and a BRDF sample's weight f cos / pdf finite.
 * Catches the cosine r.wi not clamped to <= 1 in brdf_eval (f = Inf) or in the Phong lobe pdf
 * (pdf = Inf, weight Inf / Inf = NaN). */
START_TEST(test_brdf_phong_with_huge_shininess_stays_finite_at_the_mirror_direction)
{
    const double shin = 1e18;
    brdf_case c = {"", BRDF_PHONG, SAMPLING_BRDF, 0.5, 0.5, shin, 0, 0};
    surface s = make_surface(&c);
    double t = brdf_specular_probability(&s);
    rng r;
    rng_seed(&r, 11, 0);
    int above_one = 0, bad = 0;
    for (int i = 0; i < 1000; i++) {
        vec3 wo = sampling_uniform_hemisphere(rng_uniform(&r), rng_uniform(&r));
        if (!(wo.z > 1e-3)) continue;
        vec3 wi = vec3_reflect(vec3_neg(wo), s.n); /* r: the lobe's axis, as brdf.c computes it */
        above_one += vec3_dot(wi, wi) > 1;
        double f = brdf_eval(&s, wo, wi).r, pdf = brdf_pdf(&s, wo, wi, SAMPLING_BRDF);
        double f_peak = 0.5 / M_PI + 0.5 * (shin + 2) / (2 * M_PI);
        double pdf_peak = (1 - t) * wi.z / M_PI + t * (shin + 1) / (2 * M_PI);
        /* r.wi = 1 - 2^-53 gives (1 - 2^-53)^1e18 = e^-111: 0 to the tolerance */
        bad += !(fabs(f - f_peak) <= 1e-12 * f_peak || f <= 0.5 / M_PI + 1e-12);
        bad += !(fabs(pdf - pdf_peak) <= 1e-12 * pdf_peak || pdf <= (1 - t) * wi.z / M_PI + 1e-12);
        brdf_sample_result bs;
        if (brdf_sample(&s, wo, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r), 0.0, &bs))
            bad += !rgb_is_finite(bs.weight) || !isfinite(bs.pdf);
    }
    ck_assert_msg(above_one > 0, "no direction had r.r > 1: the test cannot fail");
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* A mirror-like GGX (roughness 0, the scene's default, or any alpha at or below 2^-27) under a
 * normal that is not an axis: every specular sample is the mirror direction with weight F / t.
 * Catches roughness 0 kept as a delta outside f (every weight 0: a smooth GGX ball renders black)
 * and n . h rounding to 1 + 2^-52 at the peak unclamped in D (an audit found 11% of the samples
 * lost at alpha 1e-9; the test above has n = +z, where that rounding does not happen). */
START_TEST(test_brdf_mirror_like_ggx_finds_every_specular_sample_under_any_normal)
{
    const double alphas[] = {0, 1e-300, 1e-9, SAMPLING_GGX_ALPHA_MIN};
    brdf_case c = {"", BRDF_GGX, SAMPLING_BRDF, 0.5, 0.5, 0, 0, 0};
    rng r;
    rng_seed(&r, 17, 0);
    int lost = 0, wrong = 0;
    for (int i = 0; i < 4; i++) {
        c.roughness = alphas[i];
        surface s = make_surface(&c);
        for (int k = 0; k < 4000; k++) {
            s.n = s.ng = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
            vec3 wo = sampling_to_world(
                sampling_cosine_hemisphere(rng_uniform(&r), rng_uniform(&r)), s.n);
            double cos_o = vec3_dot(wo, s.n);
            if (!(cos_o > 1e-3)) continue;
            vec3 mirror = vec3_reflect(vec3_neg(wo), s.n);
            double t = brdf_specular_probability(&s), F = 0.5 + 0.5 * pow(1 - cos_o, 5);
            brdf_sample_result bs;
            /* xi3 = 0 < t: the specular lobe */
            if (!brdf_sample(&s, wo, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r), 0.0, &bs)) {
                lost++;
                continue;
            }
            wrong += !(vec3_length(vec3_sub(bs.wi, mirror)) < 1e-12);
            wrong += !(fabs(bs.weight.r - F / t) < 1e-6 * (F / t));
        }
    }
    ck_assert_int_eq(lost, 0);
    ck_assert_int_eq(wrong, 0);
}
END_TEST

/* GGX at roughnesses far beyond the lecture's range reaches its two limits with finite numbers.
 * Huge alpha (1e155 .. DBL_MAX): the specular lobe has vanished, f = kd / pi to 1e-20 away from
 * grazing, and pdf and sample weights are finite.  Tiny alpha (1e-300 .. 1e-20): a mirror, the
 * specular sample is the mirror direction with weight f cos / pdf = F / t (D dominates f and
 * the pdf alike; Schlick's F at 80 degrees is far from ks, so the diffuse weight kd / (1 - t) = 1
 * cannot pass for it).  alpha = 0 (the mirror limit, as 2^-27) stays finite.
 * Catches alpha^2 overflowing in D or in G1 (f = pdf = NaN once alpha > 1e154; G1 alone: NaN
 * at wi = n, Inf * tan^2 = Inf * 0), D's peak overflowing for alpha below ~1e-81 (weight
 * Inf / Inf = NaN), and a tiny alpha flushed to 0 instead of clamped up (as alpha^2 underflowing
 * to 0 below 1e-154 does: the specular lobe gone, weight 1, not F / t). */
START_TEST(test_brdf_ggx_with_extreme_roughness_is_finite_and_reaches_its_limits)
{
    const double huge[] = {1e155, 1e200, 1e300, 1.7976931348623157e308};
    const double tiny[] = {1e-300, 1e-160, 1e-100, 1e-20};
    brdf_case c = {"", BRDF_GGX, SAMPLING_BRDF, 0.5, 0.5, 0, 0, 0};
    rng r;
    rng_seed(&r, 13, 0);
    int bad = 0;
    for (int i = 0; i < 4; i++) {
        c.roughness = huge[i];
        surface s = make_surface(&c);
        for (int k = 0; k < 500; k++) {
            vec3 wo = sampling_cosine_hemisphere(rng_uniform(&r), rng_uniform(&r));
            vec3 wi = sampling_cosine_hemisphere(rng_uniform(&r), rng_uniform(&r));
            double f = brdf_eval(&s, wo, wi).r, pdf = brdf_pdf(&s, wo, wi, SAMPLING_BRDF);
            if (wo.z > 1e-3 && wi.z > 1e-3) bad += !(fabs(f - 0.5 / M_PI) <= 1e-20);
            bad += !isfinite(f) || !(isfinite(pdf) && pdf > 0);
            brdf_sample_result bs;
            if (brdf_sample(&s, wo, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r),
                            rng_uniform(&r), &bs))
                bad += !rgb_is_finite(bs.weight) || !isfinite(bs.pdf);
            /* wi = n exactly: tan = 0 in G1, where an unclamped alpha^2 = Inf gives Inf * 0 */
            if (wo.z > 1e-3) bad += !(fabs(brdf_eval(&s, wo, s.n).r - 0.5 / M_PI) <= 1e-20);
        }
    }
    vec3 wo = wo_of(80);
    double t = 0.5, F = 0.5 + 0.5 * pow(1 - wo.z, 5); /* Schlick at wi.h = wo.n */
    for (int i = 0; i < 4; i++) {
        c.roughness = tiny[i];
        surface s = make_surface(&c);
        vec3 mirror = vec3_reflect(vec3_neg(wo), s.n);
        for (int k = 0; k < 100; k++) {
            brdf_sample_result bs;
            /* xi3 = 0 < t: the specular lobe */
            if (!brdf_sample(&s, wo, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r), 0.0, &bs)) {
                bad++;
                continue;
            }
            bad += !(vec3_length(vec3_sub(bs.wi, mirror)) < 1e-12);
            bad += !(fabs(bs.weight.r - F / t) < 1e-6);
        }
    }
    /* both directions grazing at 1e-170: 4 cos_i cos_o underflows to 0 where G = 0 too (0/0:
     * an audit found f = NaN): the specular term is 0 there, f = kd / pi */
    c.roughness = 0.5;
    surface sg = make_surface(&c);
    double fg = brdf_eval(&sg, vec3_make(1, 0, 1e-170), vec3_make(-1, 0, 1e-170)).r;
    bad += !(fabs(fg - 0.5 / M_PI) <= 1e-15);
    c.roughness = 0;
    surface s = make_surface(&c);
    for (int k = 0; k < 500; k++) {
        vec3 wo2 = sampling_cosine_hemisphere(rng_uniform(&r), rng_uniform(&r));
        vec3 wi = sampling_cosine_hemisphere(rng_uniform(&r), rng_uniform(&r));
        bad += !rgb_is_finite(brdf_eval(&s, wo2, wi)) ||
               !isfinite(brdf_pdf(&s, wo2, wi, SAMPLING_BRDF));
        brdf_sample_result bs;
        if (brdf_sample(&s, wo2, SAMPLING_BRDF, rng_uniform(&r), rng_uniform(&r), rng_uniform(&r),
                        &bs))
            bad += !rgb_is_finite(bs.weight) || !isfinite(bs.pdf);
    }
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* a mirror reflects exactly with weight ks; glass returns the reflection or the refraction with
 * weight 1, reflecting with probability F; neither has a pdf or an f */
START_TEST(test_brdf_delta_surfaces_reflect_and_refract_exactly)
{
    brdf_case c = {"", BRDF_MIRROR, SAMPLING_BRDF, 0, 0.8, 0, 0, 0};
    surface s = make_surface(&c);
    s.ks = rgb_make(0.8, 0.5, 0.2);
    vec3 wo = wo_of(50), r = vec3_make(-wo.x, -wo.y, wo.z);
    brdf_sample_result bs;
    ck_assert(brdf_sample(&s, wo, SAMPLING_BRDF, 0.3, 0.6, 0.9, &bs));
    ck_assert(bs.is_delta && bs.pdf == 0);
    ck_assert(vec3_length(vec3_sub(bs.wi, r)) < 1e-15);
    ck_assert(bs.weight.r == 0.8 && bs.weight.g == 0.5 && bs.weight.b == 0.2);
    ck_assert(rgb_is_black(brdf_eval(&s, wo, r)) && brdf_pdf(&s, wo, r, SAMPLING_BRDF) == 0);

    s.kind = BRDF_GLASS;
    s.ior = 1.5;
    long n = 20000, refl = 0, bad = 0;
    rng g;
    rng_seed(&g, 5, 0);
    for (long i = 0; i < n; i++) {
        ck_require(brdf_sample(&s, wo, SAMPLING_BRDF, 0.5, 0.5, rng_uniform(&g), &bs));
        bad += !(bs.weight.r == 1 && bs.weight.g == 1 && bs.weight.b == 1 && bs.is_delta);
        if (bs.wi.z > 0) {
            refl++;
            bad += vec3_length(vec3_sub(bs.wi, r)) > 1e-15;
        } else {
            /* Snell: sin(theta_t) = sin(theta_i) / 1.5, in the plane of incidence */
            double st = sqrt(bs.wi.x * bs.wi.x + bs.wi.y * bs.wi.y);
            bad += fabs(st - sin(50 * M_PI / 180) / 1.5) > 1e-12;
            bad += fabs(bs.wi.x * wo.y - bs.wi.y * wo.x) > 1e-12 || bs.wi.x * wo.x > 0;
        }
    }
    ck_assert_int_eq(bad, 0);
    /* Fresnel at 50 degrees, n = 1.5 (unpolarized): Rs = 0.1147, Rp = 0.0186 -> F = 0.0667 */
    double ci = cos(50 * M_PI / 180), ct = sqrt(1 - pow(sin(50 * M_PI / 180) / 1.5, 2));
    double rs = pow((ci - 1.5 * ct) / (ci + 1.5 * ct), 2),
           rp = pow((1.5 * ci - ct) / (1.5 * ci + ct), 2);
    double F = 0.5 * (rs + rp), se = sqrt(F * (1 - F) / n);
    ck_assert_msg(fabs((double)refl / n - F) < 4 * se, "reflected %g, want F = %g",
                  (double)refl / n, F);
}
END_TEST

/* Glass seen from inside (entering = 0: a ray leaving the ball, the normal turned to its side):
 * eta = n_t / n_i = 1 / ior.  Below the critical angle asin(1 / 1.5) = 41.8 degrees it reflects
 * exactly when xi3 < F = fresnel_dielectric(cos, 1 / ior) (written out here: F at 40 degrees is
 * 0.245, with the entering eta 0.046) and otherwise refracts by Snell, sin_t = ior sin_i, on the
 * far side; beyond it, it always reflects (total internal reflection).  Catches eta = ior when
 * leaving, and F computed with the entering eta. */
START_TEST(test_brdf_glass_leaving_the_ball_refracts_with_one_over_ior)
{
    const double ior = 1.5, eta = 1 / ior, below[] = {10, 25, 40}, beyond[] = {45, 60, 85};
    brdf_case c = {"", BRDF_GLASS, SAMPLING_BRDF, 0, 0, 0, 0, 0};
    surface s = make_surface(&c);
    s.entering = 0;
    s.ior = ior;
    brdf_sample_result bs;
    for (int i = 0; i < 3; i++) {
        vec3 wo = wo_of(below[i]), mirror = vec3_make(-wo.x, -wo.y, wo.z);
        double ci = wo.z, si = sqrt(1 - ci * ci), ct = sqrt(1 - pow(si / eta, 2));
        double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
        double F = 0.5 * (rs * rs + rp * rp);
        ck_assert_near(F, fresnel_dielectric(ci, eta), 1e-12);
        ck_assert(brdf_sample(&s, wo, SAMPLING_BRDF, 0.5, 0.5, F * (1 - 1e-6), &bs));
        ck_assert_msg(vec3_length(vec3_sub(bs.wi, mirror)) < 1e-12,
                      "%g deg: xi3 below F = %g did not reflect", below[i], F);
        ck_assert(brdf_sample(&s, wo, SAMPLING_BRDF, 0.5, 0.5, F * (1 + 1e-6), &bs));
        double st = sqrt(bs.wi.x * bs.wi.x + bs.wi.y * bs.wi.y);
        ck_assert_msg(bs.wi.z < 0 && fabs(st - si / eta) < 1e-12,
                      "%g deg: sin_t %g, want %g (wi.z %g)", below[i], st, si / eta, bs.wi.z);
        ck_assert(fabs(bs.wi.x * wo.y - bs.wi.y * wo.x) < 1e-12 &&
                  bs.wi.x * wo.x <= 0); /* plane, far side */
        ck_assert(bs.is_delta && bs.weight.r == 1 && bs.weight.g == 1 && bs.weight.b == 1);
    }
    for (int i = 0; i < 3; i++) {
        vec3 wo = wo_of(beyond[i]), mirror = vec3_make(-wo.x, -wo.y, wo.z);
        const double xis[] = {0, 0.3, 0.7, 0.999999};
        for (int k = 0; k < 4; k++) {
            ck_assert(brdf_sample(&s, wo, SAMPLING_BRDF, 0.5, 0.5, xis[k], &bs));
            ck_assert_msg(vec3_length(vec3_sub(bs.wi, mirror)) < 1e-12 && bs.weight.g == 1,
                          "%g deg, xi3 %g: no total internal reflection", beyond[i], xis[k]);
        }
    }
}
END_TEST

/* Modified Phong's value at a known angle: f = kd / pi + ks (s + 2) / (2 pi) (r . wi)^s, with r
 * the mirror direction of wo (brdf.h), for wi 20 degrees off r in the plane of incidence and
 * for wi = r.  The albedo test bounds f only through its integral; this catches a wrong
 * normalization ((s + 1) / (2 pi) still keeps the albedo within [kd, kd + ks]) or exponent. */
START_TEST(test_brdf_phong_eval_is_the_modified_phong_formula)
{
    const double kd = 0.3, ks = 0.5, shin = 10;
    brdf_case c = {"", BRDF_PHONG, SAMPLING_BRDF, kd, ks, shin, 0, 40};
    surface s = make_surface(&c);
    vec3 wo = vec3_make(sin(40 * M_PI / 180), 0, cos(40 * M_PI / 180));
    vec3 wi = vec3_make(-sin(20 * M_PI / 180), 0, cos(20 * M_PI / 180)); /* r at -40: 20 deg off */
    vec3 r = vec3_make(-wo.x, 0, wo.z);
    double want = kd / M_PI + ks * (shin + 2) / (2 * M_PI) * pow(cos(20 * M_PI / 180), shin);
    ck_assert_near(brdf_eval(&s, wo, wi).r, want, 1e-12);
    ck_assert_near(brdf_eval(&s, wo, r).r, kd / M_PI + ks * (shin + 2) / (2 * M_PI), 1e-12);
}
END_TEST

/* GGX at a known off-specular pair against FORMAT.md's formulas written out here:
 * f = kd/pi + F G D / (4 cos_i cos_o), D = a^2 / (pi cos^4 th_h (a^2 + tan^2 th_h)^2),
 * G = G1(wi) G1(wo) with G1 = 2 / (1 + sqrt(1 + a^2 tan^2 th)), F = ks + (1 - ks) (1 - wi.h)^5.
 * (Only golden images saw a wrong G1, tan^2 or Schlick term before.) */
START_TEST(test_brdf_ggx_eval_is_the_courses_microfacet_formula)
{
    const double kd = 0.2, ks = 0.3, a = 0.4;
    brdf_case c = {"", BRDF_GGX, SAMPLING_BRDF, kd, ks, 0, a, 50};
    surface s = make_surface(&c);
    vec3 wo = vec3_make(sin(50 * M_PI / 180), 0, cos(50 * M_PI / 180));
    vec3 wi = vec3_normalize(vec3_make(-0.5, 0.3, 0.8));
    vec3 h = vec3_normalize(vec3_add(wi, wo));
    double ci = wi.z, co = wo.z, ch = h.z;
    double tan2h = (1 - ch * ch) / (ch * ch);
    double D = a * a / (M_PI * pow(ch, 4) * pow(a * a + tan2h, 2));
    double ti = (1 - ci * ci) / (ci * ci), to = (1 - co * co) / (co * co);
    double G = 2 / (1 + sqrt(1 + a * a * ti)) * 2 / (1 + sqrt(1 + a * a * to));
    double F = ks + (1 - ks) * pow(1 - vec3_dot(wi, h), 5);
    double want = kd / M_PI + F * G * D / (4 * ci * co);
    ck_assert_near(brdf_eval(&s, wo, wi).g, want, 1e-12 * want);
    ck_assert_near(brdf_eval(&s, wi, wo).g, want, 1e-12 * want); /* reciprocal */
}
END_TEST

/* Mirror and glass are deltas: f and every strategy's pdf are 0 even when the material also
 * has a diffuse colour (brdf.h: "0 ... for delta BRDFs"), so nothing can add a kd / pi lobe
 * to them; and a black mirror's sample carries nothing, so it ends the path (returns 0). */
START_TEST(test_brdf_delta_surfaces_have_no_f_or_pdf_even_with_a_diffuse_colour)
{
    const brdf_kind kinds[] = {BRDF_MIRROR, BRDF_GLASS};
    const sampling_kind strat[] = {SAMPLING_HEMISPHERE, SAMPLING_COSINE, SAMPLING_BRDF};
    vec3 wo = wo_of(30), wi = wo_of(60);
    for (int k = 0; k < 2; k++) {
        brdf_case c = {"", kinds[k], SAMPLING_BRDF, 0.5, 0.4, 10, 0.3, 0};
        surface s = make_surface(&c);
        ck_assert(rgb_is_black(brdf_eval(&s, wo, wi)));
        for (int j = 0; j < 3; j++) ck_assert(brdf_pdf(&s, wo, wi, strat[j]) == 0);
    }
    brdf_case m = {"", BRDF_MIRROR, SAMPLING_BRDF, 0.5, 0.0, 0, 0, 0};
    surface s = make_surface(&m);
    brdf_sample_result bs;
    ck_assert_int_eq(brdf_sample(&s, wo, SAMPLING_BRDF, 0.3, 0.6, 0.9, &bs), 0);
}
END_TEST

Suite *brdf_suite(void)
{
    Suite *s = suite_create("brdf");
    TCase *tc = tcase_create("sampling");
    tcase_add_loop_test(tc, test_brdf_samples_fit_brdf_pdf, 0, N_CASES);
    suite_add_tcase(s, tc);
    tc = tcase_create("eval");
    tcase_add_test(tc, test_brdf_eval_is_reciprocal);
    tcase_add_test(tc, test_brdf_phong_albedo_never_exceeds_kd_plus_ks);
    tcase_add_test(tc, test_brdf_specular_probability_follows_the_course);
    tcase_add_test(tc, test_brdf_ggx_with_ks_zero_reflects_schlicks_fresnel);
    tcase_add_test(tc, test_brdf_glass_leaving_the_ball_refracts_with_one_over_ior);
    tcase_add_test(tc, test_brdf_is_zero_below_the_surface);
    tcase_add_test(tc, test_brdf_delta_surfaces_reflect_and_refract_exactly);
    tcase_add_test(tc, test_brdf_delta_surfaces_have_no_f_or_pdf_even_with_a_diffuse_colour);
    tcase_add_test(tc, test_brdf_phong_eval_is_the_modified_phong_formula);
    tcase_add_test(tc, test_brdf_ggx_eval_is_the_courses_microfacet_formula);
    tcase_add_test(tc, test_brdf_phong_with_huge_shininess_stays_finite_at_the_mirror_direction);
    tcase_add_test(tc, test_brdf_ggx_with_extreme_roughness_is_finite_and_reaches_its_limits);
    tcase_add_test(tc, test_brdf_mirror_like_ggx_finds_every_specular_sample_under_any_normal);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(brdf_suite)

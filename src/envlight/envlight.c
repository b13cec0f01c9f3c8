/* envlight.c - the environment as a light: the lecture's CDF sampling in (u = cos theta,
 * v = phi), PBRT's sin-theta variant and uniform sampling; median cut's point lights come from
 * mediancut.c (see include/envtex/envlight/envlight.h). */
#include "envtex/envlight/envlight.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/core/stepcheck.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/core/sampling.h"

/* cdf-sintheta: the least remapped value inside a row, so that theta > 0 (sin theta > 0) */
#define ENVLIGHT_POLE_REM 1e-9

/* transform_is_conformal: how far A A^T may be from s^2 I, relative to s^2.  The
 * scene's matrices are products of a few rotations in double (errors ~1e-15); 1e-6 still
 * refuses a scale of 1 + 1e-6 along one axis, which would move a sample by ~1e-6 radians. */
#define ENVLIGHT_CONFORMAL_TOL 1e-6

/* A texel as the light sees it: NaN, Inf and negative channels are 0 (NaN fails both tests),
 * then scaled. */
static inline double clean(float v) { return v > 0 && v <= FLT_MAX ? (double)v : 0.0; }

static inline rgb texel(const envlight *el, int c, int r)
{
    const float *p = image_px(el->map, c, r);
    double s = el->env->scale;
    return rgb_make(clean(p[0]) * s, clean(p[1]) * s, clean(p[2]) * s);
}

/* solid angle of a texel in row r: (cos theta_r - cos theta_{r+1}) 2 pi / w (tabulated) */
static inline double texel_omega(const envlight *el, int r) { return el->row_omega[r]; }

/* world direction -> the texel that holds it (nearest), in the envmap frame.  uv here is
 * latlong's image (u = phi / 2 pi, v = theta / pi), not the lecture's u = cos theta, v = phi. */
static int world_to_texel(const envlight *el, vec3 wi, int *c, int *r, double *sin_theta)
{
    uv2 uv;
    vec3 d = el->identity ? wi : envmap_to_frame(el->env, wi);
    if (latlong_dir_to_uv(d, &uv)) return -1;
    int x = (int)(uv.u * el->w), y = (int)(uv.v * el->h);
    *c = x < el->w ? x : el->w - 1;
    *r = y < el->h ? y : el->h - 1;
    STEPCHECK_INDEX(*c, el->w, "latlong", "column");
    STEPCHECK_INDEX(*r, el->h, "latlong", "row");
    if (sin_theta) *sin_theta = sin(M_PI * uv.v);
    return 0;
}

rgb envlight_texel(const envlight *el, int c, int r) { return texel(el, c, r); }

rgb envlight_radiance(const envlight *el, vec3 wi)
{
    int c, r;
    if (!el->env->present || world_to_texel(el, wi, &c, &r, NULL)) return rgb_gray(0);
    return texel(el, c, r);
}

/* median cut's point lights (mediancut.h), their directions turned to the world */
static int build_mediancut(envlight *el, const double *energy, int n_lights, error *err)
{
    mediancut_map m = {el->map, el->env->scale, energy, el->row_omega};
    if (mediancut_build(&m, n_lights, &el->points, &el->n_points, &el->point_choice, err))
        return -1;
    mat4 to_world;
    if (mat4_inverse(el->env->to_env, &to_world)) to_world = mat4_identity();
    for (int k = 0; k < el->n_points; k++)
        el->points[k].dir = vec3_normalize(mat4_dir(&to_world, el->points[k].dir));
    return 0;
}

/* A A^T = s^2 I within ENVLIGHT_CONFORMAL_TOL, s^2 = trace(A A^T) / 3 > 0, for the linear part A
 * (upper 3 x 3) of m: directions are turned (and maybe mirrored and uniformly scaled), never
 * distorted. */
static int transform_is_conformal(const mat4 *m)
{
    double aat[3][3], s2 = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            aat[i][j] = 0;
            for (int k = 0; k < 3; k++) aat[i][j] += m->m[i][k] * m->m[j][k]; /* (A A^T)_ij */
        }
    for (int i = 0; i < 3; i++) s2 += aat[i][i] / 3;
    if (!(s2 > 0) || !isfinite(s2)) return 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (!(fabs(aat[i][j] - (i == j) * s2) <= ENVLIGHT_CONFORMAL_TOL * s2)) return 0;
    return 1;
}

/* What every light needs, envlight_build's and envlight_build_lookup's: the lat-long map (another
 * representation resampled to it), its frame, and each row's edges and solid angle. */
static int build_rows(envlight *el, const envmap *env, envsampling_mode mode,
                      envsampler_kind sampler, error *err)
{
    memset(el, 0, sizeof *el);
    el->env = env;
    el->mode = mode;
    el->sampler = sampler;
    if (!env->present) return error_set(err, NULL, 0, "no environment map to sample");
    /* Directions see only the linear part A of to_env (mat4_dir drops the translation, the
     * envmap being at infinity).  A sampled direction d goes back to the world as A^T d / |A^T d|,
     * which is A^-1 d up to its length with the pdf unchanged exactly when A A^T = s^2 I.
     * Uniform sampling draws in the world and only looks the map up: any transform. */
    mat4 m = env->to_env;
    if (mode != ENVSAMPLING_UNIFORM && !transform_is_conformal(&m))
        return error_set(err, NULL, 0,
                         "the envmap's transform is not a rotation (nor a rotation times a uniform "
                         "scale), so it cannot be sampled as a light (put only 'rotate' before "
                         "'envmap', or use 'envsampling uniform')");
    el->map = env->img;
    if (!el->map) { /* another representation: resample it to lat-long once (no-op otherwise) */
        if (envmap_to_latlong(env, 0, 0, &el->converted, err))
            return error_prefix(err, "resampling the environment to lat-long for sampling");
        el->map = &el->converted;
    }
    int w = el->w = el->map->w, h = el->h = el->map->h;
    el->to_world = mat4_transpose(m);
    el->identity = 1; /* A = I: lookups and samples skip the matrix (a translation is no matter) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) el->identity &= m.m[i][j] == (i == j);
    el->cos_edge = malloc((size_t)(h + 1) * sizeof *el->cos_edge);
    el->row_omega = malloc((size_t)h * sizeof *el->row_omega);
    if (!el->cos_edge || !el->row_omega) {
        envlight_free(el);
        return error_set(err, NULL, 0, "out of memory for a %d-row map", h);
    }
    /* row r spans theta in [pi r / h, pi (r + 1) / h]: u = cos theta from 1 down to -1 */
    for (int r = 0; r <= h; r++) el->cos_edge[r] = r == 0 ? 1.0 : r == h ? -1.0 : cos(M_PI * r / h);
    for (int r = 0; r < h; r++) {
        /* STEP(cdf): the exact solid angle of a texel of row r, in the lecture's u = cos theta, v =
         * phi where d(omega) = du dv (slide 22 (Sampling General 2D Distributions)); cos_edge[r] is
         * u at the row's top edge. It weights each texel's probability and the map's power |L| */
        /* STUB: el->row_omega[r] = 4 * M_PI / ((double)w * h); */
        el->row_omega[r] = (el->cos_edge[r] - el->cos_edge[r + 1]) * 2 * M_PI / w;
        /* END STEP(cdf) */
    }
    return 0;
}

/* One pass over the texels: n_bad, the power |L| = sum L_avg dOmega and kappa, and, if energy
 * is given, each texel's weight for `mode` (column-major, outer = column = phi, inner = row):
 * the cdf's L_avg dOmega_r, so that p(c, r) = L_avg(c, r) dOmega_r / |L|, or PBRT's
 * L_avg sin(theta at the row centre) for cdf-sintheta (rows uniform in theta). */
static void measure_texels(envlight *el, envsampling_mode mode, double *energy)
{
    int w = el->w, h = el->h;
    double power = 0, second = 0;
    for (int r = 0; r < h; r++) {
        double om = texel_omega(el, r);
        double sin_c = sin(M_PI * (r + 0.5) / h);
        for (int c = 0; c < w; c++) {
            const float *p = image_px(el->map, c, r);
            for (int k = 0; k < 3; k++) el->n_bad += !(isfinite(p[k]) && p[k] >= 0);
            double L = rgb_avg(texel(el, c, r));
            power += L * om;      /* |L| = sum L_avg dOmega, in double */
            second += L * L * om; /* sum L_avg^2 dOmega, for kappa */
            if (energy)
                energy[(size_t)c * h + r] = L * (mode == ENVSAMPLING_CDF_SINTHETA ? sin_c : om);
        }
    }
    el->power = power;
    /* kappa = E[L^2] / E[L]^2 over uniform directions = (second / 4 pi) / (power / 4 pi)^2 */
    el->kappa = power > 0 ? 4 * M_PI * second / (power * power) : 1.0;
}

/* After build_rows: measure the map and build the tables `mode` samples by (a black map falls
 * back: cdf to uniform, median cut to equal strata).  On failure *el is freed. */
static int build_sampling(envlight *el, envsampling_mode mode, envsampler_kind sampler,
                          int mediancut_n, error *err)
{
    int w = el->w, h = el->h, status = 0;
    double *energy = NULL; /* uniform sampling needs only the power and kappa: no array */
    if (mode != ENVSAMPLING_UNIFORM) {
        energy = malloc((size_t)w * (size_t)h * sizeof *energy);
        if (!energy) {
            envlight_free(el);
            return error_set(err, NULL, 0, "out of memory for the sampling table of a %d x %d map",
                             w, h);
        }
    }
    measure_texels(el, mode, energy);
    if (!(el->power > 0)) {
        el->fell_back = 1; /* all black: nothing to importance sample */
        el->mode = mode == ENVSAMPLING_MEDIANCUT ? ENVSAMPLING_MEDIANCUT : ENVSAMPLING_UNIFORM;
    }
    if (el->mode == ENVSAMPLING_CDF || el->mode == ENVSAMPLING_CDF_SINTHETA) {
        status = distrib2d_init(&el->table, energy, w, h, err);
        if (!status && sampler == ENVSAMPLER_ALIAS) status = distrib2d_alias_build(&el->table, err);
    } else if (el->mode == ENVSAMPLING_MEDIANCUT) {
        if (el->fell_back)
            for (size_t i = 0; i < (size_t)w * h; i++) energy[i] = 1; /* equal strata */
        int n = mediancut_n > 0 ? mediancut_n : MEDIANCUT_DEFAULT_LIGHTS;
        status = build_mediancut(el, energy, n, err);
    }
    free(energy);
    if (status) envlight_free(el);
    return status;
}

/* The bytes build_rows keeps for env: a map in another representation resampled to lat-long,
 * and the rows' tables.  *w, *h: the lat-long map it samples. */
static double lookup_bytes(const envmap *env, int *w, int *h)
{
    double keep = 0;
    if (env->img) {
        *w = env->img->w;
        *h = env->img->h;
    } else { /* resampled to lat-long first (envmap_to_latlong at its default width) */
        convert_env v = envmap_view(env);
        *w = convert_default_width(&v, CONVERT_LATLONG);
        *h = *w / 2 > 1 ? *w / 2 : 1;
        keep += (double)*w * *h * IMAGE_TEXEL_BYTES;
    }
    return keep + (2.0 * *h + 1) * sizeof(double); /* cos_edge, row_omega */
}

/* The bytes envlight_build keeps for env in `mode` (*tables of them for the sampling tables
 * alone), and in *scratch the most it holds only while building: the energy of every texel and
 * median cut's summed-area table. */
static double sampling_bytes(const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                             int n_lights, int *w, int *h, double *tables, double *scratch)
{
    double keep = lookup_bytes(env, w, h);
    *tables = *scratch = 0;
    if (mode == ENVSAMPLING_UNIFORM) return keep;
    *scratch = (double)*w * *h * sizeof(double); /* the energy of each texel */
    if (mode == ENVSAMPLING_CDF || mode == ENVSAMPLING_CDF_SINTHETA) {
        *tables = distrib2d_bytes(*w, *h);
        if (sampler == ENVSAMPLER_ALIAS) *tables += distrib2d_alias_bytes(*w, *h);
    } else if (mode == ENVSAMPLING_SIS) { /* the strata: sis_envlight_build charges its own */
    } else { /* median cut: the summed-area table and the regions; the points and their choice */
        int n = n_lights > 0 ? n_lights : MEDIANCUT_DEFAULT_LIGHTS;
        *scratch += mediancut_scratch_bytes(*w, *h, n);
        *tables = mediancut_bytes(n);
    }
    return keep + *tables;
}

int envlight_build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                   int mediancut_n, budget *mem, error *err)
{
    memset(el, 0, sizeof *el);
    if (!env->present) return error_set(err, NULL, 0, "no environment map to sample");
    int w, h;
    double tables, scratch;
    double keep = sampling_bytes(env, mode, sampler, mediancut_n, &w, &h, &tables, &scratch);
    const char *what = mode != ENVSAMPLING_UNIFORM ? "sampling tables" : "lookup tables";
    if (budget_charge(mem, keep + scratch, NULL, 0, err, "%s for a %d x %d lat-long map", what, w,
                      h))
        return -1;
    clock_t t0 = clock();
    int rc = build_rows(el, env, mode, sampler, err);
    if (!rc) rc = build_sampling(el, mode, sampler, mediancut_n, err);
    el->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    /* a black map falls back to uniform directions: its cdf tables were never built */
    double unused = rc ? keep : el->fell_back && el->mode == ENVSAMPLING_UNIFORM ? tables : 0;
    budget_release(mem, scratch + unused);
    return rc;
}

int envlight_build_lookup(envlight *el, const envmap *env, budget *mem, error *err)
{
    memset(el, 0, sizeof *el);
    if (!env->present) return error_set(err, NULL, 0, "no environment map to sample");
    int w, h;
    double keep = lookup_bytes(env, &w, &h);
    if (budget_charge(mem, keep, NULL, 0, err, "lookup tables for a %d x %d lat-long map", w, h))
        return -1;
    clock_t t0 = clock();
    int rc = build_rows(el, env, ENVSAMPLING_UNIFORM, ENVSAMPLER_BINARY, err);
    el->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    budget_release(mem, rc ? keep : 0);
    return rc;
}

void envlight_free(envlight *el)
{
    distrib2d_free(&el->table);
    distrib1d_free(&el->point_choice);
    if (el->strata_free) el->strata_free(el->strata);
    el->strata = NULL;
    el->strata_free = NULL;
    free(el->points);
    image_free(&el->converted);
    el->map = NULL;
    free(el->cos_edge);
    free(el->row_omega);
    el->points = NULL;
    el->cos_edge = el->row_omega = NULL;
    el->n_points = 0;
}

/* The cdf mode's pdf of texel (c, r): p(omega) = p(c, r) / dOmega_r with
 * p(c, r) = L_avg dOmega_r / |L|, so p(omega) = L_avg(c, r) / |L|, "the pdf cancels the light".
 * Computed from the texel rather than as the table's pmf / dOmega (the same number up to the
 * CDF's rounding, distrib.h), alike by sampling and lookup so that they agree to the last bit. */
static inline double cdf_pdf(const envlight *el, int c, int r)
{
    return rgb_avg(texel(el, c, r)) / el->power;
}

/* cdf-sintheta's density of a direction at sin theta in a texel of probability pmf:
 * p(omega) = p(theta, phi) / sin theta, p(theta, phi) = p(c, r) W H / (2 pi^2) */
static inline double sintheta_pdf(const envlight *el, double pmf, double sin_t)
{
    return pmf * el->w * el->h / (2 * M_PI * M_PI * sin_t);
}

/* envmap frame -> world for sampled directions: A^T d / |A^T d|, which is A^-1 d / |A^-1 d| for
 * the linear part A of to_env, A A^T = s^2 I (envlight_build; the inverse of a rotation is its
 * transpose) */
static inline vec3 frame_to_world(const envlight *el, vec3 d)
{
    return el->identity ? d : vec3_normalize(mat4_dir(&el->to_world, d));
}

double envlight_pdf(const envlight *el, vec3 wi)
{
    int c, r;
    double sin_t;
    switch (el->mode) {
    case ENVSAMPLING_UNIFORM: return 1 / (4 * M_PI);
    case ENVSAMPLING_CDF:
        if (world_to_texel(el, wi, &c, &r, NULL)) return 0;
        return cdf_pdf(el, c, r);
    case ENVSAMPLING_CDF_SINTHETA:
        if (world_to_texel(el, wi, &c, &r, &sin_t) || !(sin_t > 0)) return 0;
        return sintheta_pdf(el, distrib2d_pmf(&el->table, c, r), sin_t);
    default: return 0; /* median cut has no density */
    }
}

rgb envlight_radiance_pdf(const envlight *el, vec3 wi, double *pdf)
{
    int c, r;
    double sin_t = 0;
    *pdf = 0;
    /* sin theta only where the pdf needs it (cdf-sintheta): a sin() call a lookup otherwise */
    double *want_sin = el->mode == ENVSAMPLING_CDF_SINTHETA ? &sin_t : NULL;
    if (!el->env->present || world_to_texel(el, wi, &c, &r, want_sin)) return rgb_gray(0);
    switch (el->mode) {
    case ENVSAMPLING_UNIFORM: *pdf = 1 / (4 * M_PI); break;
    case ENVSAMPLING_CDF: {
        rgb L = texel(el, c, r); /* one read for L and cdf_pdf */
        *pdf = rgb_avg(L) / el->power;
        return L;
    }
    case ENVSAMPLING_CDF_SINTHETA:
        if (sin_t > 0) *pdf = sintheta_pdf(el, distrib2d_pmf(&el->table, c, r), sin_t);
        break;
    default: break; /* median cut: no density */
    }
    return texel(el, c, r);
}

/* uniform directions on the sphere, pdf = 1 / (4 pi): in the world, as in any frame */
static int sample_uniform(const envlight *el, double xi1, double xi2, envlight_sample_result *out)
{
    out->wi = sampling_uniform_sphere(xi1, xi2);
    out->pdf = 1 / (4 * M_PI);
    out->L = envlight_radiance(el, out->wi);
    return 1;
}

/* cdf-sintheta (PBRT): a point uniform in theta inside texel (c, r) of probability pmf.  rr = 0
 * in a lit row 0 would give theta = 0, where sin theta = 0 and the density is infinite: start
 * ENVLIGHT_POLE_REM of a row inside it (a set of probability 1e-9 moved by 1e-9 of a row) */
static int point_in_texel_sintheta(const envlight *el, int c, int r, double pmf, double rc,
                                   double rr, envlight_sample_result *out)
{
    double phi = 2 * M_PI * (c + rc) / el->w;
    double theta = M_PI * (r + fmax(rr, ENVLIGHT_POLE_REM)) / el->h;
    double sin_t = sin(theta);
    out->wi = frame_to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos(theta)));
    out->L = texel(el, c, r);
    out->pdf = sin_t > 0 ? sintheta_pdf(el, pmf, sin_t) : 0;
    return out->pdf > 0;
}

/* The lecture's point in the chosen texel (c, r): uniform in u = cos theta and in phi, where
 * d(omega) = du dphi, so pdf(omega) = p(c, r) / dOmega_r = L_avg(c, r) / |L|: the pdf cancels
 * the light.  (rc, rr) are the samples remapped to [0, 1) inside the cell. */
static int point_in_texel(const envlight *el, int c, int r, double rc, double rr,
                          envlight_sample_result *out)
{
    double phi = 2 * M_PI * (c + rc) / el->w;                                  /* v = phi */
    double u = el->cos_edge[r] + rr * (el->cos_edge[r + 1] - el->cos_edge[r]); /* u = cos theta */
    double sin_t = sqrt(fmax(0.0, 1 - u * u));
    out->wi = frame_to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), u));
    out->L = texel(el, c, r);
    out->pdf = rgb_avg(out->L) / el->power; /* p(omega) = L_avg / |L| (cdf_pdf) */
    return out->pdf > 0;
}

int envlight_sample(const envlight *el, double xi1, double xi2, envlight_sample_result *out)
{
    if (el->mode == ENVSAMPLING_UNIFORM) return sample_uniform(el, xi1, xi2, out);
    if (el->mode != ENVSAMPLING_CDF && el->mode != ENVSAMPLING_CDF_SINTHETA) return 0;
    /* slide 23 (How to Sample 2D Distribution): the column (phi) from the marginal CDF, then the
     * row (u = cos theta) from the column's conditional CDF; alias tables pick the same cells in
     * O(1) */
    int c, r;
    double pmf, rc, rr;
    if (el->sampler == ENVSAMPLER_ALIAS)
        distrib2d_sample_alias(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr);
    else
        distrib2d_sample(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr);
    if (el->mode == ENVSAMPLING_CDF_SINTHETA)
        return point_in_texel_sintheta(el, c, r, pmf, rc, rr, out);
    return point_in_texel(el, c, r, rc, rr, out);
}

int envlight_sample_stratified(const envlight *el, double xi1, double xi2,
                               envlight_sample_result *out)
{
    if (el->mode == ENVSAMPLING_UNIFORM) return sample_uniform(el, xi1, xi2, out);
    if (el->mode != ENVSAMPLING_CDF && el->mode != ENVSAMPLING_CDF_SINTHETA) return 0;
    int c, r;
    double pmf, rc, rr;
    distrib2d_sample(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr); /* inversion keeps strata */
    if (el->mode == ENVSAMPLING_CDF_SINTHETA)
        return point_in_texel_sintheta(el, c, r, pmf, rc, rr, out);
    return point_in_texel(el, c, r, rc, rr, out);
}

int envlight_mediancut_pick(const envlight *el, double xi, double xi1, double xi2, int *k,
                            vec3 *shadow_dir, double *prob)
{
    if (el->n_points == 0) return 0;
    double pmf;
    int i = distrib1d_sample(&el->point_choice, xi, &pmf, NULL); /* a light by its power */
    vec3 d = mediancut_jitter(&el->points[i], el->w, el->cos_edge, xi1, xi2);
    *shadow_dir = frame_to_world(el, d);
    *k = i;
    *prob = pmf;
    return pmf > 0;
}

int envlight_transform_is_conformal(const mat4 *m) { return transform_is_conformal(m); }

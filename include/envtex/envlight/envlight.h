/* envlight.h - the environment as a light (slides 16-23 (Environment Maps Generally)).  The
 * lecture's cdf mode: texel (c, r) by its 2D CDF (distrib.h), p = L_avg dOmega_r / |L|, then a
 * point uniform in (u = cos theta, v = phi), d(omega) = du dv: pdf = L_avg / |L|.  Also uniform,
 * cdf-sintheta, mediancut, sis (sis.h).
 *
 *     if (envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, &mem, &err)) ...
 *     if (envlight_sample(&el, xi1, xi2, &s)) ... s.wi, s.L, s.pdf ...
 *     envlight_free(&el);
 *
 * Conventions: unit world directions, tables in the envmap frame; L_avg: the channels' mean;
 * bad channels (NaN, Inf, < 0) read as 0.  A black map falls back (fell_back) to uniform
 * (mediancut: equal texel counts).  Other kinds are resampled to lat-long, sampled and lit.
 */
#ifndef ENVTEX_ENVLIGHT_H
#define ENVTEX_ENVLIGHT_H

#include "envtex/core/budget.h"
#include "envtex/envlight/distrib.h"
#include "envtex/envlight/mediancut.h"
#include "envtex/reflection/envmap.h"

/* `envsampling MODE [N]` */
typedef enum envsampling_mode {
    ENVSAMPLING_UNIFORM,
    ENVSAMPLING_CDF, /* the default */
    ENVSAMPLING_CDF_SINTHETA,
    ENVSAMPLING_MEDIANCUT,
    ENVSAMPLING_SIS /* built by sis_envlight_build (sis.h); envlight_build makes the shared part */
} envsampling_mode;
/* `envsampler binary|alias` */
typedef enum envsampler_kind { ENVSAMPLER_BINARY, ENVSAMPLER_ALIAS } envsampler_kind;

typedef struct envlight {
    const envmap *env;
    const image *map; /* env->img, or `converted` (owned) for other kinds */
    image converted;
    envsampling_mode mode;
    envsampler_kind sampler;
    int w, h;
    distrib2d table;   /* cdf modes: outer = columns (phi), inner = rows */
    double power;      /* |L| = sum of L_avg dOmega (after scale) */
    double kappa;      /* 4 pi sum L_avg^2 dOmega / |L|^2: 1 + uniform sampling's rel. variance */
    long n_bad;        /* NaN / Inf / negative texel channels */
    int fell_back;     /* the map was black */
    double *cos_edge;  /* h + 1: cos theta at the row edges */
    double *row_omega; /* h: a texel's solid angle per row */
    int identity;      /* to_env's linear part is I */
    mat4 to_world;     /* to_env transposed (normalize after it) */
    mediancut_point *points; /* mediancut: n_points lights, world directions */
    int n_points;
    distrib1d point_choice; /* mediancut, sis: a light by its power */
    void *strata;           /* sis: its shadow-ray tables (sis.h), owned, freed by strata_free */
    void (*strata_free)(void *strata);
    double build_seconds;
} envlight;

/* Build what `mode` samples by (mediancut_n lights, 0: the default); env must outlive el,
 * unchanged.  Table modes need to_env's linear part conformal (envlight_transform_is_conformal)
 * and refuse any other (-1, a message).  Charged to mem first (budget.h; NULL: none); the
 * scratch is released after.  On failure el is empty and nothing stays charged. */
int envlight_build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                   int mediancut_n, budget *mem, error *err);

/* A light looked up, never sampled (no next-event estimation): uniform, no pass over the
 * texels, so power, kappa, n_bad, fell_back stay 0 (keep it from lights_build, misfraction). */
int envlight_build_lookup(envlight *el, const envmap *env, budget *mem, error *err);
/* Free what el owns (not env); safe after a failed build. */
void envlight_free(envlight *el);

/* Texel (c, r) in [0, w) x [0, h) as the light sees it: scaled, bad channels as 0. */
rgb envlight_texel(const envlight *el, int c, int r);

/* Radiance from world direction wi: its texel (piecewise constant). */
rgb envlight_radiance(const envlight *el, vec3 wi);

typedef struct envlight_sample_result {
    vec3 wi;    /* world direction towards the environment */
    rgb L;      /* envlight_radiance(wi) */
    double pdf; /* per steradian, > 0 */
} envlight_sample_result;

/* A direction for (xi1, xi2) in [0,1)^2 by the light's sampler; 0 if none (median cut). */
int envlight_sample(const envlight *el, double xi1, double xi2, envlight_sample_result *out);

/* The same by CDF inversion whatever the sampler: it keeps strata, alias tables do not. */
int envlight_sample_stratified(const envlight *el, double xi1, double xi2,
                               envlight_sample_result *out);

/* The pdf per steradian that envlight_sample returns wi (0 for median cut). */
double envlight_pdf(const envlight *el, vec3 wi);

/* envlight_radiance(wi), and envlight_pdf(wi) in *pdf, from one lookup (MIS of a BRDF ray). */
rgb envlight_radiance_pdf(const envlight *el, vec3 wi, double *pdf);

/* mediancut: light *k with probability *prob = power_avg(k) / sum, and its shadow direction
 * jittered in its stratum (mediancut_jitter), xi, xi1, xi2 in [0,1). */
int envlight_mediancut_pick(const envlight *el, double xi, double xi1, double xi2, int *k,
                            vec3 *shadow_dir, double *prob);

/* 1 if m's linear part A has A A^T = s^2 I (a rotation, maybe scaled or mirrored) within a
 * tolerance: what table modes and `integrator prefiltered` ask of env->to_env. */
int envlight_transform_is_conformal(const mat4 *m);

#endif

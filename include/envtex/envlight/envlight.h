/* envlight.h - the environment as a light (lecture slides 16-23): "we effectively have millions
 * of lights: importance sample the environment map, extend next-event estimation to envmaps".
 *
 * The light is the lat-long map taken as piecewise constant: each texel (c, r) has radiance
 * L(c, r) over its solid angle dOmega_r = (cos theta_r - cos theta_{r+1}) 2 pi / W.  In the
 * lecture's parameterization u = cos theta, v = phi we have d(omega) = du dv, so a texel is a
 * rectangle in (u, v) and no sin theta appears anywhere.  Sampling modes (`envsampling`):
 *
 *   uniform       directions uniform on the sphere, pdf = 1 / (4 pi)
 *   cdf           p(c, r) = L_avg(c, r) dOmega_r / |L|, |L| = sum of L_avg dOmega (the power);
 *                 a marginal CDF over columns (phi), then a conditional CDF over rows within the
 *                 column; the direction is uniform in (cos theta, phi) inside the texel, so
 *                 pdf(omega) = p(c, r) / dOmega_r = L_avg(omega) / |L|: the pdf cancels the light
 *   cdf-sintheta  PBRT's way: weights L_avg sin(theta_r centre), rows uniform in theta:
 *                 pdf(omega) = p(c, r) W H / (2 pi^2 sin theta)
 *   mediancut N   the map cut into N strata of equal energy (Debevec 2005), each a point light
 *                 at its energy centroid carrying the stratum's whole power; only the shadow
 *                 ray is jittered inside the stratum (envlight_mediancut_*)
 *   sis N         the same kind of N point lights from structured importance sampling's
 *                 strata (Agarwal et al. 2003): sis_envlight_build and sis_pick (sis.h);
 *                 envlight_build in this mode makes only what every mode shares
 *
 * L_avg is the average of the colour channels, so a sample's estimate L_c / pdf =
 * |L| L_c / L_avg: exact for grey light, and coloured light still converges (the ratio
 * L_c / L_avg is bounded wherever L_avg > 0).  Texel channels that are NaN, Inf or
 * negative are counted (n_bad; a texel with three such channels counts 3) and treated as 0
 * everywhere, for lighting and sampling alike.  An all-black map falls back (fell_back): `cdf`
 * and `cdf-sintheta` to uniform sampling, `mediancut` to strata of equal texel counts
 * (render_scene warns through render_opts.warn).
 *
 * A map in another representation (cube map, mirror ball, ...) is first resampled to a lat-long
 * map (envmap_to_latlong, solid-angle averaged, at the default resolution), which is then both
 * sampled and used as the light, so sampling and lighting stay consistent.
 *
 *     envlight el;
 *     if (envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, &mem, &err)) ...
 *     envlight_sample_result s;
 *     if (envlight_sample(&el, xi1, xi2, &s)) ... s.wi, s.L, s.pdf ...
 *     double pdf = envlight_pdf(&el, wi);   // for MIS, of a direction found another way
 *     envlight_free(&el);
 */
#ifndef ENVTEX_ENVLIGHT_H
#define ENVTEX_ENVLIGHT_H

#include "envtex/core/budget.h"
#include "envtex/envlight/distrib.h"
#include "envtex/reflection/envmap.h"

/* `envsampling MODE [N]`: how the envmap is sampled as a light (envlight.h) */
typedef enum envsampling_mode {
    ENVSAMPLING_UNIFORM,      /* uniform directions on the sphere */
    ENVSAMPLING_CDF,          /* the lecture's 2D CDF in (u = cos theta, v = phi); default */
    ENVSAMPLING_CDF_SINTHETA, /* PBRT: rows uniform in theta, weights times sin theta */
    ENVSAMPLING_MEDIANCUT,    /* the map reduced to N point lights (median cut) */
    ENVSAMPLING_SIS           /* N point lights by structured importance sampling (sis.h) */
} envsampling_mode;
/* `envsampler binary|alias`: CDF inversion by binary search or Walker/Vose alias tables */
typedef enum envsampler_kind { ENVSAMPLER_BINARY, ENVSAMPLER_ALIAS } envsampler_kind;

typedef struct envlight_point {
    vec3 dir;        /* world-space unit direction of the stratum's energy centroid, taken in
                      * image coordinates (c, r) so that it lies inside the stratum */
    rgb power;       /* integral of L over the stratum (W/m^2 of irradiance at normal incidence) */
    int c0, c1, r0, r1; /* the stratum: columns [c0, c1), rows [r0, r1) */
} envlight_point;

typedef struct envlight {
    const envmap *env;
    const image *map;    /* the lat-long map sampled: env->img, or `converted` for other kinds */
    image converted;     /* a cube map, mirror ball... resampled to lat-long (owned); else empty */
    envsampling_mode mode;
    envsampler_kind sampler;
    int w, h;
    distrib2d table;     /* cdf and cdf-sintheta: outer = columns (phi), inner = rows */
    double power;        /* |L| = sum over texels of L_avg dOmega (after scale) */
    double kappa;        /* 4 pi sum L_avg^2 dOmega / |L|^2 >= 1: the second moment of L_avg over
                          * uniform directions relative to its mean squared; kappa - 1 is the
                          * relative variance of estimating the light with uniform directions
                          * (1 for a constant map, ~10^3 and more with a sun) */
    long n_bad;          /* NaN / Inf / negative texel channels found */
    int fell_back;       /* 1 if the map was black: sampling is uniform (median cut: equal strata) */
    double *cos_edge;    /* h + 1 entries: cos theta at the top edge of each row (and the bottom) */
    double *row_omega;   /* h entries: solid angle of one texel of each row */
    int identity;        /* the envmap transform is the identity: skip the matrix per sample */
    mat4 to_world;       /* envmap frame -> world: the transpose of env->to_env, whose linear part is
                          * a rotation times s (its translation is no matter); normalize after it */
    envlight_point *points; int n_points; /* mediancut */
    distrib1d point_choice; /* mediancut, sis: choose a point light by power */
    void *strata;           /* sis: its shadow-ray tables (sis.h), owned: freed by strata_free */
    void (*strata_free)(void *strata);
    double build_seconds;
} envlight;

/* Build the tables `mode` needs (nothing for uniform).  `mediancut_n` is used for mediancut.
 * The envmap must stay alive and unchanged while the envlight is used.  The envmap's transform
 * acts on directions by its linear part A only (a translation changes nothing).  The table
 * modes (cdf, cdf-sintheta, mediancut) need A A^T = s^2 I, a rotation, possibly times a uniform
 * scale or a mirror (sampled directions go back as A^T d, normalized): anything else, a
 * non-uniform scale or a shear, would distort the pdf and is refused (-1, a message).  Uniform
 * sampling takes any transform, as the background does.  What it builds is charged to `mem`
 * first (budget.h; NULL: none) and stays charged, its scratch released: a map in another
 * representation resampled to lat-long (12 bytes a texel), the energy of each texel while
 * building (8), the cdf tables (about 8, 16 with alias tables: distrib2d_bytes), median cut's
 * summed-area table while building (8). */
int envlight_build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                   int mediancut_n, budget *mem, error *err);

/* The light for an integrator that looks it up but never samples it as a light (a path tracer
 * without next-event estimation): mode uniform, and no measuring pass over the texels (a map in
 * another representation is still resampled to lat-long, which the lookups read), so power,
 * kappa, n_bad and fell_back stay 0 (a 1024 x 512 map's pass was 15% of the instructions of a
 * small 1-spp render).  envlight_radiance and uniform sampling work as after
 * envlight_build; whatever needs the power (lights_build, envlight_mis_fraction) must not be
 * given it. */
int envlight_build_lookup(envlight *el, const envmap *env, budget *mem, error *err);
void envlight_free(envlight *el);

/* Radiance arriving from world direction wi as the sampling integrators see it: the texel's
 * value (piecewise constant), scaled, bad texels as 0. */
rgb envlight_radiance(const envlight *el, vec3 wi);

typedef struct envlight_sample_result {
    vec3 wi;     /* world direction towards the environment */
    rgb L;       /* envlight_radiance(wi) */
    double pdf;  /* per steradian, > 0 */
} envlight_sample_result;

/* Sample a direction with (xi1, xi2) in [0,1)^2 (modes uniform, cdf, cdf-sintheta), by the
 * scene's sampler (binary search or alias tables).  Returns 0 if nothing can be sampled (never
 * for a valid table). */
int envlight_sample(const envlight *el, double xi1, double xi2, envlight_sample_result *out);

/* The same by CDF inversion whatever the sampler, for stratified (xi1, xi2): inversion is
 * monotone in each xi, so strata stay strata; the alias method shuffles them. */
int envlight_sample_stratified(const envlight *el, double xi1, double xi2,
                               envlight_sample_result *out);

/* pdf (per steradian) that envlight_sample returns wi. */
double envlight_pdf(const envlight *el, vec3 wi);

/* envlight_radiance(wi) and, in *pdf, envlight_pdf(wi), from one direction-to-texel lookup (what
 * MIS needs when a BRDF ray leaves the scene). */
rgb envlight_radiance_pdf(const envlight *el, vec3 wi, double *pdf);

/* How often MIS should sample this map: the fraction c of its picks (lights.h) that minimizes
 * variance x time for a model surface, c in {0, 1/32, 1/16, 1/8, 1/4, 1/2, 3/4, 1}.
 * The model: diffuse surfaces (albedo 1) facing 64 normals spread over the sphere, lit by the
 * map reduced to at most ENVLIGHT_MIS_GRID_W x _H cells of mean radiance; per vertex one cosine
 * (BRDF) sample plus, with probability c, one cdf light sample, combined as 1 + c samples of the
 * mixture p_m = (p_brdf + c p_light) / (1 + c) (what the balance heuristic approaches):
 *     relative variance V(c) = (integral g^2 / p_m / I^2 - 1) / (1 + c),  g = L cos+ / pi,
 * averaged over the normals, and time per vertex 1 + light_cost c (a light sample costs
 * light_cost of a BRDF sample's ray and shading).  A constant map gives c = 0 (cosine sampling
 * has no variance there); a sun gives c = 1 (V grows like 1/c).  For the cdf modes
 * (cdf-sintheta's pdf is modelled as the cdf's); uniform and median cut return 1.
 * rel_var_out, if given, receives V for each c (ENVLIGHT_MIS_FRACTIONS values).  Reads every
 * texel once, allocates nothing. */
#define ENVLIGHT_MIS_GRID_W 64
#define ENVLIGHT_MIS_GRID_H 32
#define ENVLIGHT_MIS_FRACTIONS 8
double envlight_mis_fraction(const envlight *el, double light_cost, double *rel_var_out);

/* mediancut and sis: pick point light k with probability power_avg(k) / sum (xi in [0,1)); the
 * shadow direction is jittered inside its stratum with (xi1, xi2) (median cut's rectangles;
 * sis_pick for sis).  *prob = the pick probability. */
int envlight_mediancut_pick(const envlight *el, double xi, double xi1, double xi2, int *k,
                            vec3 *shadow_dir, double *prob);

/* 1 if the linear part A (upper 3 x 3) of m turns directions without distorting them,
 * A A^T = s^2 I within a tolerance: a rotation, possibly times a uniform scale or a mirror, what
 * the sampling modes ask of env->to_env (and `integrator prefiltered`, whose maps live in the
 * envmap frame). */
int envlight_transform_is_conformal(const mat4 *m);

#endif

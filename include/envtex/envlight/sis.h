/* sis.h - structured importance sampling (slides 18-20 (Structured Importance Sampling): "reduce
 * the environment to point lights"; Agarwal et al. 2003), `envsampling sis N`.
 *
 *     sis_strata s;  // lum: w * h luminances, row-major; s.label[r * w + c]: a texel's stratum
 *     if (sis_stratify(lum, w, h, 64, NULL, &s, &err)) ...   else ... sis_strata_free(&s);
 *
 * Importance Gamma = E^a Omega^b; layer i holds the texels with L >= i sigma; a connected
 * region R gets floor(N Gamma_R / Gamma_4pi) samples, placed farthest-point; each texel joins
 * its nearest sample's stratum (docs/sis.md).  A stratum lights as a point light at its energy
 * centroid with its power; only the shadow ray is jittered inside it.
 * Frame and texels as latlong.h (row 0 the zenith); texels are adjacent across the phi seam,
 * and all of row 0 (of row H - 1) meet at the pole.
 */
#ifndef ENVTEX_SIS_H
#define ENVTEX_SIS_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/envlight/envlight.h"

#define SIS_A          1.0  /* Gamma = E^a Omega^b: the exponent of the energy */
#define SIS_B          0.25 /* ... and of the solid angle */
#define SIS_MAX_LAYERS 16   /* thresholds t_0 .. t_15 at most */
#define SIS_MAX_LIGHTS 4096 /* `envsampling sis N`: N in [1, SIS_MAX_LIGHTS] */

typedef struct sis_strata {
    int w, h;        /* the lat-long map */
    int n;           /* strata made: N, or the texel count if fewer */
    int *label;      /* w * h, row-major: the stratum of each texel, in [0, n) (owned) */
    int *seed;       /* n texel indices r * w + c: the samples, in the order placed (owned) */
    int *seed_layer; /* n: the layer that placed each (owned) */
    int n_layers;    /* d: thresholds t_0 .. t_{d-1} */
    double sigma;    /* standard deviation of L over the sphere */
    double threshold[SIS_MAX_LAYERS]; /* t_i = i sigma */
    int regions[SIS_MAX_LAYERS];      /* connected regions of each layer */
    int layer_total[SIS_MAX_LAYERS];  /* sum of each layer's n_R */
    int layer_new[SIS_MAX_LAYERS];    /* samples each layer placed itself */
    double gamma_4pi;                 /* Gamma of the whole map */
    double radius;                    /* largest angle (radians) from a texel to its sample */
} sis_strata;

/* Stratify the w x h lat-long luminance `lum` (row-major, finite, >= 0) into n in [1, w h]
 * strata, charged to `mem` first (NULL: none; the scratch is released after).  0, or -1 with
 * *err (a black map, bad n, memory) and *out empty (safe to free). */
int sis_stratify(const double *lum, int w, int h, int n, budget *mem, sis_strata *out, error *err);
void sis_strata_free(sis_strata *s);
/* The bytes sis_stratify keeps, and holds while it runs. */
double sis_strata_bytes(int w, int h, int n);
double sis_scratch_bytes(int w, int h, int n);

/* The channels' average times scale (NaN, Inf, negatives: 0) of a lat-long image, w * h doubles
 * row-major, malloc'd (NULL: no memory). */
double *sis_luminance(const image *map, double scale);

/* The envmap as `envsampling sis n` (n < 1: 64): envlight_build's shared tables, the strata's
 * point lights in el->points (n, or fewer texels), el->point_choice by power, the shadow-ray
 * tables in el->strata.  A black map falls back as envlight_build says.  Charged to `mem`
 * first.  0, or -1 with *err and *el freed.  Free with envlight_free. */
int sis_envlight_build(envlight *el, const envmap *env, envsampler_kind sampler, int n, budget *mem,
                       error *err);
double sis_envlight_bytes(int w, int h, int n);
double sis_envlight_scratch_bytes(int w, int h, int n);

/* Light k with probability *prob = power_avg(k) / sum (xi in [0, 1)) and its shadow direction
 * sis_shadow_dir(el, k, xi1, xi2); 0 if there is nothing to pick. */
int sis_pick(const envlight *el, double xi, double xi1, double xi2, int *k, vec3 *shadow_dir,
             double *prob);

/* The world direction of a shadow ray towards light k: a texel of stratum k by energy (xi1),
 * then uniform in (cos theta, phi) inside it (the rest of xi1, and xi2); xi in [0, 1). */
vec3 sis_shadow_dir(const envlight *el, int k, double xi1, double xi2);

/* The paper's figure: s's map (times `scale`), strata boundaries `edge`, a 3 x 3 `mark` on each
 * sample, into *out (free with image_free).  0, or -1 with *err (memory). */
int sis_strata_picture(const sis_strata *s, const image *map, double scale, rgb edge, rgb mark,
                       image *out, error *err);

#endif

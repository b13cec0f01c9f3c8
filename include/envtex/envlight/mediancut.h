/* mediancut.h - Debevec's median cut (slides 18-21 (Structured Importance Sampling), structured
 * importance sampling): the map cut into N strata of equal energy, each a point light; shadow rays
 * jittered in the stratum.
 *
 *     mediancut_map m = {&img, scale, energy, row_omega};      // energy: L_avg dOmega
 *     if (mediancut_build(&m, 64, &pts, &n, &choice, &err)) ...
 *     vec3 d = mediancut_jitter(&pts[k], img.w, cos_edge, xi1, xi2);
 *
 * Conventions: unit directions, envmap frame; texel (c, r): column (phi), row (theta) of a
 * w x h map; energy[c h + r].
 */
#ifndef ENVTEX_MEDIANCUT_H
#define ENVTEX_MEDIANCUT_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"
#include "envtex/envlight/distrib.h"

/* `envsampling mediancut` without N */
#define MEDIANCUT_DEFAULT_LIGHTS 64

/* The map: L(c, r) = scale x the texel, NaN, Inf and negative channels as 0 (as envlight.h). */
typedef struct mediancut_map {
    const image *img; /* w x h, borrowed */
    double scale;
    const double *energy;    /* w h weights >= 0: what the cuts halve */
    const double *row_omega; /* h: a texel's solid angle in row r */
} mediancut_map;

typedef struct mediancut_point {
    vec3 dir;   /* the L_avg dOmega centroid in (c, r) (a black stratum: its centre) */
    rgb power;  /* integral of L dOmega over the stratum */
    int c0, c1; /* the stratum: columns [c0, c1), rows [r0, r1) */
    int r0, r1;
} mediancut_point;

/* Halve the most energetic stratum across its longer side in angle until there are n_lights
 * >= 1 or none splits.  The caller frees *points (free) and *choice (distrib1d_free; by
 * power_avg).  -1 out of memory: *points NULL, *n_points 0, *choice empty. */
int mediancut_build(const mediancut_map *m, int n_lights, mediancut_point **points, int *n_points,
                    distrib1d *choice, error *err);

/* The bytes mediancut_build holds while building, and returns. */
double mediancut_scratch_bytes(int w, int h, int n_lights);
double mediancut_bytes(int n_lights);

/* The shadow ray in stratum pt, uniform in (cos theta, phi) for (xi1, xi2) in [0,1)^2;
 * cos_edge: cos theta at the h + 1 row edges. */
vec3 mediancut_jitter(const mediancut_point *pt, int w, const double *cos_edge, double xi1,
                      double xi2);

#endif

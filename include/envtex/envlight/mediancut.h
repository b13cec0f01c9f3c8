/* mediancut.h - Debevec's median cut (lecture slides 18-21, structured importance sampling): the
 * lat-long map cut into N strata of equal energy, each a point light at its energy centroid that
 * carries the stratum's whole power; only the shadow ray is jittered inside the stratum.
 *
 *     mediancut_map m = {&img, scale, energy, row_omega};      // energy: L_avg dOmega
 *     mediancut_point *pts; int n; distrib1d choice;
 *     if (mediancut_build(&m, 64, &pts, &n, &choice, &err)) ...
 *     int k = distrib1d_sample(&choice, xi, &prob, NULL);      // a light by its power
 *     vec3 d = mediancut_jitter(&pts[k], img.w, cos_edge, xi1, xi2); // its shadow ray
 *     free(pts); distrib1d_free(&choice);
 *
 * Conventions: directions are unit vectors in the envmap frame (latlong.h: +z up, theta from +z);
 * texel (c, r) is column c (phi) and row r (theta) of a w x h map; energies are column-major,
 * energy[c h + r].  envlight.h builds this for `envsampling mediancut N`.
 */
#ifndef ENVTEX_MEDIANCUT_H
#define ENVTEX_MEDIANCUT_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"
#include "envtex/envlight/distrib.h"

/* The number of point lights when the scene names none (`envsampling mediancut`). */
#define MEDIANCUT_DEFAULT_LIGHTS 64

/* The map median cut reads: radiance L(c, r) = scale x the texel, its NaN, Inf and negative
 * channels read as 0 (as envlight.h reads them). */
typedef struct mediancut_map {
    const image *img;        /* the lat-long map, w x h texels; borrowed */
    double scale;            /* radiance per texel value */
    const double *energy;    /* w h weights >= 0, energy[c h + r]: what the cuts halve */
    const double *row_omega; /* h: the solid angle of one texel of row r */
} mediancut_map;

typedef struct mediancut_point {
    vec3 dir;   /* unit direction of the stratum's energy centroid, taken in image coordinates
                 * (c, r) so that it lies inside the stratum; envmap frame from mediancut_build
                 * (envlight.h turns it to the world) */
    rgb power;  /* integral of L over the stratum (W/m^2 of irradiance at normal incidence) */
    int c0, c1; /* the stratum's columns [c0, c1) */
    int r0, r1; /* and rows [r0, r1) */
} mediancut_point;

/* Cut the map into at most n_lights >= 1 strata: split the most energetic stratum in two halves
 * of (about) equal energy across its longer side measured in angle (the phi side shortened by
 * sin theta at its middle), until there are n_lights or nothing splits.  Each stratum becomes a
 * point light: power = sum of L dOmega, dir = the centroid of its texel centres weighted by
 * L_avg dOmega (a black stratum: its centre).  *points (free with free) and *choice (free with
 * distrib1d_free; picks light k with probability power_avg(k) / sum) are the caller's.  -1 if
 * memory runs out: *points is NULL, *n_points 0, *choice empty. */
int mediancut_build(const mediancut_map *m, int n_lights, mediancut_point **points,
                    int *n_points, distrib1d *choice, error *err);

/* The most bytes mediancut_build holds while building (its summed-area table and strata) for a
 * w x h map and n_lights, and those it returns (the points and their choice). */
double mediancut_scratch_bytes(int w, int h, int n_lights);
double mediancut_bytes(int n_lights);

/* The shadow ray's direction in stratum pt, uniform in (cos theta, phi) over it with (xi1, xi2)
 * in [0,1)^2: cos theta between cos_edge[r0] and cos_edge[r1], phi = 2 pi (c0 + xi2 (c1 - c0)) / w.
 * cos_edge: h + 1 entries, cos theta at the top edge of each row (and the bottom).  Envmap
 * frame, unit. */
vec3 mediancut_jitter(const mediancut_point *pt, int w, const double *cos_edge, double xi1,
                      double xi2);

#endif

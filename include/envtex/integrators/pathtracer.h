/* pathtracer.h - `integrator pathtracer` (CSE 168 hw3-hw4, lecture slides 16-23).
 *
 * Paths start at the camera and bounce with `importancesampling hemisphere|cosine|brdf`.
 * A path of k bounces that reaches a light (a quad light or, leaving the scene, the envmap)
 * carries L = Le prod (f cos / pdf).  `maxdepth` d allows paths of at most d bounces
 * (-1: unlimited, though never past INTEGRATOR_UNLIMITED_DEPTH = 1000, with `russianroulette on`
 * to end them: survival probability = the largest component of the throughput, clamped to 1;
 * without roulette a path whose throughput is 0, after a black surface, ends too, as nothing
 * further along can add to it).  `nexteventestimation`:
 *   off  light is found only by hitting it;
 *   on   at every non-delta bounce the direct light by light sampling, direct_lighting (direct.h:
 *        `lightsamples` samples of every light under `lightselection all`, the default; of a
 *        light picked by power each under `power`); hitting a light after a non-delta bounce adds
 *        nothing, so no path is counted twice;
 *   mis  both, weighted by the power heuristic (beta = 2), for quad lights and the envmap: a
 *        light sample by direct_lighting_mis, a BRDF ray that finds light k against
 *        lightsamples x lights_selection_prob(k) x pdf_k (lights.h), whichever the selection.
 * All three converge to the same image (tested).  Geometry with `emission` is not sampled as a
 * light and always counts when hit.  Both strategies see only directions above the geometric
 * surface (ng . wi > 0): a diffuse or glossy sample that an interpolated or bumped normal sends
 * below it ends the path, as light sampling sends no shadow ray there.
 */
#ifndef ENVTEX_PATHTRACER_H
#define ENVTEX_PATHTRACER_H

#include "envtex/integrators/integrator.h"

rgb pathtracer_radiance(integrator *it, ray r, rng *g);
/* ... with the camera ray's differentials rd (NULL: none), carried through perfect mirror and
 * glass bounces; after the first diffuse or glossy bounce the path has none (raydiff.h). */
rgb pathtracer_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

#endif

/* pathtracer.h - `integrator pathtracer` (CSE 168 hw3-hw4, slides 16-23): paths from the camera
 * bounce by `importancesampling`; one that reaches a light carries L = Le prod (f cos / pdf).
 * `maxdepth` bounces at most (-1: INTEGRATOR_UNLIMITED_DEPTH, with `russianroulette on`:
 * survival = the throughput's largest component, at most 1; a zero throughput ends a path).
 * `nexteventestimation`: off, light found by hitting it; on, direct_lighting at each non-delta
 * bounce (a light then hit adds nothing); mis, both by the power heuristic, the BRDF ray's pdf
 * against lightsamples x lights_selection_prob(k) x pdf_k.  All three converge alike (tested).
 * Emissive geometry always counts when hit.  Directions below ng end the path.
 */
#ifndef ENVTEX_PATHTRACER_H
#define ENVTEX_PATHTRACER_H

#include "envtex/integrators/integrator.h"

rgb pathtracer_radiance(integrator *it, ray r, rng *g);
/* ... with the camera ray's differentials (NULL: none), kept to the first non-delta bounce. */
rgb pathtracer_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

#endif

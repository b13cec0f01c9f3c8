/* pathtracer.h - `integrator pathtracer` (CSE 168 hw3-hw4, slides 16-23 (Environment Maps
 * Generally)): a path bounces by `importancesampling`, at most `maxdepth` times (-1: with
 * `russianroulette on`, survival = the throughput's largest component); reaching a light it carries
 * Le prod (f cos / pdf). `nexteventestimation on` adds direct_lighting at each non-delta bounce and
 * drops light then hit; `mis` weighs both by the power heuristic.  Emissive geometry counts when
 * hit; a direction below ng ends the path.  docs/design-notes.md.
 *
 *     rgb L = render_radiance(&it, camera_ray(&cam, x, y), &rng); // render.h calls
 *                                                                 // pathtracer_radiance_hit
 */
#ifndef ENVTEX_PATHTRACER_H
#define ENVTEX_PATHTRACER_H

#include "envtex/integrators/integrator.h"

/* Radiance along camera ray r from its first hit sh (integrator_intersect_diff's), the
 * differentials rd (NULL: none) kept to the first non-delta bounce. */
rgb pathtracer_radiance_hit(integrator *it, ray r, const ray_diff *rd, const scene_hit *sh, rng *g);

#endif

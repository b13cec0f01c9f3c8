/* direct.h - `integrator direct` (CSE 168 hw2): direct lighting only.  At the first non-delta
 * hit:  L = Le + sum over lights of (1/N) sum_j f(wo, wi_j) cos(theta_j) Li(wi_j) V / pdf(wi_j)
 * with N = `lightsamples` samples per quad light and for the environment (sampled as
 * `envsampling` says; `lightstratify on`: a sqrt(N) x sqrt(N) grid), N = 1 for a point or
 * directional light (a delta: more samples would all be the same).  Perfect mirror and glass
 * surfaces are followed (up to maxdepth bounces) to the first surface that can be lit.
 */
#ifndef ENVTEX_DIRECT_H
#define ENVTEX_DIRECT_H

#include "envtex/integrator.h"

rgb direct_radiance(integrator *it, ray r, rng *g);
/* ... with the camera ray's differentials rd (NULL: none), carried through mirrors and glass. */
rgb direct_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

/* Estimate of the direct light s reflects towards wo, from every light: the sum above without
 * Le.  Shared with analytic tests. */
rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g);

#endif

/* perlin.h - Perlin's Improved Noise (SIGGRAPH 2002) and the solid textures made from it:
 * fbm, turbulence, marble, wood.  Slides 44-46.
 *
 *     double n = perlin_noise(p.x, p.y, p.z);                 // about [-1, 1]
 *     double f = perlin_fbm(p, 6, 2.0, 0.5);                  // 6 octaves
 *     double m = perlin_marble(p, 4.0, 8.0, 6);               // [0, 1]: lerp two colours by it
 *     double g = perlin_fbm_filtered(p, w, 6, 2.0, 0.5);      // w: the footprint at p
 *
 * perlin_noise is his reference implementation's to rounding (his permutation, fade
 * 6t^5 - 15t^4 + 10t^3, 12 edge gradients, his corner hash: docs/texture-mapping.md, section
 * 11), defined for any finite coordinate.  0 at lattice points, C2, |n| <= PERLIN_NOISE_BOUND.
 * Pure, thread-safe, allocation free.
 */
#ifndef ENVTEX_PERLIN_H
#define ENVTEX_PERLIN_H

#include "envtex/core/vec.h"

/* A bound on |perlin_noise| (tested; section 11 of docs/texture-mapping.md) */
#define PERLIN_NOISE_BOUND 1.05

/* E|noise(p)| over a period cube (tested; docs/design-notes.md) */
#define PERLIN_MEAN_ABS 0.2204

/* Octave counts are clamped to this (finer octaves are below the spacing of doubles) */
#define PERLIN_MAX_OCTAVES 30

/* Improved Noise, period 256 on each axis, finite for finite input; NaN or infinite: 0. */
double perlin_noise(double x, double y, double z);

/* fbm = sum_{i<octaves} gain^i noise(lacunarity^i p); octaves <= 0: 0. */
double perlin_fbm(vec3 p, int octaves, double lacunarity, double gain);

/* turbulence = sum_{i<octaves} gain^i |noise(lacunarity^i p)| >= 0. */
double perlin_turbulence(vec3 p, int octaves, double lacunarity, double gain);

/* Band-limited fbm; footprint: the filter's width at p, in p's units.  Octave i is weighted
 * a_i = 1 - smoothstep(1/2, 1, lacunarity^i footprint), the rest of it its mean 0: continuous
 * in footprint.  footprint <= 0 or NaN: perlin_fbm.  lacunarity > 1 (the first octave faded
 * out ends the sum). */
double perlin_fbm_filtered(vec3 p, double footprint, int octaves, double lacunarity, double gain);

/* Band-limited turbulence, as perlin_fbm_filtered with the mean PERLIN_MEAN_ABS. */
double perlin_turbulence_filtered(vec3 p, double footprint, int octaves, double lacunarity,
                                  double gain);

/* Marble in [0, 1]: 0.5 + 0.5 perlin_marble_veins(frequency p.x + amplitude
 * perlin_turbulence(p, octaves, 2, 0.5)), amplitude in radians per unit of turbulence. */
double perlin_marble(vec3 p, double frequency, double amplitude, int octaves);

/* sin(phase) for a finite phase; 0 (its mean) for an infinite or NaN one (an overflow). */
double perlin_marble_veins(double phase);

/* Wood about the y axis in [0, 1): frac(rings sqrt(p.x^2 + p.z^2) + amplitude noise(p)). */
double perlin_wood(vec3 p, double rings, double amplitude);

#endif

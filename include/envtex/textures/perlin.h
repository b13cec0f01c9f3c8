/* perlin.h - Perlin's Improved Noise (2002) and its solid textures: fbm, turbulence, marble,
 * wood (slides 45-46 (Solid textures)).
 *
 *     double n = perlin_noise(p.x, p.y, p.z);                 // about [-1, 1]
 *     double g = perlin_fbm_filtered(p, w, 6, 2.0, 0.5);      // w: the footprint at p
 *
 * perlin_noise is his reference code's to rounding (docs/texture-mapping.md, section 11):
 * 0 at lattice points, C2, |n| <= PERLIN_NOISE_BOUND.  Pure, thread-safe, allocation free.
 */
#ifndef ENVTEX_PERLIN_H
#define ENVTEX_PERLIN_H

#include "envtex/core/vec.h"

/* A bound on |perlin_noise| (tested) */
#define PERLIN_NOISE_BOUND 1.05

/* E|noise(p)| over a period cube (tested; docs/design-notes.md) */
#define PERLIN_MEAN_ABS 0.2204

/* Octave counts are clamped to this */
#define PERLIN_MAX_OCTAVES 30

/* Improved Noise, period 256 on each axis, finite for finite input; NaN or infinite: 0. */
double perlin_noise(double x, double y, double z);

/* fbm = sum_{i<octaves} gain^i noise(lacunarity^i p); octaves <= 0: 0. */
double perlin_fbm(vec3 p, int octaves, double lacunarity, double gain);

/* turbulence = sum_{i<octaves} gain^i |noise(lacunarity^i p)| >= 0. */
double perlin_turbulence(vec3 p, int octaves, double lacunarity, double gain);

/* fbm with octave i weighted 1 - smoothstep(1/2, 1, lacunarity^i footprint), the rest its mean
 * 0; footprint in p's units (<= 0 or NaN: perlin_fbm); lacunarity > 1. */
double perlin_fbm_filtered(vec3 p, double footprint, int octaves, double lacunarity, double gain);

/* Band-limited turbulence, as perlin_fbm_filtered with the mean PERLIN_MEAN_ABS. */
double perlin_turbulence_filtered(vec3 p, double footprint, int octaves, double lacunarity,
                                  double gain);

/* 0.5 + 0.5 perlin_marble_veins(frequency p.x + amplitude perlin_turbulence(p, octaves, 2,
 * 0.5)), in [0, 1]. */
double perlin_marble(vec3 p, double frequency, double amplitude, int octaves);

/* sin(phase) for a finite phase; 0 (its mean) for an infinite or NaN one (an overflow). */
double perlin_marble_veins(double phase);

/* Wood about the y axis in [0, 1): frac(rings sqrt(p.x^2 + p.z^2) + amplitude noise(p)). */
double perlin_wood(vec3 p, double rings, double amplitude);

#endif

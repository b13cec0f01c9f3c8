/* perlin.h - Ken Perlin's Improved Noise (SIGGRAPH 2002) and the solid textures built from it:
 * fractal sums (fbm), turbulence, marble and wood.  Lecture "Environment, Texture Maps", the
 * procedural (solid) texture slides 44-46: noise, turbulence, marble, wood.
 *
 *     double n = perlin_noise(p.x, p.y, p.z);                        // about [-1, 1]
 *     double f = perlin_fbm(p, 6, 2.0, 0.5);                        // 6 octaves
 *     double m = perlin_marble(p, 4.0, 8.0, 6);                     // [0, 1]
 *     rgb c = rgb_add(rgb_scale(vein, 1 - m), rgb_scale(stone, m)); // the caller picks colours
 *     // anti-aliased: w = width of the pixel's footprint at p, in the same (object) units as p
 *     double g = perlin_fbm_filtered(p, w, 6, 2.0, 0.5);
 *
 * perlin_noise agrees with Perlin's reference Java implementation
 * (https://mrl.nyu.edu/~perlin/noise/) to rounding, at every point.  It has the same
 * permutation p of 0..255 repeated twice, the fade curve 6t^5 - 15t^4 + 10t^3, the 12 edge
 * gradients of a cube (padded to 16 by hash & 15), and his hash of the cell's corners: with
 * (X, Y, Z) the cell, each mod 256, A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z,
 * B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z; the corner (i, j, k) takes the gradient
 * of p[AA], p[BA], p[AB], p[BB] for (0,0,0), (1,0,0), (0,1,0), (1,1,0), and of p[AA + 1],
 * p[BA + 1], p[AB + 1], p[BB + 1] for the same corners with k = 1.  (Any other hash would be as
 * random, but not his noise: the tests compare with his values.)  Unlike a literal
 * transcription it stays defined for any finite coordinate: the lattice cell is floor(x)
 * reduced modulo 256 in double, never an overflowing int.  Every function here is pure,
 * thread-safe and allocation free.
 *
 * The noise is 0 at every integer lattice point, continuous with continuous first and second
 * derivatives, and bounded by |n| <= PERLIN_NOISE_BOUND.
 */
#ifndef ENVTEX_PERLIN_H
#define ENVTEX_PERLIN_H

#include "envtex/core/vec.h"

/* A bound on |perlin_noise|.  Random points give |n| < 1; climbing to local maxima finds about
 * 1.017 (the 12 gradients have length sqrt 2, so "[-1, 1]" is only approximate).  The bound
 * leaves slack above that; the tests check it. */
#define PERLIN_NOISE_BOUND 1.05

/* E|noise(p)| over p uniform in a period cube, measured over 10^7 random points (0.22036,
 * standard error 5e-5); the tests re-measure it. */
#define PERLIN_MEAN_ABS 0.2204

/* Octave counts above this are clamped: 2^30 times the base frequency is below the spacing of
 * doubles for any coordinate worth texturing. */
#define PERLIN_MAX_OCTAVES 30

/* Improved Noise at (x, y, z).  Period 256 along each axis; 0 at integer lattice points; about
 * [-1, 1] (|n| <= PERLIN_NOISE_BOUND).  Finite input gives finite output (for |x| >= 2^52 the
 * coordinate is an integer and contributes a fraction of 0).  A NaN or infinite coordinate
 * returns 0. */
double perlin_noise(double x, double y, double z);

/* Fractal Brownian motion: sum_{i=0}^{octaves-1} gain^i noise(lacunarity^i p).
 * Typical: lacunarity 2, gain 0.5 (|fbm| < PERLIN_NOISE_BOUND * 1 / (1 - gain)).
 * octaves <= 0 gives 0; octaves > PERLIN_MAX_OCTAVES are clamped. */
double perlin_fbm(vec3 p, int octaves, double lacunarity, double gain);

/* Turbulence: sum_{i=0}^{octaves-1} gain^i |noise(lacunarity^i p)|, >= 0.  Same parameters. */
double perlin_turbulence(vec3 p, int octaves, double lacunarity, double gain);

/* Band-limited fbm (anti-aliased).  `footprint` is the width of the filter (a pixel's footprint)
 * at p, in the same units as p (object space).  Octave i has lattice frequency
 * f_i = lacunarity^i; its energy lies mostly between f_i / 4 and f_i, peaking near f_i / 2.
 * With samples `footprint` apart the Nyquist limit is 1 / (2 footprint), so octave i is weighted
 *     a_i = 1 - smoothstep(1/2, 1, f_i * footprint)
 * kept whole while its whole band is under the limit (f_i w <= 1/2), gone once its peak passes
 * it (f_i w >= 1), faded smoothly between: the result is continuous in footprint (no pop).
 * A faded octave is replaced by its mean, 0.  footprint <= 0 (or NaN) gives perlin_fbm.
 * Assumes lacunarity > 1: the first octave faded away entirely ends the sum (every later one is
 * finer), so with lacunarity < 1 a footprint >= 1 fades octave 0 and with it the coarser octaves
 * after it (the scene's textures use 2). */
double perlin_fbm_filtered(vec3 p, double footprint, int octaves, double lacunarity, double gain);

/* Band-limited turbulence: as perlin_fbm_filtered, but a faded octave is replaced by the mean
 * of |noise|, PERLIN_MEAN_ABS, so a distant turbulent surface keeps its average brightness. */
double perlin_turbulence_filtered(vec3 p, double footprint, int octaves, double lacunarity,
                                  double gain);

/* Marble: 0.5 + 0.5 sin(frequency * p.x + amplitude * turbulence(p)), in [0, 1],
 * with turbulence = perlin_turbulence(p, octaves, 2, 0.5).  The veins run across x with period
 * 2 pi / frequency; `amplitude` (radians per unit of turbulence) bends them.  Example:
 * frequency 4, amplitude 8, octaves 6.  Map to colours with a lerp or a colour ramp.  Where
 * the phase overflows, 0.5 (perlin_marble_veins). */
double perlin_marble(vec3 p, double frequency, double amplitude, int octaves);

/* The veins' profile at a marble phase (frequency * p.x + amplitude * turbulence): sin(phase),
 * or its mean 0 where the phase is infinite or NaN.  The parser accepts any finite frequency,
 * amplitude and scale, and their products overflow (1e200 * 1e200); veins that fine are far
 * below the spacing of doubles, so their mean is the only meaningful value (the one the filtered
 * marble fades them to).  Finite phases, however large, keep sin. */
double perlin_marble_veins(double phase);

/* Wood: rings about the y axis.  v = rings * sqrt(p.x^2 + p.z^2) + amplitude *
 * noise(p); returns the fraction v - floor(v), in [0, 1).  `rings` = rings per unit of radius;
 * `amplitude` (in rings) makes them wobble.  Example: rings 8, amplitude 0.5. */
double perlin_wood(vec3 p, double rings, double amplitude);

#endif

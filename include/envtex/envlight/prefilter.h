/* prefilter.h - illumination maps (slide 44 (Environment Maps), Miller & Hoffman 1984): the
 * environment convolved once with a lobe, so a diffuse or glossy surface is one lookup; irradiance
 * from 9 spherical harmonics (Ramamoorthi & Hanrahan 2001).  Figures: docs/illumination-maps.md.
 *
 *     if (prefilter_sh9_project(&env, &sh, &err)) ...          // env: convert.h, any kind
 *     rgb E = prefilter_sh9_irradiance(&sh, n);                 // E(n), n unit
 *     if (prefilter_irradiance_exact(&env, 64, &irr, &err)) ... // 64 x 32 map of E / pi
 *
 * Conventions: the envmap frame (+z up).  Sums sum_t L_t f(w_t) dOmega_t over the input's
 * texels at their centres (pulled onto a disc's rim), exact solid angles, in double.  Output:
 * lat-long W x W/2, texel centres, unscaled.  SH order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1)
 * (2,0) (2,1) (2,2); A_l = pi, 2 pi / 3, pi / 4.  Phong K(r, w) = (S + 1) max(0, r . w)^S / 2 pi.
 */
#ifndef ENVTEX_PREFILTER_H
#define ENVTEX_PREFILTER_H

#include "envtex/envmaps/convert.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* `prefilter exact|sh9` (`integrator prefiltered`) */
typedef enum irradiance_method { IRRADIANCE_EXACT, IRRADIANCE_SH9 } irradiance_method;

#define PREFILTER_SH9 9

#define PREFILTER_MAX_WIDTH     8192 /* output widths: even, in [2, this] */
#define PREFILTER_MAX_SHININESS 1e6  /* Phong exponents S: finite, in [0, this] */
/* The most input texels an exact map may visit in all (a map of rows; other kinds). */
#define PREFILTER_MAX_ROW_WORK  2e10
#define PREFILTER_MAX_LIST_WORK 3e9
/* prefilter_phong drops what adds at most this fraction of the mean radiance. */
#define PREFILTER_PHONG_DROP 1e-12

/* The 9 coefficients L_lm per channel (r, g, b), in the order above. */
typedef struct prefilter_sh9 {
    double L[PREFILTER_SH9][3];
} prefilter_sh9;

/* R&H's quadratic form per channel: E(n) = (n, 1)^T M (n, 1), M symmetric 4 x 4. */
typedef struct prefilter_sh9_quadratic {
    double m[3][4][4];
} prefilter_sh9_quadratic;

/* l and m of coefficient k in [0, 9) (-1 and 0 outside). */
int prefilter_sh9_l(int k);
int prefilter_sh9_m(int k);

/* The 9 basis functions at unit d = (x, y, z) into y: k0, k1 (y, z, x), k2 (xy, yz),
 * k20 (3 z^2 - 1), k2 xz, k22 (x^2 - y^2); k0 = 1 / (2 sqrt pi), k1 = sqrt(3 / 4 pi),
 * k2 = sqrt(15 / 4 pi), k20 = sqrt(5 / 16 pi), k22 = sqrt(15 / 16 pi). */
void prefilter_sh9_basis(vec3 d, double y[PREFILTER_SH9]);

/* L_lm = sum_t L_t Y_lm(w_t) dOmega_t into *out; fails (out zeroed) only out of memory. */
int prefilter_sh9_project(const convert_env *env, prefilter_sh9 *out, error *err);

/* E(n) = sum A_l L_lm Y_lm(n) at unit normal n. */
rgb prefilter_sh9_irradiance(const prefilter_sh9 *sh, vec3 n);

/* R&H's matrix form (their eq. 12; c1 = A2 k2 / 2, c2 = A1 k1 / 2, c3 = 3 A2 k20, c4 = A0 k0,
 * c5 = A2 k20) and its value at unit n: prefilter_sh9_irradiance to rounding. */
void prefilter_sh9_matrix(const prefilter_sh9 *sh, prefilter_sh9_quadratic *q);
rgb prefilter_sh9_quadratic_eval(const prefilter_sh9_quadratic *q, vec3 n);

/* 0 if width is even and in [2, PREFILTER_MAX_WIDTH], else -1 with a message. */
int prefilter_check_width(long width, error *err);

/* The map of E(n) / pi (a white Lambertian surface, unshadowed) into *out, width x width / 2
 * (free with image_free; empty on failure). */
int prefilter_irradiance_sh9(const prefilter_sh9 *sh, int width, image *out, error *err);

/* The exact map of E(n) / pi: prefilter_irradiance_arcs for a map of rows, else
 * prefilter_irradiance_brute, refused past PREFILTER_MAX_LIST_WORK.  Fails on a bad width or
 * out of memory; out as above. */
int prefilter_irradiance_exact(const convert_env *env, int width, image *out, error *err);

/* The plain sum over every pair of texels (no work limit). */
int prefilter_irradiance_brute(const convert_env *env, int width, image *out, error *err);

/* The same sum for a map of rows (lat-long, equal-area, cylindrical; -1 otherwise), O(1) per
 * input row from running sums over an arc of phi (prefilter.c). */
int prefilter_irradiance_arcs(const convert_env *env, int width, image *out, error *err);

/* The Phong-lobe map: texel r holds sum_t L_t K(r, w_t) dOmega_t without r . w_t <= c,
 * c^S = PREFILTER_PHONG_DROP / (2 (S + 1)).  Refused past the work limits; fails on a bad width
 * or S.  out as above. */
int prefilter_phong(const convert_env *env, double s, int width, image *out, error *err);

/* The plain Phong sum, nothing left out (no work limit). */
int prefilter_phong_brute(const convert_env *env, double s, int width, image *out, error *err);

/* The Phong map width for exponent S: the least power of two >= 4 pi sqrt(S) (two texels
 * across a lobe ~1 / sqrt(S) wide), clamped to [64, 1024]. */
int prefilter_phong_width(double s);

#endif

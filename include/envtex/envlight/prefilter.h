/* prefilter.h - illumination maps: the environment convolved once with a reflection lobe, so
 * that shading a diffuse or glossy surface is one lookup instead of an integral (lecture slide
 * 44, Miller & Hoffman 1984; slide 16: can an envmap render every effect?).  Irradiance needs
 * only 9 spherical-harmonic coefficients and is a quadratic polynomial of the normal
 * (Ramamoorthi & Hanrahan 2001).  docs/illumination-maps.md has the measurements.
 *
 *     prefilter_sh9 sh;
 *     if (prefilter_sh9_project(&env, &sh, &err)) ...        // env: convert.h, any kind
 *     rgb E = prefilter_sh9_irradiance(&sh, n);               // E(n), n unit, envmap frame
 *     image irr = {0}, glossy = {0};
 *     if (prefilter_irradiance_exact(&env, 64, &irr, &err)) ...     // 64 x 32 map of E / pi
 *     if (prefilter_phong(&env, 50, 256, &glossy, &err)) ...        // the Phong lobe, S = 50
 *     rgb Ld = latlong_lookup_bilinear(&irr, n);   // a white Lambertian surface facing n
 *     image_free(&irr); image_free(&glossy);
 *
 * Conventions.  Directions are in the envmap frame (+z up, latlong.h).  The sums are over the
 * input's own texels, each constant over its texel, at its centre direction, weighted by its
 * exact solid angle (convert_texel_solid_angle), in double:  sum_t L_t f(w_t) dOmega_t.  A disc
 * texel (mirror ball, angular map) whose centre is outside the disc but which holds some of it
 * is taken at its centre pulled onto the rim; texels of solid angle 0 are left out.  Output maps
 * are lat-long, W x W/2, texel (c, r) at its centre ((c + 0.5) / W, (r + 0.5) / H), in the
 * envmap frame, without any scale.  Real SH basis (R&H, +z up):  Y00 = 1 / (2 sqrt pi),
 * Y1-1 = k1 y, Y10 = k1 z, Y11 = k1 x (k1 = sqrt(3 / 4 pi)), Y2-2 = k2 xy, Y2-1 = k2 yz,
 * Y21 = k2 xz (k2 = sqrt(15 / 4 pi)), Y20 = sqrt(5 / 16 pi) (3 z^2 - 1),
 * Y22 = sqrt(15 / 16 pi) (x^2 - y^2); coefficients in that order, (0,0) (1,-1) (1,0) (1,1)
 * (2,-2) (2,-1) (2,0) (2,1) (2,2).  Irradiance E(n) = sum A_l L_lm Y_lm(n), A_0 = pi,
 * A_1 = 2 pi / 3, A_2 = pi / 4.  Phong lobe K(r, w) = (S + 1) / (2 pi) max(0, r . w)^S, whose
 * integral over the sphere is 1 (S = 0: the hemisphere around r, 1 / (2 pi)).
 */
#ifndef ENVTEX_PREFILTER_H
#define ENVTEX_PREFILTER_H

#include "envtex/envmaps/convert.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* `prefilter exact|sh9`: how `integrator prefiltered` makes its irradiance map */
typedef enum irradiance_method { IRRADIANCE_EXACT, IRRADIANCE_SH9 } irradiance_method;

#define PREFILTER_SH9 9

/* Widths of an output map: even, from 2 to this (prefilter_check_width). */
#define PREFILTER_MAX_WIDTH 8192
/* Phong exponents S: finite, from 0 to this (a lobe of 0.06 degrees: beyond any input). */
#define PREFILTER_MAX_SHININESS 1e6
/* An exact convolution that would visit more input texels than this, summed over its output
 * texels, is refused rather than left to run for minutes (prefilter_irradiance_exact,
 * prefilter_phong): a map of rows costs a few multiply-adds a visit, a list of texels (cube,
 * mirror ball, angular) a dot product and a test as well. */
#define PREFILTER_MAX_ROW_WORK 2e10
#define PREFILTER_MAX_LIST_WORK 3e9
/* prefilter_phong leaves out the texels where r . w <= c, c chosen so that what they could add
 * is at most this fraction of the map's mean radiance (see prefilter_phong). */
#define PREFILTER_PHONG_DROP 1e-12

/* The 9 coefficients L_lm of a map, per channel (r, g, b), in the order above. */
typedef struct prefilter_sh9 {
    double L[PREFILTER_SH9][3];
} prefilter_sh9;

/* R&H's quadratic form, one 4 x 4 symmetric matrix per channel: E(n) = (n, 1)^T M (n, 1). */
typedef struct prefilter_sh9_quadratic {
    double m[3][4][4];
} prefilter_sh9_quadratic;

/* The order of the coefficients: l and m of index k in [0, 9). */
int prefilter_sh9_l(int k);
int prefilter_sh9_m(int k);

/* The 9 basis functions at unit direction d (envmap frame) into y[0..8]. */
void prefilter_sh9_basis(vec3 d, double y[PREFILTER_SH9]);

/* Project env onto the basis: L_lm = sum_t L_t Y_lm(w_t) dOmega_t (conventions above) into
 * *out.  Fails (out zeroed) only when out of memory. */
int prefilter_sh9_project(const convert_env *env, prefilter_sh9 *out, error *err);

/* Irradiance at unit normal n from the coefficients: E(n) = sum A_l L_lm Y_lm(n). */
rgb prefilter_sh9_irradiance(const prefilter_sh9 *sh, vec3 n);

/* R&H's matrix form of the same (their eq. 12), and its value at unit normal n:
 * c1 = A2 k2 / 2, c2 = A1 k1 / 2, c3 = 3 A2 k20, c4 = A0 k0, c5 = A2 k20 (k: the basis's
 * constants), so it equals prefilter_sh9_irradiance to rounding. */
void prefilter_sh9_matrix(const prefilter_sh9 *sh, prefilter_sh9_quadratic *q);
rgb prefilter_sh9_quadratic_eval(const prefilter_sh9_quadratic *q, vec3 n);

/* 0 if width is an even number in [2, PREFILTER_MAX_WIDTH], else -1 with a message. */
int prefilter_check_width(long width, error *err);

/* The map of E(n) / pi from the coefficients: the radiance a white Lambertian surface facing n
 * reflects, unshadowed.  *out is overwritten (width x width / 2; free with image_free); on
 * failure it is empty. */
int prefilter_irradiance_sh9(const prefilter_sh9 *sh, int width, image *out, error *err);

/* The exact map of E(n) / pi = sum_t L_t max(0, n . w_t) dOmega_t / pi.  Lat-long, equal-area
 * and cylindrical inputs (rows of constant theta, columns uniform in phi) take
 * prefilter_irradiance_arcs; the other kinds the plain sum, prefilter_irradiance_brute, which is
 * refused (out empty, the message naming the cost and what to do) when width x width / 2 x the
 * input's texels exceeds PREFILTER_MAX_LIST_WORK.  Fails also on a bad width or out of memory. */
int prefilter_irradiance_exact(const convert_env *env, int width, image *out, error *err);

/* The plain sum above: every output texel against every input texel (no work limit). */
int prefilter_irradiance_brute(const convert_env *env, int width, image *out, error *err);

/* The same sum for a map of rows (lat-long, equal-area, cylindrical; -1 for any other kind),
 * row by row: on an input row the texels with n . w > 0 are the columns within an arc of phi
 * around the normal's, where n . w = a + b cos(phi - phi_n) with a, b fixed by the two rows, so
 * the row's share is a S0 + b (cos phi_n Sc + sin phi_n Ss) from running sums S0, Sc, Ss of L,
 * L cos phi and L sin phi over the columns: the same sum reordered, in O(1) per row. */
int prefilter_irradiance_arcs(const convert_env *env, int width, image *out, error *err);

/* The Phong-lobe map: texel at r holds sum_t L_t (S + 1) / (2 pi) max(0, r . w_t)^S dOmega_t.
 * Texels with r . w_t <= c are left out, with c^S = PREFILTER_PHONG_DROP / (2 (S + 1)) (c = 0
 * for S = 0), which bounds what they could add by PREFILTER_PHONG_DROP x the map's mean
 * radiance (the kernel is at most (S + 1) c^S / (2 pi) there, the power is 4 pi x the mean); a
 * map of rows visits only the rows and arcs of phi that reach past c.  Refused like
 * prefilter_irradiance_exact when the texels it would visit exceed PREFILTER_MAX_ROW_WORK (a
 * map of rows, (1 - c) / 2 of its texels for each output texel) or PREFILTER_MAX_LIST_WORK (the
 * other kinds, every texel for each); fails on
 * a bad width or S (finite, in [0, PREFILTER_MAX_SHININESS]). */
int prefilter_phong(const convert_env *env, double s, int width, image *out, error *err);

/* The plain Phong sum over every texel, nothing left out (no work limit). */
int prefilter_phong_brute(const convert_env *env, double s, int width, image *out, error *err);

/* The Phong map width prefiltered.h uses for exponent S: the lobe's width is about 1 / sqrt(S)
 * radians, so the smallest power of two >= 4 pi sqrt(S) (two texels across it), clamped to
 * [64, 1024]. */
int prefilter_phong_width(double s);

#endif

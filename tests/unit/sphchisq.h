/* sphchisq.h - chi-square tests of direction samplers against their pdf (header only, for the
 * unit tests of sampling, brdf and envlight).
 *
 * The sphere is cut into n_u x n_phi bins of EQUAL solid angle: uniform in u = cos theta over
 * [-1, 1] and in phi over [0, 2 pi) (d(omega) = du dphi, so each bin has 4 pi / (n_u n_phi) sr).
 * The expected probability of a bin is the integral of the pdf over it, computed numerically:
 * each bin is cut at the "breaks" where the pdf may jump (an envmap's texel edges, given in theta
 * and phi), and every piece is integrated in (theta, phi) with sub x sub (default SPH_GL_SUB)
 * sub-intervals of 4-point Gauss-Legendre in each variable, weight sin theta dtheta dphi.  That
 * is exact to rounding for a pdf constant on each piece (an envmap's cdf mode), for the
 * sin-theta mode (pdf sin theta is constant on a piece), and very accurate for smooth lobes.
 *
 *     sph_grid g = sph_grid_make(16, 32);
 *     double prob[SPH_MAX_BINS + 1];
 *     double total = sph_expected(&g, my_pdf, ctx, prob);      // sum of prob, ~1
 *     long obs[SPH_MAX_BINS + 1] = {0};
 *     for (...) obs[sph_bin(&g, w)]++;
 *     chisq_result r = chisq_test(obs, prob, sph_n_bins(&g), N);
 *
 * A sampler that may fail (a BRDF sample below the surface) gets one extra bin, index
 * sph_n_bins(&g), of probability 1 - total: sph_add_reject_bin.
 */
#ifndef ENVTEX_SPHCHISQ_H
#define ENVTEX_SPHCHISQ_H

#include <math.h>
#include <stdlib.h>

#include "envtex/core/vec.h"

#define SPH_MAX_BINS   4096
#define SPH_MAX_BREAKS 1024
#define SPH_GL_SUB                                                                                 \
    2 /* default sub-intervals per piece and variable, each with 4 Gauss-Legendre
                      * nodes: enough for piecewise-constant pdfs; peaked lobes need more */

typedef double (*sph_pdf_fn)(void *ctx, vec3 w); /* w: unit direction in the bin frame */

typedef struct sph_grid {
    int n_u, n_phi;
    int sub; /* sub-intervals per piece (SPH_GL_SUB) */
    const double *theta_breaks;
    int n_theta_breaks; /* ascending, in [0, pi]; may be NULL */
    const double *phi_breaks;
    int n_phi_breaks; /* ascending, in [0, 2 pi]; may be NULL */
} sph_grid;

static inline sph_grid sph_grid_make(int n_u, int n_phi)
{
    sph_grid g = {n_u, n_phi, SPH_GL_SUB, NULL, 0, NULL, 0};
    return g;
}

static inline int sph_n_bins(const sph_grid *g) { return g->n_u * g->n_phi; }

/* The bin of unit direction w (frame of the grid). */
static inline int sph_bin(const sph_grid *g, vec3 w)
{
    double u = w.z, phi = atan2(w.y, w.x);
    if (phi < 0) phi += 2 * M_PI;
    int iu = (int)floor((u + 1) * 0.5 * g->n_u), ip = (int)floor(phi / (2 * M_PI) * g->n_phi);
    iu = iu < 0 ? 0 : iu >= g->n_u ? g->n_u - 1 : iu;
    ip = ip < 0 ? 0 : ip >= g->n_phi ? g->n_phi - 1 : ip;
    return iu * g->n_phi + ip;
}

/* 4-point Gauss-Legendre on [-1, 1] */
static const double sph_gl_x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                   0.8611363115940526};
static const double sph_gl_w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                   0.3478548451374538};

/* cut [a, b] at the breaks strictly inside it: out[0] = a, ..., out[n] = b; returns n pieces */
static inline int sph_cuts(double a, double b, const double *br, int n_br, double *out)
{
    int n = 0;
    out[n++] = a;
    for (int i = 0; i < n_br; i++)
        if (br[i] > a && br[i] < b) out[n++] = br[i];
    out[n] = b;
    return n;
}

/* integral of pdf sin(theta) over [t0, t1] x [p0, p1], Gauss-Legendre on sub-intervals */
static inline double sph_piece(sph_pdf_fn pdf, void *ctx, int sub, double t0, double t1, double p0,
                               double p1)
{
    double sum = 0, ht = (t1 - t0) / sub, hp = (p1 - p0) / sub;
    for (int a = 0; a < sub; a++)
        for (int i = 0; i < 4; i++) {
            double th = t0 + ht * (a + 0.5 + 0.5 * sph_gl_x[i]), st = sin(th), ct = cos(th);
            double wt = sph_gl_w[i] * 0.5 * ht * st;
            for (int b = 0; b < sub; b++)
                for (int j = 0; j < 4; j++) {
                    double ph = p0 + hp * (b + 0.5 + 0.5 * sph_gl_x[j]);
                    vec3 w = vec3_make(st * cos(ph), st * sin(ph), ct);
                    sum += wt * sph_gl_w[j] * 0.5 * hp * pdf(ctx, w);
                }
        }
    return sum;
}

/* prob[k] = integral of pdf over bin k, for k < sph_n_bins(g).  Returns the sum (ideally 1). */
static inline double sph_expected(const sph_grid *g, sph_pdf_fn pdf, void *ctx, double *prob)
{
    static double tc[SPH_MAX_BREAKS + 2], pc[SPH_MAX_BREAKS + 2];
    double total = 0;
    for (int iu = 0; iu < g->n_u; iu++) {
        /* bin iu: u in [u0, u1], theta in [acos u1, acos u0] */
        double u0 = -1 + 2.0 * iu / g->n_u, u1 = -1 + 2.0 * (iu + 1) / g->n_u;
        int nt = sph_cuts(acos(u1), acos(u0), g->theta_breaks, g->n_theta_breaks, tc);
        for (int ip = 0; ip < g->n_phi; ip++) {
            int np = sph_cuts(2 * M_PI * ip / g->n_phi, 2 * M_PI * (ip + 1) / g->n_phi,
                              g->phi_breaks, g->n_phi_breaks, pc);
            double s = 0;
            for (int a = 0; a < nt; a++)
                for (int b = 0; b < np; b++)
                    s += sph_piece(pdf, ctx, g->sub, tc[a], tc[a + 1], pc[b], pc[b + 1]);
            prob[iu * g->n_phi + ip] = s;
            total += s;
        }
    }
    return total;
}

/* Append the "sample failed" bin with probability 1 - total (clamped at 0); returns the new
 * bin count. */
static inline int sph_add_reject_bin(const sph_grid *g, double *prob, double total)
{
    double r = 1 - total;
    prob[sph_n_bins(g)] = r > 0 ? r : 0;
    return sph_n_bins(g) + 1;
}

#endif

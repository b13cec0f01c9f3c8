/* misfraction.c - how often MIS should sample the map: a variance model of a diffuse surface (see
 * include/envtex/envlight/misfraction.h; lecture slide 22 (Sampling General 2D Distributions)). */
#include "envtex/envlight/misfraction.h"

#include <math.h>

#include "envtex/core/sampling.h"
#include "envtex/envmaps/latlong.h"

/* The fractions c tried, and the normals the model averages over (a Fibonacci sphere). */
static const double fractions[] = {0, 1.0 / 32, 1.0 / 16, 1.0 / 8, 0.25, 0.5, 0.75, 1};
#define MODEL_NORMALS 64
enum {
    NC = sizeof fractions / sizeof fractions[0],
    CELLS = MISFRACTION_GRID_W * MISFRACTION_GRID_H
};
_Static_assert(NC == MISFRACTION_COUNT, "misfraction.h promises MISFRACTION_COUNT values");

/* The map reduced to gw x gh cells (energy and solid angle summed, so each cell holds the mean
 * radiance of its texels), and each cell's centre direction in the envmap frame. */
static void reduce_to_cells(const envlight *el, int gw, int gh, double *energy, double *omega,
                            vec3 *dir)
{
    for (int r = 0; r < el->h; r++) {
        int gr = (int)((long long)r * gh / el->h);
        double om = el->row_omega[r];
        for (int c = 0; c < el->w; c++) {
            int k = gr * gw + (int)((long long)c * gw / el->w);
            energy[k] += rgb_avg(envlight_texel(el, c, r)) * om;
            omega[k] += om;
        }
    }
    for (int gr = 0; gr < gh; gr++)
        for (int gc = 0; gc < gw; gc++)
            dir[gr * gw + gc] = latlong_uv_to_dir((uv2){(gc + 0.5) / gw, (gr + 0.5) / gh});
}

/* For a diffuse surface of albedo 1 facing nrm, g = L cos+ / pi: adds its relative variance
 * V(c) for each fraction into rel_var; 0 if the surface sees no light (not counted). */
static int add_surface(const envlight *el, vec3 nrm, int n_cells, const double *energy,
                       const double *omega, const vec3 *dir, double *rel_var)
{
    double I = 0, S[NC] = {0};
    for (int k = 0; k < n_cells; k++) {
        double cs = vec3_dot(nrm, dir[k]);
        if (!(cs > 0) || !(omega[k] > 0)) continue;
        double L = energy[k] / omega[k], g = L * cs / M_PI;
        /* cosine sampling; the cdf's pdf L / |L| (PBRT's, nearly) */
        double pb = cs / M_PI, pl = L / el->power;
        I += g * omega[k];
        for (int i = 0; i < NC; i++) {
            double c = fractions[i], pm = (pb + c * pl) / (1 + c); /* the mixture */
            S[i] += g * g / pm * omega[k]; /* second moment: integral of g^2 / p_m */
        }
    }
    if (!(I > 0)) return 0;
    for (int i = 0; i < NC; i++) {
        /* relative variance of 1 + c samples of the mixture: (S / I^2 - 1) / (1 + c) */
        double rv = fmax(0.0, S[i] / (I * I) - 1) / (1 + fractions[i]);
        rel_var[i] += rv;
    }
    return 1;
}

double misfraction_choose(const envlight *el, double light_cost, double *rel_var_out)
{
    if (rel_var_out)
        for (int i = 0; i < NC; i++) rel_var_out[i] = 0;
    int cdf = el->mode == ENVSAMPLING_CDF || el->mode == ENVSAMPLING_CDF_SINTHETA;
    if (el->fell_back || !(el->power > 0) || !cdf) return 1;
    int gw = el->w < MISFRACTION_GRID_W ? el->w : MISFRACTION_GRID_W;
    int gh = el->h < MISFRACTION_GRID_H ? el->h : MISFRACTION_GRID_H;
    double energy[CELLS] = {0}, omega[CELLS] = {0};
    vec3 dir[CELLS];
    reduce_to_cells(el, gw, gh, energy, omega, dir);
    double cost[NC] = {0};
    int counted = 0;
    for (int n = 0; n < MODEL_NORMALS; n++) {
        vec3 nrm =
            sampling_uniform_sphere((n + 0.5) / MODEL_NORMALS, fmod(n * 0.6180339887498949, 1.0));
        counted += add_surface(el, nrm, gw * gh, energy, omega, dir, cost);
    }
    if (!counted) return 1;
    int best = NC - 1;
    for (int i = 0; i < NC; i++) {
        cost[i] /= counted;
        if (rel_var_out) rel_var_out[i] = cost[i];
        cost[i] *= 1 + light_cost * fractions[i]; /* variance x time: the inefficiency */
    }
    /* a smaller fraction must win by more than rounding (1e-9 relative, far above the ~1e-15
     * of these sums, far below any real difference): on a tie the larger c, more light samples */
    for (int i = NC - 1; i >= 0; i--)
        if (cost[i] < cost[best] * (1 - 1e-9)) best = i;
    return fractions[best];
}

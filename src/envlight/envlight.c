/* envlight.c - the environment as a light: numerical-CDF importance sampling in
 * (u = cos theta, v = phi), PBRT's sin-theta variant, uniform sampling and median cut
 * (see include/envtex/envlight/envlight.h). */
#include "envtex/envlight/envlight.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/envmaps/latlong.h"
#include "envtex/core/sampling.h"

/* cdf-sintheta: the least remapped value inside a row, so that theta > 0 (sin theta > 0) */
#define ENVLIGHT_POLE_REM 1e-9

/* transform_is_conformal: how far A A^T may be from s^2 I, relative to s^2.  The
 * scene's matrices are products of a few rotations in double (errors ~1e-15); 1e-6 still
 * refuses a scale of 1 + 1e-6 along one axis, which would move a sample by ~1e-6 radians. */
#define ENVLIGHT_CONFORMAL_TOL 1e-6

/* A texel as the light sees it: NaN, Inf and negative channels are 0, then scaled. */
static inline double clean(float v) { return v > 0 && v <= FLT_MAX ? (double)v : 0.0; } /* NaN fails both */

static inline rgb texel(const envlight *el, int c, int r)
{
    const float *p = image_px(el->map, c, r);
    double s = el->env->scale;
    return rgb_make(clean(p[0]) * s, clean(p[1]) * s, clean(p[2]) * s);
}

/* solid angle of a texel in row r: (cos theta_r - cos theta_{r+1}) 2 pi / w (tabulated) */
static inline double texel_omega(const envlight *el, int r) { return el->row_omega[r]; }

/* world direction -> the texel that holds it (nearest), in the envmap frame.  uv here is
 * latlong's image (u = phi / 2 pi, v = theta / pi), not the lecture's u = cos theta, v = phi. */
static int world_to_texel(const envlight *el, vec3 wi, int *c, int *r, double *sin_theta)
{
    uv2 uv;
    vec3 d = el->identity ? wi : envmap_to_frame(el->env, wi);
    if (latlong_dir_to_uv(d, &uv)) return -1;
    int x = (int)(uv.u * el->w), y = (int)(uv.v * el->h);
    *c = x < el->w ? x : el->w - 1;
    *r = y < el->h ? y : el->h - 1;
    if (sin_theta) *sin_theta = sin(M_PI * uv.v);
    return 0;
}

rgb envlight_radiance(const envlight *el, vec3 wi)
{
    int c, r;
    if (!el->env->present || world_to_texel(el, wi, &c, &r, NULL)) return rgb_gray(0);
    return texel(el, c, r);
}

/* ---- median cut (Debevec 2005): strata of equal energy ------------------------------------ */

typedef struct region { int c0, c1, r0, r1; double energy; } region;

/* energy of columns [c0,c1) x rows [r0,r1) from the summed-area table S ((w+1) x (h+1)) */
static double sat_sum(const double *S, int h, int c0, int c1, int r0, int r1)
{
    int H = h + 1;
    return S[c1 * H + r1] - S[c0 * H + r1] - S[c1 * H + r0] + S[c0 * H + r0];
}

/* Split region g in two halves of (about) equal energy across its longer side, measured in
 * angle: the phi side is shortened by sin theta at the region's middle.  0 if it cannot split. */
static int split_region(const envlight *el, const double *S, const region *g, region *a, region *b)
{
    int cw = g->c1 - g->c0, rh = g->r1 - g->r0;
    if (cw < 2 && rh < 2) return 0;
    /* STEP(mediancut): the median cut: split across the longer side in angle (phi's side
     * shortened by sin theta at the middle row), at the first cut whose part [c0, k) or
     * [r0, k) holds half the energy (sat_sum; a binary search), k in (c0, c1) or (r0, r1); a
     * side of one texel never splits (slides 18-21) */
    /* STUB: *a = *b = *g;
     * if (cw >= rh) a->c1 = b->c0 = g->c0 + cw / 2; else a->r1 = b->r0 = g->r0 + rh / 2; */
    double mid_theta = M_PI * 0.5 * (g->r0 + g->r1) / el->h;
    double phi_len = cw * 2 * M_PI / el->w * sin(mid_theta), theta_len = rh * M_PI / el->h;
    int by_cols = rh < 2 || (cw >= 2 && phi_len >= theta_len);
    *a = *b = *g;
    double half = 0.5 * g->energy;
    if (by_cols) {
        int lo = g->c0 + 1, hi = g->c1 - 1; /* first cut k with energy of [c0, k) >= half */
        while (lo < hi) {
            int m = lo + (hi - lo) / 2;
            if (sat_sum(S, el->h, g->c0, m, g->r0, g->r1) >= half) hi = m;
            else lo = m + 1;
        }
        a->c1 = b->c0 = lo;
    } else {
        int lo = g->r0 + 1, hi = g->r1 - 1;
        while (lo < hi) {
            int m = lo + (hi - lo) / 2;
            if (sat_sum(S, el->h, g->c0, g->c1, g->r0, m) >= half) hi = m;
            else lo = m + 1;
        }
        a->r1 = b->r0 = lo;
    }
    /* END STEP(mediancut) */
    a->energy = sat_sum(S, el->h, a->c0, a->c1, a->r0, a->r1);
    b->energy = sat_sum(S, el->h, b->c0, b->c1, b->r0, b->r1);
    return 1;
}

/* max-heap of regions by energy */
static void heap_push(region *hp, int *n, region g)
{
    int i = (*n)++;
    hp[i] = g;
    while (i > 0 && hp[(i - 1) / 2].energy < hp[i].energy) {
        region t = hp[i]; hp[i] = hp[(i - 1) / 2]; hp[(i - 1) / 2] = t;
        i = (i - 1) / 2;
    }
}

static region heap_pop(region *hp, int *n)
{
    region top = hp[0];
    hp[0] = hp[--*n];
    int i = 0;
    for (;;) {
        int l = 2 * i + 1, r = l + 1, m = i;
        if (l < *n && hp[l].energy > hp[m].energy) m = l;
        if (r < *n && hp[r].energy > hp[m].energy) m = r;
        if (m == i) break;
        region t = hp[i]; hp[i] = hp[m]; hp[m] = t;
        i = m;
    }
    return top;
}

static int build_mediancut(envlight *el, const double *energy, int n_lights, error *err)
{
    int w = el->w, h = el->h, H = h + 1;
    int status = -1;
    double *S = calloc((size_t)(w + 1) * (size_t)H, sizeof *S);
    region *heap = malloc((size_t)n_lights * sizeof *heap), *done = malloc((size_t)n_lights * sizeof *done);
    double *wts = malloc((size_t)n_lights * sizeof *wts);
    if (!S || !heap || !done || !wts) {
        error_set(err, NULL, 0, "out of memory for median cut of a %d x %d map", w, h);
        goto cleanup;
    }
    /* summed-area table: S[c][r] = energy of columns [0,c) x rows [0,r) */
    for (int c = 0; c < w; c++)
        for (int r = 0; r < h; r++)
            S[(c + 1) * H + r + 1] = energy[(size_t)c * h + r] + S[c * H + r + 1] + S[(c + 1) * H + r] - S[c * H + r];
    int n_heap = 0, n_done = 0;
    heap_push(heap, &n_heap, (region){0, w, 0, h, sat_sum(S, h, 0, w, 0, h)});
    /* split the most energetic region until there are n_lights (or nothing splits) */
    while (n_heap > 0 && n_heap + n_done < n_lights) {
        region g = heap_pop(heap, &n_heap), a, b;
        if (g.energy <= 0 || !split_region(el, S, &g, &a, &b)) { done[n_done++] = g; continue; }
        heap_push(heap, &n_heap, a);
        heap_push(heap, &n_heap, b);
    }
    while (n_heap > 0) done[n_done++] = heap_pop(heap, &n_heap);
    el->points = calloc((size_t)n_done, sizeof *el->points);
    if (!el->points) { error_set(err, NULL, 0, "out of memory for %d median-cut lights", n_done); goto cleanup; }
    mat4 to_world;
    if (mat4_inverse(el->env->to_env, &to_world)) to_world = mat4_identity();
    for (int k = 0; k < n_done; k++) {
        const region *g = &done[k];
        envlight_point *pt = &el->points[k];
        /* the energy centroid in image coordinates (Debevec 2005): a weighted mean of texel
         * centres, so it lies inside the stratum (the mean 3D direction of a stratum wide in
         * phi near a pole lies poleward of it, outside) */
        double sx = 0, sy = 0, se = 0;
        rgb power = rgb_gray(0);
        for (int c = g->c0; c < g->c1; c++)
            for (int r = g->r0; r < g->r1; r++) {
                double om = texel_omega(el, r);
                rgb L = texel(el, c, r);
                power = rgb_madd(power, L, om); /* power = sum of L dOmega over the stratum */
                double e = rgb_avg(L) * om;
                sx += e * (c + 0.5);
                sy += e * (r + 0.5);
                se += e;
            }
        uv2 uv = {0.5 * (g->c0 + g->c1) / w, 0.5 * (g->r0 + g->r1) / h}; /* a black stratum: its centre */
        if (se > 0) uv = (uv2){sx / se / w, sy / se / h};
        pt->dir = vec3_normalize(mat4_dir(&to_world, latlong_uv_to_dir(uv)));
        pt->power = power;
        pt->c0 = g->c0; pt->c1 = g->c1; pt->r0 = g->r0; pt->r1 = g->r1;
        wts[k] = rgb_avg(power);
    }
    el->n_points = n_done;
    if (distrib1d_init(&el->point_choice, wts, n_done, err)) goto cleanup;
    status = 0;
cleanup:
    free(S);
    free(heap);
    free(done);
    free(wts);
    return status;
}

/* A A^T = s^2 I within ENVLIGHT_CONFORMAL_TOL, s^2 = trace(A A^T) / 3 > 0, for the linear part A
 * (upper 3 x 3) of m: directions are turned (and maybe mirrored and uniformly scaled), never
 * distorted. */
static int transform_is_conformal(const mat4 *m)
{
    double aat[3][3], s2 = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            aat[i][j] = 0;
            for (int k = 0; k < 3; k++) aat[i][j] += m->m[i][k] * m->m[j][k]; /* (A A^T)_ij */
        }
    for (int i = 0; i < 3; i++) s2 += aat[i][i] / 3;
    if (!(s2 > 0) || !isfinite(s2)) return 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (!(fabs(aat[i][j] - (i == j) * s2) <= ENVLIGHT_CONFORMAL_TOL * s2)) return 0;
    return 1;
}

/* envlight_build, and with measure = 0 (mode uniform) envlight_build_lookup: no pass over the
 * texels at all. */
static int build_tables(envlight *el, const envmap *env, envsampling_mode mode,
                        envsampler_kind sampler, int mediancut_n, int measure, error *err)
{
    memset(el, 0, sizeof *el);
    el->env = env;
    el->mode = mode;
    el->sampler = sampler;
    if (!env->present) return error_set(err, NULL, 0, "no environment map to sample");
    /* Directions see only the linear part A of to_env (the upper 3 x 3: mat4_dir drops the
     * translation, the envmap being at infinity).  The tables live in the map's frame and a
     * sampled direction d goes back to the world as A^T d / |A^T d|, which is A^-1 d up to its
     * length, with the pdf unchanged, exactly when A A^T = s^2 I: a rotation, possibly times a
     * uniform scale s or a mirror.  Anything else (a non-uniform scale, a shear) would distort
     * the pdf, so the table modes refuse it.  Uniform sampling draws in the world and only looks
     * the map up, like the background: any transform. */
    mat4 m = env->to_env;
    if (mode != ENVSAMPLING_UNIFORM && !transform_is_conformal(&m))
        return error_set(err, NULL, 0, "the envmap's transform is not a rotation (nor a rotation times a uniform "
                         "scale), so it cannot be sampled as a light (put only 'rotate' before 'envmap', or use "
                         "'envsampling uniform')");
    clock_t t0 = clock();
    el->map = env->img;
    if (!el->map) { /* another representation: resample it to lat-long once (no-op otherwise) */
        if (envmap_to_latlong(env, 0, 0, &el->converted, err))
            return error_prefix(err, "resampling the environment to lat-long for sampling");
        el->map = &el->converted;
    }
    int w = el->w = el->map->w, h = el->h = el->map->h;
    el->to_world = mat4_transpose(m);
    el->identity = 1; /* A = I: lookups and samples skip the matrix (a translation is no matter) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) el->identity &= m.m[i][j] == (i == j);
    el->cos_edge = malloc((size_t)(h + 1) * sizeof *el->cos_edge);
    el->row_omega = malloc((size_t)h * sizeof *el->row_omega);
    if (!el->cos_edge || !el->row_omega) {
        envlight_free(el);
        return error_set(err, NULL, 0, "out of memory for a %d-row map", h);
    }
    /* row r spans theta in [pi r / h, pi (r + 1) / h]: u = cos theta from 1 down to -1 */
    for (int r = 0; r <= h; r++) el->cos_edge[r] = r == 0 ? 1.0 : r == h ? -1.0 : cos(M_PI * r / h);
    for (int r = 0; r < h; r++) {
        /* STEP(cdf): the exact solid angle of a texel of row r, in the lecture's u = cos theta, v = phi where d(omega) = du dv: (cos theta_top - cos theta_bottom) (2 pi / w), with cos_edge[r] = cos theta_top (slide 22); it weights each texel's probability and the map's power |L| */
        /* STUB: el->row_omega[r] = 4 * M_PI / ((double)w * h); */
        el->row_omega[r] = (el->cos_edge[r] - el->cos_edge[r + 1]) * 2 * M_PI / w;
        /* END STEP(cdf) */
    }
    if (!measure) {
        el->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
        return 0;
    }
    /* energy of each texel, column-major (outer = column = phi, inner = row = u): the pmf of
     * the lecture's cdf mode.  p(c, r) = L_avg(c, r) dOmega_r / |L|.  Uniform sampling needs
     * only the power (lights.h chooses among lights by it) and kappa: no array. */
    double *energy = NULL;
    if (mode != ENVSAMPLING_UNIFORM) {
        energy = malloc((size_t)w * (size_t)h * sizeof *energy);
        if (!energy) {
            envlight_free(el);
            return error_set(err, NULL, 0, "out of memory for the sampling table of a %d x %d map", w, h);
        }
    }
    double power = 0, second = 0;
    for (int r = 0; r < h; r++) {
        double om = texel_omega(el, r);
        /* PBRT's weights: L sin(theta at the row centre) (rows uniform in theta) */
        double sin_c = sin(M_PI * (r + 0.5) / h);
        for (int c = 0; c < w; c++) {
            const float *p = image_px(el->map, c, r);
            for (int k = 0; k < 3; k++) el->n_bad += !(isfinite(p[k]) && p[k] >= 0);
            double L = rgb_avg(texel(el, c, r));
            power += L * om; /* |L| = sum L_avg dOmega, in double */
            second += L * L * om; /* sum L_avg^2 dOmega, for kappa */
            if (energy) energy[(size_t)c * h + r] = L * (mode == ENVSAMPLING_CDF_SINTHETA ? sin_c : om);
        }
    }
    el->power = power;
    /* kappa = E[L^2] / E[L]^2 over uniform directions = (second / 4 pi) / (power / 4 pi)^2 */
    el->kappa = power > 0 ? 4 * M_PI * second / (power * power) : 1.0;
    int status = 0;
    if (!(power > 0)) {
        el->fell_back = 1; /* all black: nothing to importance sample */
        el->mode = mode == ENVSAMPLING_MEDIANCUT ? ENVSAMPLING_MEDIANCUT : ENVSAMPLING_UNIFORM;
    }
    if (el->mode == ENVSAMPLING_CDF || el->mode == ENVSAMPLING_CDF_SINTHETA) {
        status = distrib2d_init(&el->table, energy, w, h, err);
        if (!status && sampler == ENVSAMPLER_ALIAS) status = distrib2d_alias_build(&el->table, err);
    } else if (el->mode == ENVSAMPLING_MEDIANCUT) {
        if (el->fell_back) for (size_t i = 0; i < (size_t)w * h; i++) energy[i] = 1; /* equal strata */
        status = build_mediancut(el, energy, mediancut_n > 0 ? mediancut_n : 64, err);
    }
    free(energy);
    if (status) envlight_free(el);
    el->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return status;
}

/* The bytes build_tables keeps for env in `mode` (*tables of them for the sampling tables
 * alone), and in *scratch the most it holds only while building: the energy of every texel and
 * median cut's summed-area table.  *w, *h: the lat-long map it samples. */
static double build_bytes(const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                          int n_lights, int measure, int *w, int *h, double *tables,
                          double *scratch)
{
    double keep = 0;
    if (env->img) {
        *w = env->img->w;
        *h = env->img->h;
    } else { /* resampled to lat-long first (envmap_to_latlong at its default width) */
        convert_env v = envmap_view(env);
        *w = convert_default_width(&v, CONVERT_LATLONG);
        *h = *w / 2 > 1 ? *w / 2 : 1;
        keep += (double)*w * *h * IMAGE_TEXEL_BYTES;
    }
    double texels = (double)*w * *h;
    int cdf = mode == ENVSAMPLING_CDF || mode == ENVSAMPLING_CDF_SINTHETA;
    keep += (2.0 * *h + 1) * sizeof(double); /* cos_edge, row_omega */
    *tables = *scratch = 0;
    if (!measure || mode == ENVSAMPLING_UNIFORM) return keep;
    *scratch = texels * sizeof(double); /* the energy of each texel */
    if (cdf) {
        *tables = distrib2d_bytes(*w, *h, sampler == ENVSAMPLER_ALIAS);
    } else { /* median cut: the summed-area table and the regions; the points and their choice */
        int n = n_lights > 0 ? n_lights : 64;
        *scratch += (double)(*w + 1) * (*h + 1) * sizeof(double) +
                    (double)n * (2 * sizeof(region) + sizeof(double));
        *tables = (double)n * (sizeof(envlight_point) + 2 * sizeof(double));
    }
    return keep + *tables;
}

/* build_tables, its memory charged to the budget first */
static int build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                 int mediancut_n, int measure, budget *mem, error *err)
{
    memset(el, 0, sizeof *el);
    if (!env->present) return error_set(err, NULL, 0, "no environment map to sample");
    int w, h;
    double tables, scratch;
    double keep = build_bytes(env, mode, sampler, mediancut_n, measure, &w, &h, &tables, &scratch);
    const char *what = measure && mode != ENVSAMPLING_UNIFORM ? "sampling tables" : "lookup tables";
    if (budget_charge(mem, keep + scratch, NULL, 0, err, "%s for a %d x %d lat-long map", what, w,
                      h))
        return -1;
    int rc = build_tables(el, env, mode, sampler, mediancut_n, measure, err);
    /* a black map falls back to uniform directions: its cdf tables were never built */
    double unused = rc ? keep : el->fell_back && el->mode == ENVSAMPLING_UNIFORM ? tables : 0;
    budget_release(mem, scratch + unused);
    return rc;
}

int envlight_build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                   int mediancut_n, budget *mem, error *err)
{
    return build(el, env, mode, sampler, mediancut_n, 1, mem, err);
}

int envlight_build_lookup(envlight *el, const envmap *env, budget *mem, error *err)
{
    return build(el, env, ENVSAMPLING_UNIFORM, ENVSAMPLER_BINARY, 0, 0, mem, err);
}

void envlight_free(envlight *el)
{
    distrib2d_free(&el->table);
    distrib1d_free(&el->point_choice);
    free(el->points);
    image_free(&el->converted);
    el->map = NULL;
    free(el->cos_edge);
    free(el->row_omega);
    el->points = NULL;
    el->cos_edge = el->row_omega = NULL;
    el->n_points = 0;
}

/* The cdf mode's pdf of texel (c, r): p(omega) = p(c,r) / dOmega_r with p(c,r) = L_avg dOmega_r / |L|,
 * so p(omega) = L_avg(c, r) / |L|, "the pdf cancels the light".  Computed from the texel (one
 * read, which the caller needs for L anyway) rather than as the table's pmf / dOmega: the same
 * number up to the CDF's rounding (~1e-16 / p relative, distrib.h), used alike by sampling and
 * lookup so that they agree to the last bit. */
static inline double cdf_pdf(const envlight *el, int c, int r) { return rgb_avg(texel(el, c, r)) / el->power; }

/* envmap frame -> world for sampled directions: A^T d / |A^T d|, which is A^-1 d / |A^-1 d| for
 * the linear part A of to_env, A A^T = s^2 I (envlight_build; the inverse of a rotation is its
 * transpose) */
static inline vec3 frame_to_world(const envlight *el, vec3 d)
{
    return el->identity ? d : vec3_normalize(mat4_dir(&el->to_world, d));
}

double envlight_pdf(const envlight *el, vec3 wi)
{
    int c, r;
    double sin_t;
    switch (el->mode) {
    case ENVSAMPLING_UNIFORM: return 1 / (4 * M_PI);
    case ENVSAMPLING_CDF:
        if (world_to_texel(el, wi, &c, &r, NULL)) return 0;
        return cdf_pdf(el, c, r);
    case ENVSAMPLING_CDF_SINTHETA:
        if (world_to_texel(el, wi, &c, &r, &sin_t) || !(sin_t > 0)) return 0;
        /* p(omega) = p(theta, phi) / sin theta, p(theta, phi) = p(c,r) W H / (2 pi^2) */
        return distrib2d_pmf(&el->table, c, r) * el->w * el->h / (2 * M_PI * M_PI * sin_t);
    default: return 0; /* median cut has no density */
    }
}

rgb envlight_radiance_pdf(const envlight *el, vec3 wi, double *pdf)
{
    int c, r;
    double sin_t = 0;
    *pdf = 0;
    /* sin theta only where the pdf needs it (cdf-sintheta): a sin() call a lookup otherwise */
    double *want_sin = el->mode == ENVSAMPLING_CDF_SINTHETA ? &sin_t : NULL;
    if (!el->env->present || world_to_texel(el, wi, &c, &r, want_sin)) return rgb_gray(0);
    switch (el->mode) {
    case ENVSAMPLING_UNIFORM: *pdf = 1 / (4 * M_PI); break;
    case ENVSAMPLING_CDF: { rgb L = texel(el, c, r); *pdf = rgb_avg(L) / el->power; return L; } /* cdf_pdf */
    case ENVSAMPLING_CDF_SINTHETA:
        if (sin_t > 0) *pdf = distrib2d_pmf(&el->table, c, r) * el->w * el->h / (2 * M_PI * M_PI * sin_t);
        break;
    default: break; /* median cut: no density */
    }
    return texel(el, c, r);
}

/* uniform directions on the sphere, pdf = 1 / (4 pi): in the world, as in any frame */
static int sample_uniform(const envlight *el, double xi1, double xi2, envlight_sample_result *out)
{
    out->wi = sampling_uniform_sphere(xi1, xi2);
    out->pdf = 1 / (4 * M_PI);
    out->L = envlight_radiance(el, out->wi);
    return 1;
}

/* cdf-sintheta (PBRT): a point uniform in theta inside texel (c, r) of probability pmf.  rr = 0
 * in a lit row 0 would give theta = 0, where sin theta = 0 and the density is infinite: start
 * ENVLIGHT_POLE_REM of a row inside it (a set of probability 1e-9 moved by 1e-9 of a row) */
static int point_in_texel_sintheta(const envlight *el, int c, int r, double pmf, double rc,
                                   double rr, envlight_sample_result *out)
{
    double phi = 2 * M_PI * (c + rc) / el->w;
    double theta = M_PI * (r + fmax(rr, ENVLIGHT_POLE_REM)) / el->h;
    double sin_t = sin(theta);
    out->wi = frame_to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos(theta)));
    out->L = texel(el, c, r);
    /* p(omega) = p(c,r) W H / (2 pi^2 sin theta) */
    out->pdf = sin_t > 0 ? pmf * el->w * el->h / (2 * M_PI * M_PI * sin_t) : 0;
    return out->pdf > 0;
}

/* The lecture's point in the chosen texel (c, r): uniform in u = cos theta and in phi, where
 * d(omega) = du dphi, so pdf(omega) = p(c, r) / dOmega_r = L_avg(c, r) / |L|: the pdf cancels
 * the light.  (rc, rr) are the samples remapped to [0, 1) inside the cell. */
static int point_in_texel(const envlight *el, int c, int r, double pmf, double rc, double rr,
                          envlight_sample_result *out)
{
    if (el->mode == ENVSAMPLING_CDF_SINTHETA)
        return point_in_texel_sintheta(el, c, r, pmf, rc, rr, out);
    double phi = 2 * M_PI * (c + rc) / el->w;                     /* v = phi */
    double u = el->cos_edge[r] + rr * (el->cos_edge[r + 1] - el->cos_edge[r]); /* u = cos theta */
    double sin_t = sqrt(fmax(0.0, 1 - u * u));
    out->wi = frame_to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), u));
    out->L = texel(el, c, r);
    out->pdf = rgb_avg(out->L) / el->power; /* p(omega) = L_avg / |L| (cdf_pdf) */
    return out->pdf > 0;
}

int envlight_sample(const envlight *el, double xi1, double xi2, envlight_sample_result *out)
{
    if (el->mode == ENVSAMPLING_UNIFORM) return sample_uniform(el, xi1, xi2, out);
    if (el->mode != ENVSAMPLING_CDF && el->mode != ENVSAMPLING_CDF_SINTHETA) return 0;
    /* slide 22: the column (phi) from the marginal CDF, then the row (u = cos theta) from the
     * column's conditional CDF; alias tables pick the same cells in O(1) */
    int c, r;
    double pmf, rc, rr;
    if (el->sampler == ENVSAMPLER_ALIAS)
        distrib2d_sample_alias(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr);
    else
        distrib2d_sample(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr);
    return point_in_texel(el, c, r, pmf, rc, rr, out);
}

int envlight_sample_stratified(const envlight *el, double xi1, double xi2,
                               envlight_sample_result *out)
{
    if (el->mode == ENVSAMPLING_UNIFORM) return sample_uniform(el, xi1, xi2, out);
    if (el->mode != ENVSAMPLING_CDF && el->mode != ENVSAMPLING_CDF_SINTHETA) return 0;
    int c, r;
    double pmf, rc, rr;
    distrib2d_sample(&el->table, xi1, xi2, &c, &r, &pmf, &rc, &rr); /* inversion keeps strata */
    return point_in_texel(el, c, r, pmf, rc, rr, out);
}

/* ---- how often MIS should sample the map (lights.h, envsamplefraction auto) --------------- */

/* The fractions c tried, and the normals the model averages over (a Fibonacci sphere). */
static const double mis_fractions[] = {0, 1.0 / 32, 1.0 / 16, 1.0 / 8, 0.25, 0.5, 0.75, 1};
#define MIS_MODEL_NORMALS 64

double envlight_mis_fraction(const envlight *el, double light_cost, double *rel_var_out)
{
    enum { NC = sizeof mis_fractions / sizeof mis_fractions[0] };
    _Static_assert(NC == ENVLIGHT_MIS_FRACTIONS, "envlight.h promises ENVLIGHT_MIS_FRACTIONS values");
    if (rel_var_out)
        for (int i = 0; i < NC; i++) rel_var_out[i] = 0;
    int cdf = el->mode == ENVSAMPLING_CDF || el->mode == ENVSAMPLING_CDF_SINTHETA;
    if (el->fell_back || !(el->power > 0) || !cdf) return 1;
    /* the map reduced to at most ENVLIGHT_MIS_GRID_W x _H cells (energy and solid angle summed, so
     * each cell holds the mean radiance of its texels) */
    int gw = el->w < ENVLIGHT_MIS_GRID_W ? el->w : ENVLIGHT_MIS_GRID_W;
    int gh = el->h < ENVLIGHT_MIS_GRID_H ? el->h : ENVLIGHT_MIS_GRID_H;
    enum { CELLS = ENVLIGHT_MIS_GRID_W * ENVLIGHT_MIS_GRID_H };
    double energy[CELLS] = {0}, omega[CELLS] = {0};
    for (int r = 0; r < el->h; r++) {
        int gr = (int)((long long)r * gh / el->h);
        double om = texel_omega(el, r);
        for (int c = 0; c < el->w; c++) {
            int k = gr * gw + (int)((long long)c * gw / el->w);
            energy[k] += rgb_avg(texel(el, c, r)) * om;
            omega[k] += om;
        }
    }
    vec3 dir[CELLS];
    for (int gr = 0; gr < gh; gr++)
        for (int gc = 0; gc < gw; gc++) /* the cell's centre, in the envmap frame */
            dir[gr * gw + gc] = latlong_uv_to_dir((uv2){(gc + 0.5) / gw, (gr + 0.5) / gh});
    double cost[NC] = {0};
    int counted = 0;
    for (int n = 0; n < MIS_MODEL_NORMALS; n++) {
        /* a diffuse surface of albedo 1 facing normal nrm: g = L cos+ / pi */
        vec3 nrm = sampling_uniform_sphere((n + 0.5) / MIS_MODEL_NORMALS, fmod(n * 0.6180339887498949, 1.0));
        double I = 0, S[NC] = {0};
        for (int k = 0; k < gw * gh; k++) {
            double cs = vec3_dot(nrm, dir[k]);
            if (!(cs > 0) || !(omega[k] > 0)) continue;
            double L = energy[k] / omega[k], g = L * cs / M_PI;
            /* cosine sampling; the cdf's pdf L / |L| (PBRT's, nearly) */
            double pb = cs / M_PI, pl = L / el->power;
            I += g * omega[k];
            for (int i = 0; i < NC; i++) {
                double c = mis_fractions[i], pm = (pb + c * pl) / (1 + c); /* the mixture */
                S[i] += g * g / pm * omega[k]; /* second moment: integral of g^2 / p_m */
            }
        }
        if (!(I > 0)) continue;
        counted++;
        for (int i = 0; i < NC; i++) {
            /* relative variance of 1 + c samples of the mixture: (S / I^2 - 1) / (1 + c) */
            double rv = fmax(0.0, S[i] / (I * I) - 1) / (1 + mis_fractions[i]);
            cost[i] += rv;
        }
    }
    if (!counted) return 1;
    int best = NC - 1;
    for (int i = 0; i < NC; i++) {
        cost[i] /= counted;
        if (rel_var_out) rel_var_out[i] = cost[i];
        cost[i] *= 1 + light_cost * mis_fractions[i]; /* variance x time: the inefficiency */
    }
    /* a smaller fraction must win by more than rounding (1e-9 relative, far above the ~1e-15
     * of these sums, far below any real difference): on a tie the larger c, more light samples */
    for (int i = NC - 1; i >= 0; i--)
        if (cost[i] < cost[best] * (1 - 1e-9)) best = i;
    return mis_fractions[best];
}

int envlight_mediancut_pick(const envlight *el, double xi, double xi1, double xi2, int *k, vec3 *shadow_dir,
                            double *prob)
{
    if (el->n_points == 0) return 0;
    double pmf;
    int i = distrib1d_sample(&el->point_choice, xi, &pmf, NULL);
    const envlight_point *pt = &el->points[i];
    /* jitter inside the stratum, uniform in (cos theta, phi): for the shadow ray only */
    double u0 = el->cos_edge[pt->r0], u1 = el->cos_edge[pt->r1];
    double cos_t = u0 + xi1 * (u1 - u0), sin_t = sqrt(fmax(0.0, 1 - cos_t * cos_t));
    double phi = 2 * M_PI * (pt->c0 + xi2 * (pt->c1 - pt->c0)) / el->w;
    *shadow_dir = frame_to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos_t));
    *k = i;
    *prob = pmf;
    return pmf > 0;
}

int envlight_transform_is_conformal(const mat4 *m) { return transform_is_conformal(m); }

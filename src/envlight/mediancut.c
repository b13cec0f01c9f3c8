/* mediancut.c - Debevec's median cut: strata of equal energy, each a point light (see
 * include/envtex/envlight/mediancut.h; lecture slides 18-21 (Structured Importance Sampling)). */
#include "envtex/envlight/mediancut.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/envmaps/latlong.h"

typedef struct region {
    int c0, c1, r0, r1;
    double energy;
} region;

/* A texel as the light sees it: NaN, Inf and negative channels are 0 (NaN fails both), then
 * scaled; the same reading as envlight.c's. */
static inline double clean(float v) { return v > 0 && v <= FLT_MAX ? (double)v : 0.0; }

static inline rgb texel(const mediancut_map *m, int c, int r)
{
    const float *p = image_px(m->img, c, r);
    double s = m->scale;
    return rgb_make(clean(p[0]) * s, clean(p[1]) * s, clean(p[2]) * s);
}

/* energy of columns [c0,c1) x rows [r0,r1) from the summed-area table S ((w+1) x (h+1)) */
static double sat_sum(const double *S, int h, int c0, int c1, int r0, int r1)
{
    int H = h + 1;
    return S[c1 * H + r1] - S[c0 * H + r1] - S[c1 * H + r0] + S[c0 * H + r0];
}

/* Split region g in two halves of (about) equal energy across its longer side, measured in
 * angle: the phi side is shortened by sin theta at the region's middle.  0 if it cannot split. */
static int split_region(int w, int h, const double *S, const region *g, region *a, region *b)
{
    int cw = g->c1 - g->c0, rh = g->r1 - g->r0;
    if (cw < 2 && rh < 2) return 0;
    /* STEP(mediancut): Debevec's median cut, slides 18-21 (Structured Importance Sampling): "reduce
     * environment to point lights", "integrate lighting in strata": split the region across its
     * longer side, measured in angle, where half its energy lies (sat_sum: a region's energy); a
     * side one texel wide never splits */
    /* STUB: (void)w;
     * *a = *b = *g;
     * if (cw >= rh) a->c1 = b->c0 = g->c0 + cw / 2; else a->r1 = b->r0 = g->r0 + rh / 2; */
    double mid_theta = M_PI * 0.5 * (g->r0 + g->r1) / h;
    double phi_len = cw * 2 * M_PI / w * sin(mid_theta), theta_len = rh * M_PI / h;
    int by_cols = rh < 2 || (cw >= 2 && phi_len >= theta_len);
    *a = *b = *g;
    double half = 0.5 * g->energy;
    if (by_cols) {
        int lo = g->c0 + 1, hi = g->c1 - 1; /* first cut k with energy of [c0, k) >= half */
        while (lo < hi) {
            int m = lo + (hi - lo) / 2;
            if (sat_sum(S, h, g->c0, m, g->r0, g->r1) >= half)
                hi = m;
            else
                lo = m + 1;
        }
        a->c1 = b->c0 = lo;
    } else {
        int lo = g->r0 + 1, hi = g->r1 - 1;
        while (lo < hi) {
            int m = lo + (hi - lo) / 2;
            if (sat_sum(S, h, g->c0, g->c1, g->r0, m) >= half)
                hi = m;
            else
                lo = m + 1;
        }
        a->r1 = b->r0 = lo;
    }
    /* END STEP(mediancut) */
    a->energy = sat_sum(S, h, a->c0, a->c1, a->r0, a->r1);
    b->energy = sat_sum(S, h, b->c0, b->c1, b->r0, b->r1);
    return 1;
}

/* max-heap of regions by energy */
static void heap_push(region *hp, int *n, region g)
{
    int i = (*n)++;
    hp[i] = g;
    while (i > 0 && hp[(i - 1) / 2].energy < hp[i].energy) {
        region t = hp[i];
        hp[i] = hp[(i - 1) / 2];
        hp[(i - 1) / 2] = t;
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
        region t = hp[i];
        hp[i] = hp[m];
        hp[m] = t;
        i = m;
    }
    return top;
}

/* The strata: split the most energetic region until there are n_lights (or nothing splits).
 * S is the summed-area table, done[] receives the strata; returns how many. */
static int cut_strata(int w, int h, const double *S, int n_lights, region *heap, region *done)
{
    int n_heap = 0, n_done = 0;
    heap_push(heap, &n_heap, (region){0, w, 0, h, sat_sum(S, h, 0, w, 0, h)});
    while (n_heap > 0 && n_heap + n_done < n_lights) {
        region g = heap_pop(heap, &n_heap), a, b;
        if (g.energy <= 0 || !split_region(w, h, S, &g, &a, &b)) {
            done[n_done++] = g;
            continue;
        }
        heap_push(heap, &n_heap, a);
        heap_push(heap, &n_heap, b);
    }
    while (n_heap > 0) done[n_done++] = heap_pop(heap, &n_heap);
    return n_done;
}

/* Stratum g as a point light: its power and its energy centroid in image coordinates (Debevec
 * 2005), a weighted mean of texel centres, so it lies inside the stratum (the mean 3D direction
 * of a stratum wide in phi near a pole lies poleward of it, outside). */
static mediancut_point point_light(const mediancut_map *m, const region *g)
{
    int w = m->img->w, h = m->img->h;
    double sx = 0, sy = 0, se = 0;
    rgb power = rgb_gray(0);
    for (int c = g->c0; c < g->c1; c++)
        for (int r = g->r0; r < g->r1; r++) {
            double om = m->row_omega[r];
            rgb L = texel(m, c, r);
            power = rgb_madd(power, L, om); /* power = sum of L dOmega over the stratum */
            double e = rgb_avg(L) * om;
            sx += e * (c + 0.5);
            sy += e * (r + 0.5);
            se += e;
        }
    uv2 uv = {0.5 * (g->c0 + g->c1) / w, 0.5 * (g->r0 + g->r1) / h}; /* black: its centre */
    if (se > 0) uv = (uv2){sx / se / w, sy / se / h};
    mediancut_point pt = {latlong_uv_to_dir(uv), power, g->c0, g->c1, g->r0, g->r1};
    return pt;
}

int mediancut_build(const mediancut_map *m, int n_lights, mediancut_point **points, int *n_points,
                    distrib1d *choice, error *err)
{
    int w = m->img->w, h = m->img->h, H = h + 1, status = -1, n = 0;
    *points = NULL;
    *n_points = 0;
    memset(choice, 0, sizeof *choice);
    double *S = calloc((size_t)(w + 1) * (size_t)H, sizeof *S);
    region *heap = malloc((size_t)n_lights * sizeof *heap);
    region *done = malloc((size_t)n_lights * sizeof *done);
    double *wts = malloc((size_t)n_lights * sizeof *wts);
    if (!S || !heap || !done || !wts) {
        error_set(err, NULL, 0, "out of memory for median cut of a %d x %d map", w, h);
        goto cleanup;
    }
    /* summed-area table: S[c][r] = energy of columns [0,c) x rows [0,r) */
    for (int c = 0; c < w; c++)
        for (int r = 0; r < h; r++)
            S[(c + 1) * H + r + 1] =
                m->energy[(size_t)c * h + r] + S[c * H + r + 1] + S[(c + 1) * H + r] - S[c * H + r];
    n = cut_strata(w, h, S, n_lights, heap, done);
    mediancut_point *pts = calloc((size_t)n, sizeof *pts);
    if (!pts) {
        error_set(err, NULL, 0, "out of memory for %d median-cut lights", n);
        goto cleanup;
    }
    for (int k = 0; k < n; k++) {
        pts[k] = point_light(m, &done[k]);
        wts[k] = rgb_avg(pts[k].power);
    }
    if (distrib1d_init(choice, wts, n, err)) {
        free(pts);
        goto cleanup;
    }
    *points = pts;
    *n_points = n;
    status = 0;
cleanup:
    free(S);
    free(heap);
    free(done);
    free(wts);
    return status;
}

double mediancut_scratch_bytes(int w, int h, int n_lights)
{
    return (double)(w + 1) * (h + 1) * sizeof(double) +
           (double)n_lights * (2 * sizeof(region) + sizeof(double));
}

double mediancut_bytes(int n_lights)
{
    return (double)n_lights * (sizeof(mediancut_point) + 2 * sizeof(double));
}

vec3 mediancut_jitter(const mediancut_point *pt, int w, const double *cos_edge, double xi1,
                      double xi2)
{
    /* uniform in (cos theta, phi) over the stratum: for the shadow ray only */
    double u0 = cos_edge[pt->r0], u1 = cos_edge[pt->r1];
    double cos_t = u0 + xi1 * (u1 - u0), sin_t = sqrt(fmax(0.0, 1 - cos_t * cos_t));
    double phi = 2 * M_PI * (pt->c0 + xi2 * (pt->c1 - pt->c0)) / w;
    return vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

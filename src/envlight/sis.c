/* sis.c - structured importance sampling: layers at i sigma, their connected regions, the
 * farthest-point samples of each region, the strata as point lights
 * (see include/envtex/envlight/sis.h). */
#include "envtex/envlight/sis.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/envmaps/latlong.h"

/* bd of a texel that is a sample itself: above any dot product, so never the farthest again */
#define SIS_SEED_BD 2.0
/* |energy-weighted mean direction| / E below this: the stratum's directions all but cancel (it
 * spans more than a hemisphere), so its light sits at its sample; any real centroid is far above */
#define SIS_CENTROID_MIN 1e-6

/* What sis_stratify holds while it runs, per texel unless said: the texel centres' directions,
 * the best dot product to a sample of the texel's region and that sample, the union-find
 * parents, the regions (each texel's, the texels grouped by region, each region's start, energy,
 * solid angle and samples held) and the samples grouped by region (n). */
typedef struct work {
    int w, h, n;
    double *x, *y, *z;
    double *bd;
    int *near, *parent, *region_of, *order, *start, *held, *seed_start, *seed_order;
    double *energy, *omega, *row_omega;
} work;

/* work's texel-sized arrays: x, y, z, bd, energy, omega; parent, region_of, order, start, held,
 * seed_start (near becomes the result's label: sis_strata_bytes counts it) */
#define SIS_SCRATCH_PER_TEXEL (6 * sizeof(double) + 6 * sizeof(int))

double sis_scratch_bytes(int w, int h, int n)
{
    double texels = (double)w * h;
    return texels * SIS_SCRATCH_PER_TEXEL + 2.0 * sizeof(int) + (double)h * sizeof(double) +
           (double)n * sizeof(int);
}

double sis_strata_bytes(int w, int h, int n)
{
    return (double)w * h * sizeof(int) + 2.0 * n * sizeof(int);
}

static void work_free(work *k)
{
    free(k->x);
    free(k->y);
    free(k->z);
    free(k->bd);
    free(k->near);
    free(k->parent);
    free(k->region_of);
    free(k->order);
    free(k->start);
    free(k->held);
    free(k->seed_start);
    free(k->seed_order);
    free(k->energy);
    free(k->omega);
    free(k->row_omega);
}

static int work_alloc(work *k, int w, int h, int n)
{
    size_t t = (size_t)w * h;
    memset(k, 0, sizeof *k);
    k->w = w;
    k->h = h;
    k->n = n;
    k->x = malloc(t * sizeof(double));
    k->y = malloc(t * sizeof(double));
    k->z = malloc(t * sizeof(double));
    k->bd = malloc(t * sizeof(double));
    k->energy = malloc(t * sizeof(double));
    k->omega = malloc(t * sizeof(double));
    k->near = malloc(t * sizeof(int));
    k->parent = malloc(t * sizeof(int));
    k->region_of = malloc(t * sizeof(int));
    k->order = malloc(t * sizeof(int));
    k->start = malloc((t + 1) * sizeof(int));
    k->held = malloc(t * sizeof(int));
    k->seed_start = malloc((t + 1) * sizeof(int));
    k->seed_order = malloc((size_t)n * sizeof(int));
    k->row_omega = malloc((size_t)h * sizeof(double));
    if (!k->x || !k->y || !k->z || !k->bd || !k->energy || !k->omega || !k->near || !k->parent ||
        !k->region_of || !k->order || !k->start || !k->held || !k->seed_start || !k->seed_order ||
        !k->row_omega)
        return -1;
    for (int r = 0; r < h; r++) {
        k->row_omega[r] = latlong_texel_solid_angle(r, w, h);
        for (int c = 0; c < w; c++) { /* the texel's centre, latlong.h */
            vec3 d = latlong_uv_to_dir((uv2){(c + 0.5) / w, (r + 0.5) / h});
            size_t i = (size_t)r * w + c;
            k->x[i] = d.x;
            k->y[i] = d.y;
            k->z[i] = d.z;
        }
    }
    return 0;
}

/* ---- layers and their connected regions -------------------------------------------------- */

static int uf_find(int *p, int i)
{
    while (p[i] != i) i = p[i] = p[p[i]]; /* path halving */
    return i;
}

static void uf_union(int *p, int a, int b)
{
    if (p[a] < 0 || p[b] < 0) return; /* a texel outside the layer */
    a = uf_find(p, a);
    b = uf_find(p, b);
    if (a != b) p[a < b ? b : a] = a < b ? a : b; /* the smaller index is the root */
}

/* The connected regions of the texels with lum >= t (layer 0: all): neighbours left-right (the
 * phi seam wraps) and up-down, and all texels of the top row (of the bottom row) meet at the
 * pole.  Fills region_of (-1 outside), order, start, energy and omega; returns the count. */
static int layer_regions(work *k, const double *lum, double t, int all)
{
    int w = k->w, h = k->h, t_n = w * h;
    for (int i = 0; i < t_n; i++) k->parent[i] = all || lum[i] >= t ? i : -1;
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            int i = r * w + c;
            uf_union(k->parent, i, r * w + (c + 1) % w);
            if (r + 1 < h) uf_union(k->parent, i, i + w);
        }
    int top = -1, bottom = -1; /* the poles: every texel of row 0 touches every other */
    for (int c = 0; c < w; c++) {
        int b = (h - 1) * w + c;
        if (k->parent[c] >= 0) {
            if (top < 0) top = c;
            uf_union(k->parent, top, c);
        }
        if (k->parent[b] >= 0) {
            if (bottom < 0) bottom = b;
            uf_union(k->parent, bottom, b);
        }
    }
    int nreg = 0;
    for (int i = 0; i < t_n; i++) { /* a root comes before its texels: ids by first texel */
        if (k->parent[i] < 0) {
            k->region_of[i] = -1;
            continue;
        }
        int root = uf_find(k->parent, i);
        k->region_of[i] = root == i ? nreg++ : k->region_of[root];
    }
    for (int g = 0; g <= nreg; g++) k->start[g] = 0;
    for (int g = 0; g < nreg; g++) k->energy[g] = k->omega[g] = 0;
    for (int i = 0; i < t_n; i++) {
        int g = k->region_of[i];
        if (g < 0) continue;
        k->start[g + 1]++;
        double om = k->row_omega[i / w];
        k->energy[g] += lum[i] * om; /* E = sum L d(omega), in double */
        k->omega[g] += om;
    }
    for (int g = 0; g < nreg; g++) k->start[g + 1] += k->start[g];
    for (int g = 0; g < nreg; g++) k->held[g] = k->start[g]; /* fill cursors (reused below) */
    for (int i = 0; i < t_n; i++)
        if (k->region_of[i] >= 0) k->order[k->held[k->region_of[i]]++] = i;
    return nreg;
}

/* Gamma = E^a Omega^b (sis.h) */
static double importance(double energy, double omega)
{
    return pow(energy, SIS_A) * pow(omega, SIS_B);
}

/* ---- the farthest-point samples of one region (Hochbaum-Shmoys) -------------------------- */

/* Sample s (texel ts) joins region [b, e) of order: every texel there nearer to it than to its
 * samples so far moves to it.  Returns the texel now farthest from the region's samples. */
static int add_seed(work *k, int s, int ts, int b, int e)
{
    double sx = k->x[ts], sy = k->y[ts], sz = k->z[ts];
    int far = -1;
    double far_bd = SIS_SEED_BD;
    k->bd[ts] = SIS_SEED_BD;
    k->near[ts] = s;
    for (int j = b; j < e; j++) {
        int t = k->order[j];
        double d = k->x[t] * sx + k->y[t] * sy + k->z[t] * sz; /* cos of the angle */
        if (d > k->bd[t]) {
            k->bd[t] = d;
            k->near[t] = s;
        }
        if (k->bd[t] < far_bd) {
            far_bd = k->bd[t];
            far = t;
        }
    }
    return far;
}

/* Region g of layer `layer` holds n_g samples: those of brighter regions inside it, then new
 * ones, each the texel farthest from all before it (the first, if none: the brightest). */
static void stratify_region(work *k, const double *lum, sis_strata *out, int g, int n_g, int layer)
{
    int b = k->start[g], e = k->start[g + 1];
    for (int j = b; j < e; j++) {
        k->bd[k->order[j]] = -2;
        k->near[k->order[j]] = -1;
    }
    int far = -1;
    for (int q = k->seed_start[g]; q < k->seed_start[g + 1]; q++) {
        int s = k->seed_order[q];
        far = add_seed(k, s, out->seed[s], b, e);
    }
    int have = k->seed_start[g + 1] - k->seed_start[g];
    if (have == 0 && n_g > 0) {
        int best = k->order[b];
        for (int j = b; j < e; j++)
            if (lum[k->order[j]] > lum[best]) best = k->order[j];
        far = best;
    }
    for (; have < n_g && far >= 0 && out->n < k->n; have++) { /* k->n: the seeds' room */
        int s = out->n++;
        out->seed[s] = far;
        out->seed_layer[s] = layer;
        far = add_seed(k, s, far, b, e);
    }
}

/* Layer i: its regions, each region's n_R = floor(N Gamma_R / Gamma_4pi) (at least what it
 * already holds, at most its texels; the whole map exactly N), then their new samples. */
static void stratify_layer(work *k, const double *lum, sis_strata *out, int i, int n_total)
{
    int nreg = layer_regions(k, lum, out->threshold[i], i == 0);
    out->regions[i] = nreg;
    for (int g = 0; g <= nreg; g++) k->seed_start[g] = 0;
    for (int s = 0; s < out->n; s++) k->seed_start[k->region_of[out->seed[s]] + 1]++;
    for (int g = 0; g < nreg; g++) k->seed_start[g + 1] += k->seed_start[g];
    for (int g = 0; g < nreg; g++) k->held[g] = k->seed_start[g];
    for (int s = 0; s < out->n; s++) k->seed_order[k->held[k->region_of[out->seed[s]]]++] = s;
    int placed_before = out->n;
    out->layer_total[i] = 0;
    for (int g = 0; g < nreg; g++) {
        int held = k->seed_start[g + 1] - k->seed_start[g], size = k->start[g + 1] - k->start[g];
        double x = (double)n_total * importance(k->energy[g], k->omega[g]) / out->gamma_4pi;
        int n_g = i == 0 ? n_total : x >= size ? size : (int)floor(x); /* the rounding: floor */
        if (n_g < held) n_g = held; /* rounding never takes samples away (floor keeps it so) */
        stratify_region(k, lum, out, g, n_g, i);
        out->layer_total[i] += n_g;
    }
    out->layer_new[i] = out->n - placed_before;
}

void sis_strata_free(sis_strata *s)
{
    free(s->label);
    free(s->seed);
    free(s->seed_layer);
    memset(s, 0, sizeof *s);
}

/* sigma (solid-angle weighted), the thresholds and Gamma_4pi; -1 for a black map */
static int sis_thresholds(const work *k, const double *lum, sis_strata *out)
{
    double e = 0, om = 0, e2 = 0, lmax = 0;
    for (int i = 0; i < k->w * k->h; i++) {
        double o = k->row_omega[i / k->w];
        e += lum[i] * o;
        e2 += lum[i] * lum[i] * o;
        om += o;
        if (lum[i] > lmax) lmax = lum[i];
    }
    if (!(e > 0)) return -1;
    double mean = e / om;                                /* mu = sum L dw / 4 pi */
    out->sigma = sqrt(fmax(0.0, e2 / om - mean * mean)); /* sigma^2 = E[L^2] - mu^2 */
    out->gamma_4pi = importance(e, om);
    out->n_layers = 1;
    out->threshold[0] = 0;
    while (out->sigma > 0 && out->n_layers < SIS_MAX_LAYERS && lmax >= out->n_layers * out->sigma) {
        out->threshold[out->n_layers] = out->n_layers * out->sigma; /* t_i = i sigma */
        out->n_layers++;
    }
    return 0;
}

int sis_stratify(const double *lum, int w, int h, int n, budget *mem, sis_strata *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (w < 1 || h < 1 || n < 1 || (double)n > (double)w * h)
        return error_set(err, NULL, 0,
                         "structured importance sampling of a %d x %d map into %d "
                         "strata: the count must be in [1, %.0f]",
                         w, h, n, (double)w * h);
    double keep = sis_strata_bytes(w, h, n), scratch = sis_scratch_bytes(w, h, n);
    if (budget_charge(mem, keep + scratch, NULL, 0, err,
                      "structured importance sampling of a %d x %d map", w, h))
        return -1;
    work k;
    int status = -1;
    out->w = w;
    out->h = h;
    out->seed = malloc((size_t)n * sizeof(int));
    out->seed_layer = malloc((size_t)n * sizeof(int));
    if (work_alloc(&k, w, h, n) || !out->seed || !out->seed_layer) {
        error_set(err, NULL, 0, "out of memory stratifying a %d x %d map", w, h);
        goto cleanup;
    }
    if (sis_thresholds(&k, lum, out)) {
        error_set(err, NULL, 0, "the map is black: no energy to stratify");
        goto cleanup;
    }
    for (int i = out->n_layers - 1; i >= 0; i--) stratify_layer(&k, lum, out, i, n);
    /* layer 0 is the whole map: near[] is every texel's nearest sample of all */
    out->label = k.near;
    k.near = NULL;
    double min_bd = 1;
    for (int t = 0; t < w * h; t++) min_bd = fmin(min_bd, k.bd[t]);
    out->radius = acos(fmax(-1.0, fmin(1.0, min_bd)));
    status = 0;
cleanup:
    work_free(&k);
    budget_release(mem, scratch + (status ? keep : 0));
    if (status) sis_strata_free(out);
    return status;
}

/* ---- the strata as point lights (envsampling sis N) -------------------------------------- */

/* The shadow-ray tables: the texels of stratum k are order[first[k] .. first[k + 1]), with
 * cum[j] the energy of order[first[k] .. j] (inclusive). */
struct sis_shadow {
    int *order, *first;
    double *cum;
};

/* A texel channel as the light sees it: NaN, Inf and negative as 0 (envlight.h) */
static inline double clean(float v) { return v > 0 && v <= FLT_MAX ? (double)v : 0.0; }

double *sis_luminance(const image *map, double scale)
{
    double *lum = malloc((size_t)map->w * map->h * sizeof *lum);
    if (!lum) return NULL;
    for (int r = 0; r < map->h; r++)
        for (int c = 0; c < map->w; c++) {
            const float *p = image_px(map, c, r);
            lum[(size_t)r * map->w + c] = (clean(p[0]) + clean(p[1]) + clean(p[2])) / 3 * scale;
        }
    return lum;
}

double sis_envlight_bytes(int w, int h, int n)
{
    return (double)w * h * (sizeof(int) + sizeof(double)) + (n + 1.0) * sizeof(int) +
           (double)n * (sizeof(mediancut_point) + 2 * sizeof(double)) + sizeof(struct sis_shadow);
}

double sis_envlight_scratch_bytes(int w, int h, int n)
{
    return (double)w * h * sizeof(double) + sis_strata_bytes(w, h, n) + sis_scratch_bytes(w, h, n) +
           (double)n * (sizeof(double) + sizeof(vec3) + sizeof(int));
}

/* envlight's strata_free: the shadow-ray tables */
static void shadow_free(void *p)
{
    struct sis_shadow *sh = p;
    if (!sh) return;
    free(sh->order);
    free(sh->first);
    free(sh->cum);
    free(sh);
}

/* envmap frame -> world: A^T d / |A^T d| (envlight.c's frame_to_world) */
static vec3 to_world(const envlight *el, vec3 d)
{
    return el->identity ? d : vec3_normalize(mat4_dir(&el->to_world, d));
}

/* The lights of strata s: power = sum L d(omega) per channel, at the energy centroid (the
 * normalized energy-weighted mean direction; the sample itself if that mean is ~0, a stratum
 * of more than a hemisphere) */
static void make_points(envlight *el, const sis_strata *s, const double *lum, vec3 *mean,
                        double *wts)
{
    struct sis_shadow *sh = el->strata;
    for (int k = 0; k < s->n; k++) {
        mediancut_point *pt = &el->points[k];
        pt->c0 = el->w;
        pt->r0 = el->h;
        pt->c1 = pt->r1 = 0;
        mean[k] = vec3_make(0, 0, 0);
    }
    for (int j = 0; j < el->w * el->h; j++) {
        int t = sh->order[j], c = t % el->w, r = t / el->w, k = s->label[t];
        mediancut_point *pt = &el->points[k];
        double om = el->row_omega[r], s_env = el->env->scale;
        const float *p = image_px(el->map, c, r);
        rgb L = rgb_make(clean(p[0]) * s_env, clean(p[1]) * s_env, clean(p[2]) * s_env);
        pt->power = rgb_madd(pt->power, L, om); /* power = sum of L dOmega over the stratum */
        double e = lum[t] * om;
        vec3 d = latlong_uv_to_dir((uv2){(c + 0.5) / el->w, (r + 0.5) / el->h});
        mean[k] = vec3_add(mean[k], vec3_scale(d, e));
        int first = j == sh->first[k];
        sh->cum[j] = (first ? 0 : sh->cum[j - 1]) + e;
        if (c < pt->c0) pt->c0 = c;
        if (c + 1 > pt->c1) pt->c1 = c + 1;
        if (r < pt->r0) pt->r0 = r;
        if (r + 1 > pt->r1) pt->r1 = r + 1;
    }
    for (int k = 0; k < s->n; k++) {
        mediancut_point *pt = &el->points[k];
        double E = sh->cum[sh->first[k + 1] - 1], len = vec3_length(mean[k]);
        int t = s->seed[k];
        vec3 d =
            len > SIS_CENTROID_MIN * E
                ? vec3_scale(mean[k], 1 / len)
                : latlong_uv_to_dir((uv2){(t % el->w + 0.5) / el->w, (t / el->w + 0.5) / el->h});
        pt->dir = to_world(el, d);
        wts[k] = rgb_avg(pt->power);
    }
}

/* the lights of n strata for el, built with the common tables of mode sis */
static int build_lights(envlight *el, int n, error *err)
{
    int w = el->w, h = el->h, status = -1;
    sis_strata s = {0};
    vec3 *mean = malloc((size_t)n * sizeof *mean);
    double *wts = malloc((size_t)n * sizeof *wts);
    int *cursor = malloc((size_t)n * sizeof *cursor);
    double *lum = sis_luminance(el->map, el->env->scale);
    el->strata = calloc(1, sizeof(struct sis_shadow));
    el->strata_free = shadow_free;
    if (!mean || !wts || !cursor || !lum || !el->strata) {
        error_set(err, NULL, 0, "out of memory for structured importance sampling");
        goto cleanup;
    }
    if (n > w * h) n = w * h; /* a map smaller than the lights asked for: a light a texel */
    if (sis_stratify(lum, w, h, n, NULL, &s, err)) goto cleanup;
    struct sis_shadow *sh = el->strata;
    sh->order = malloc((size_t)w * h * sizeof(int));
    sh->cum = malloc((size_t)w * h * sizeof(double));
    sh->first = calloc((size_t)s.n + 1, sizeof(int));
    el->points = calloc((size_t)s.n, sizeof *el->points);
    if (!sh->order || !sh->cum || !sh->first || !el->points) {
        error_set(err, NULL, 0, "out of memory for %d structured-importance lights", s.n);
        goto cleanup;
    }
    for (int t = 0; t < w * h; t++) sh->first[s.label[t] + 1]++; /* texels grouped by stratum */
    for (int k = 0; k < s.n; k++) sh->first[k + 1] += sh->first[k];
    for (int k = 0; k < s.n; k++) cursor[k] = sh->first[k];
    for (int t = 0; t < w * h; t++) sh->order[cursor[s.label[t]]++] = t;
    make_points(el, &s, lum, mean, wts);
    el->n_points = s.n;
    if (distrib1d_init(&el->point_choice, wts, s.n, err)) goto cleanup;
    status = 0;
cleanup:
    sis_strata_free(&s);
    free(mean);
    free(wts);
    free(cursor);
    free(lum);
    return status;
}

/* release what mem holds above `before` (NULL: nothing) */
static void give_back(budget *mem, double before)
{
    if (mem) budget_release(mem, mem->used - before);
}

int sis_envlight_build(envlight *el, const envmap *env, envsampler_kind sampler, int n, budget *mem,
                       error *err)
{
    double before = mem ? mem->used : 0; /* on failure, envlight_build's share goes back too */
    if (envlight_build(el, env, ENVSAMPLING_SIS, sampler, n, mem, err)) return -1;
    if (el->mode != ENVSAMPLING_SIS) return 0; /* a black map: uniform directions (fell_back) */
    if (n < 1) n = 64;
    double keep = sis_envlight_bytes(el->w, el->h, n);
    double scratch = sis_envlight_scratch_bytes(el->w, el->h, n);
    if (budget_charge(mem, keep + scratch, NULL, 0, err,
                      "structured importance sampling of a %d x %d lat-long map", el->w, el->h)) {
        give_back(mem, before);
        envlight_free(el);
        return -1;
    }
    clock_t t0 = clock();
    int status = build_lights(el, n, err);
    el->build_seconds += (double)(clock() - t0) / CLOCKS_PER_SEC; /* the strata are tables too */
    budget_release(mem, scratch);
    if (status) {
        give_back(mem, before);
        envlight_free(el);
    }
    return status;
}

int sis_pick(const envlight *el, double xi, double xi1, double xi2, int *k, vec3 *shadow_dir,
             double *prob)
{
    if (el->n_points == 0 || !el->strata) return 0;
    int i = distrib1d_sample(&el->point_choice, xi, prob, NULL); /* by power */
    *k = i;
    *shadow_dir = sis_shadow_dir(el, i, xi1, xi2);
    return *prob > 0;
}

vec3 sis_shadow_dir(const envlight *el, int k, double xi1, double xi2)
{
    const struct sis_shadow *sh = el->strata;
    int lo = sh->first[k], hi = sh->first[k + 1] - 1, size = hi - lo + 1;
    double E = sh->cum[hi], frac;
    if (E > 0) { /* the first texel j with cum[j] > xi1 E: probability e_t / E */
        double target = xi1 * E;
        while (lo < hi) {
            int m = lo + (hi - lo) / 2;
            if (sh->cum[m] > target)
                hi = m;
            else
                lo = m + 1;
        }
        double before = lo > sh->first[k] ? sh->cum[lo - 1] : 0, e = sh->cum[lo] - before;
        frac = e > 0 ? (target - before) / e : 0.5;
    } else { /* a black stratum (never picked by power): its texels alike */
        double u = xi1 * size;
        lo += (int)u < size ? (int)u : size - 1;
        frac = u - floor(u);
    }
    frac = fmin(fmax(frac, 0.0), 1.0);
    int t = sh->order[lo], c = t % el->w, r = t / el->w;
    double u0 = el->cos_edge[r], u1 = el->cos_edge[r + 1];
    double cos_t = u0 + frac * (u1 - u0), sin_t = sqrt(fmax(0.0, 1 - cos_t * cos_t));
    double phi = 2 * M_PI * (c + xi2) / el->w; /* uniform in (cos theta, phi) in the texel */
    return to_world(el, vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos_t));
}

/* ---- the paper's figure ------------------------------------------------------------------ */

int sis_strata_picture(const sis_strata *s, const image *map, double scale, rgb edge, rgb mark,
                       image *out, error *err)
{
    int w = s->w, h = s->h;
    if (image_alloc(out, w, h, err)) return -1;
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            int l = s->label[r * w + c];
            int border =
                l != s->label[r * w + (c + 1) % w] || (r + 1 < h && l != s->label[(r + 1) * w + c]);
            rgb v = image_get(map, c, r);
            image_set(out, c, r, border ? edge : rgb_scale(v, scale));
        }
    for (int k = 0; k < s->n; k++)
        for (int dr = -1; dr <= 1; dr++)
            for (int dc = -1; dc <= 1; dc++) {
                int r = s->seed[k] / w + dr, c = (s->seed[k] % w + dc + w) % w;
                if (r >= 0 && r < h) image_set(out, c, r, mark);
            }
    return 0;
}

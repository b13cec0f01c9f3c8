/* compare.c - image metrics, thresholds and difference pictures (see
 * include/envtex/render/compare.h). */
#include "envtex/render/compare.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/io/tonemap.h"

static int same_size(const image *a, const image *ref, error *err)
{
    if (!a->px || !ref->px || a->w < 1 || a->h < 1)
        return error_set(err, NULL, 0, "cannot compare an empty image");
    if (a->w != ref->w || a->h != ref->h)
        return error_set(err, NULL, 0, "image sizes differ: %d x %d against a %d x %d reference",
                         a->w, a->h, ref->w, ref->h);
    return 0;
}

/* The largest `cap` values of a stream, kept in a min-heap: v[0] is the least of them, the one
 * a larger newcomer replaces.  O(log cap) a value, no allocation after the first. */
typedef struct largest {
    double *v;
    long n, cap;
} largest;

static void largest_sift_down(largest *t, long i)
{
    for (;;) {
        long c = 2 * i + 1; /* children 2i+1, 2i+2 */
        if (c >= t->n) return;
        if (c + 1 < t->n && t->v[c + 1] < t->v[c]) c++;
        if (t->v[i] <= t->v[c]) return;
        double x = t->v[i];
        t->v[i] = t->v[c];
        t->v[c] = x;
        i = c;
    }
}

static void largest_add(largest *t, double x)
{
    if (t->n < t->cap) { /* not full: append, sift up to its parent (i-1)/2 */
        long i = t->n++;
        t->v[i] = x;
        while (i > 0 && t->v[(i - 1) / 2] > t->v[i]) {
            double y = t->v[i];
            t->v[i] = t->v[(i - 1) / 2];
            t->v[(i - 1) / 2] = y;
            i = (i - 1) / 2;
        }
    } else if (t->cap > 0 && x > t->v[0]) { /* full: replace the least */
        t->v[0] = x;
        largest_sift_down(t, 0);
    }
}

/* sum of the k largest values kept (k <= n): drop the n - k least, add up the rest */
static double largest_sum(largest *t, long k)
{
    while (t->n > k) {
        t->v[0] = t->v[--t->n];
        largest_sift_down(t, 0);
    }
    double s = 0.0;
    for (long i = 0; i < t->n; i++) s += t->v[i];
    return s;
}

int compare_metrics(const image *a, const image *ref, compare_result *out, error *err)
{
    memset(out, 0, sizeof *out);
    out->max_x = out->max_y = -1;
    if (same_size(a, ref, err)) return -1;
    double se = 0.0, rel = 0.0, max_abs = 0.0; /* sums in double: up to 2^28 pixels */
    long used = 0;
    largest top = {NULL, 0, (long)((double)a->w * a->h * COMPARE_RELMSE_TRIM)};
    if (top.cap > 0 && !(top.v = malloc((size_t)top.cap * sizeof *top.v)))
        return error_set(err, NULL, 0, "out of memory comparing %d x %d images", a->w, a->h);
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            const float *p = image_px(a, x, y), *q = image_px(ref, x, y);
            int fa = image_px_is_finite(p), fr = image_px_is_finite(q);
            if (!fa) out->nonfinite++;
            if (!fr) out->ref_nonfinite++;
            if (!fa || !fr) continue;
            used++;
            double rel_px = 0.0;
            for (int k = 0; k < 3; k++) {
                double d = (double)p[k] - (double)q[k];
                se += d * d; /* (a - ref)^2 */
                rel_px +=
                    d * d / ((double)q[k] * q[k] + COMPARE_RELMSE_EPSILON); /* / (ref^2 + eps) */
                if (fabs(d) > max_abs) {
                    max_abs = fabs(d);
                    out->max_x = x;
                    out->max_y = y;
                }
            }
            rel += rel_px;
            largest_add(&top, rel_px);
        }
    out->pixels = used;
    long trim = (long)((double)used * COMPARE_RELMSE_TRIM); /* <= top.cap: used <= w h */
    double rel_top = largest_sum(&top, trim);
    free(top.v);
    if (used == 0) { /* nothing finite to compare: the metrics are undefined */
        out->rmse = out->relmse = out->relmse_trim = out->max_abs = out->psnr = NAN;
        return 0;
    }
    double mse = se / (3.0 * (double)used);
    out->rmse = sqrt(mse);
    out->relmse = rel / (3.0 * (double)used);
    out->relmse_trim =
        fmax(rel - rel_top, 0.0) / (3.0 * (double)(used - trim)); /* rounding: >= 0 */
    out->max_abs = max_abs;
    out->psnr = mse > 0.0 ? -10.0 * log10(mse) : INFINITY; /* 10 log10(peak^2 / mse), peak 1 */
    return 0;
}

compare_thresholds_params compare_thresholds_defaults(void)
{
    return (compare_thresholds_params){
        .fail_thresh = 0.004, .fail_relative = 0.0, .fail_percent = 0.02, .hard_thresh = INFINITY};
}

int compare_thresholds(const image *a, const image *ref, const compare_thresholds_params *p,
                       compare_verdict *v)
{
    memset(v, 0, sizeof *v);
    v->max_x = v->max_y = -1;
    error err = {0};
    if (same_size(a, ref, &err)) {
        size_t n = strlen(err.msg); /* copied by hand: a message is cut, never a warning */
        if (n >= sizeof v->why) n = sizeof v->why - 1;
        memcpy(v->why, err.msg, n);
        v->why[n] = '\0';
        return -1;
    }
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            const float *pa = image_px(a, x, y), *pr = image_px(ref, x, y);
            v->pixels++;
            if (!image_px_is_finite(pa) || !image_px_is_finite(pr)) {
                v->nonfinite++;
                continue;
            }
            double diff = 0.0;
            int fails = 0;
            for (int k = 0; k < 3; k++) {
                double d = fabs((double)pa[k] - (double)pr[k]);
                if (d > diff) diff = d;
                /* relative mode: also over fail_relative * mean(|a|, |ref|) in this channel */
                double mean = 0.5 * (fabs((double)pa[k]) + fabs((double)pr[k]));
                if (d > p->fail_thresh && (p->fail_relative <= 0.0 || d > p->fail_relative * mean))
                    fails = 1;
            }
            if (fails) v->failed++;
            if (diff > p->hard_thresh) v->hard_failed++;
            if (diff > v->max_diff) {
                v->max_diff = diff;
                v->max_x = x;
                v->max_y = y;
            }
        }
    v->failed_percent = 100.0 * (double)v->failed / (double)v->pixels; /* pixels >= 1 here */
    int bad_percent = v->failed_percent > p->fail_percent;
    v->pass = !bad_percent && v->hard_failed == 0 && v->nonfinite == 0;
    if (v->pass) {
        snprintf(v->why, sizeof v->why, "ok: %ld of %ld pixels (%.3g%%) over %g, max difference %g",
                 v->failed, v->pixels, v->failed_percent, p->fail_thresh, v->max_diff);
        return 0;
    }
    size_t at = 0;
    int n;
    if (bad_percent) {
        n = snprintf(v->why + at, sizeof v->why - at,
                     "%ld of %ld pixels (%.3g%% > %g%%) differ by more than %g; ", v->failed,
                     v->pixels, v->failed_percent, p->fail_percent, p->fail_thresh);
        if (n > 0 && (size_t)n < sizeof v->why - at) at += (size_t)n;
    }
    if (v->hard_failed) {
        n = snprintf(v->why + at, sizeof v->why - at,
                     "%ld pixels differ by more than the hard limit %g; ", v->hard_failed,
                     p->hard_thresh);
        if (n > 0 && (size_t)n < sizeof v->why - at) at += (size_t)n;
    }
    if (v->nonfinite) {
        n = snprintf(v->why + at, sizeof v->why - at, "%ld pixels are NaN or Inf; ", v->nonfinite);
        if (n > 0 && (size_t)n < sizeof v->why - at) at += (size_t)n;
    }
    n = snprintf(v->why + at, sizeof v->why - at, "max difference %g", v->max_diff);
    if (n > 0 && (size_t)n < sizeof v->why - at) at += (size_t)n;
    if (v->max_x >= 0) /* none when no pixel pair was finite */
        snprintf(v->why + at, sizeof v->why - at, " at (%d, %d)", v->max_x, v->max_y);
    return -1;
}

/* palette stops, sRGB-encoded 8-bit: black, blue, green, yellow, red (one per decade) */
static const unsigned char diff_stops[5][3] = {
    {0, 0, 0}, {0, 0, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
static const unsigned char diff_nonfinite[3] = {255, 0, 255}; /* magenta */

int compare_diff_image(const image *a, const image *ref, image *out, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    if (same_size(a, ref, err)) return -1;
    if (image_alloc(out, a->w, a->h, err)) return -1;
    const double decades = log10(COMPARE_DIFF_MAX / COMPARE_DIFF_MIN); /* 4 stops apart */
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            const float *pa = image_px(a, x, y), *pr = image_px(ref, x, y);
            float *o = image_px(out, x, y);
            if (!image_px_is_finite(pa) || !image_px_is_finite(pr)) {
                for (int k = 0; k < 3; k++)
                    o[k] = (float)tonemap_srgb_decode(diff_nonfinite[k] / 255.0);
                continue;
            }
            double d = 0.0;
            for (int k = 0; k < 3; k++) d = fmax(d, fabs((double)pa[k] - (double)pr[k]));
            /* t in [0, 4]: log10(d / dmin), clamped; d = 0 is below dmin, so no log of 0 */
            double t = d <= COMPARE_DIFF_MIN   ? 0.0
                       : d >= COMPARE_DIFF_MAX ? decades
                                               : log10(d / COMPARE_DIFF_MIN);
            int i = (int)t;
            if (i > 3) i = 3;
            double f = t - i; /* between stop i and i + 1 */
            for (int k = 0; k < 3; k++) {
                double e = ((1.0 - f) * diff_stops[i][k] + f * diff_stops[i + 1][k]) / 255.0;
                o[k] = (float)tonemap_srgb_decode(e); /* so the default PNG tone mapping gives e */
            }
        }
    return 0;
}

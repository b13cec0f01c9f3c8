/* gradetest.c - per-pixel z-tests of a noisy render against a reference
 * (see include/envtex/render/gradetest.h). */
#include "envtex/render/gradetest.h"

#include <string.h>

gradetest_params gradetest_defaults(void)
{
    gradetest_params p;
    p.alpha = 0.01;
    p.max_fail_fraction = 0.005;
    p.global_z = 5;
    p.img_spp = p.ref_spp = 1;
    p.var_spp = 0;
    p.rel_floor = 1e-4;
    return p;
}

double gradetest_z_for_alpha(double a)
{
    /* invert the two-sided tail P(|Z| > z) = erfc(z / sqrt 2) = a by bisection: erfc is
     * monotone and the answer lies in [0, 40] for any a >= 1e-300 */
    if (!(a > 0)) return 40;
    if (a >= 1) return 0;
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; i++) {
        double m = 0.5 * (lo + hi);
        if (erfc(m / sqrt(2.0)) > a)
            lo = m;
        else
            hi = m;
    }
    return 0.5 * (lo + hi);
}

int gradetest_run(const image *img, const image *ref, const image *var, const gradetest_params *p,
                  gradetest_result *out, image *fail_map, error *err)
{
    memset(out, 0, sizeof *out);
    if (fail_map) fail_map->w = fail_map->h = 0, fail_map->px = NULL;
    if (img->w != ref->w || img->h != ref->h || var->w != ref->w || var->h != ref->h)
        return error_set(err, NULL, 0, "sizes differ: image %dx%d, reference %dx%d, variance %dx%d",
                         img->w, img->h, ref->w, ref->h, var->w, var->h);
    if (!(p->img_spp > 0) || !(p->ref_spp > 0) || !(p->var_spp >= 0))
        return error_set(err, NULL, 0, "sample counts must be > 0");
    if (fail_map && image_alloc(fail_map, img->w, img->h, err)) return -1;
    long n = (long)img->w * img->h;
    out->pixels = n;
    out->z_threshold = gradetest_z_for_alpha(p->alpha / (double)n); /* Bonferroni: alpha / N */
    /* V var_spp is the variance of one sample; var of (img - ref) = V (var_spp / img_spp +
     * var_spp / ref_spp), which with var_spp = ref_spp is V (ref_spp / img_spp + 1) */
    double var_spp = p->var_spp > 0 ? p->var_spp : p->ref_spp;
    double ratio = var_spp / p->img_spp + var_spp / p->ref_spp;
    double sum_diff = 0, sum_var = 0; /* the global test: the image total */
    for (int y = 0; y < img->h; y++)
        for (int x = 0; x < img->w; x++) {
            double v = rgb_avg(image_get(var, x, y)), r = rgb_avg(image_get(ref, x, y));
            if (!isfinite(r) || !isfinite(v) || v < 0) {
                if (fail_map) image_free(fail_map);
                return error_set(err, NULL, 0,
                                 "reference or variance pixel (%d, %d) is not a finite, "
                                 "non-negative number",
                                 x, y);
            }
        }
    for (int y = 0; y < img->h; y++)
        for (int x = 0; x < img->w; x++) {
            double a = rgb_avg(image_get(img, x, y)), r = rgb_avg(image_get(ref, x, y));
            /* A variance estimated from a few samples can be 0 where the samples happened to
             * agree (the edge of an object, a rarely hit light): take the largest variance of
             * the 3 x 3 neighbourhood, a pixel's variance being close to its neighbours'. */
            double v = 0;
            for (int j = y - 1; j <= y + 1; j++)
                for (int i = x - 1; i <= x + 1; i++)
                    if (i >= 0 && j >= 0 && i < img->w && j < img->h)
                        v = fmax(v, rgb_avg(image_get(var, i, j)));
            double v0 = rgb_avg(image_get(var, x, y));
            rgb mark = rgb_gray(0.2);
            if (!isfinite(a)) {
                out->nonfinite++;
                out->failed++;
                mark = rgb_make(1, 0, 1);
            } else {
                /* var of (img - ref), plus the rounding floor */
                double floor_sd = p->rel_floor * fmax(fabs(r), 1e-3);
                double z = (a - r) / sqrt(v * ratio + floor_sd * floor_sd);
                sum_diff += a - r;
                sum_var += v0 * ratio + floor_sd * floor_sd;
                if (fabs(z) > out->z_threshold) {
                    out->failed++;
                    mark = z > 0 ? rgb_make(1, 0, 0) : rgb_make(0, 0.3, 1);
                }
            }
            if (fail_map) image_set(fail_map, x, y, mark);
        }
    out->failed_fraction = (double)out->failed / (double)n;
    /* Z of the image total: sum (img - ref) / sqrt(sum var); a bias spread over the image
     * adds up here even when no single pixel fails */
    out->mean_z = sum_var > 0 ? sum_diff / sqrt(sum_var) : 0;
    out->global_stat = fabs(out->mean_z);
    int ok_pixels = out->failed_fraction <= p->max_fail_fraction;
    int ok_global = out->global_stat <= p->global_z;
    out->pass = ok_pixels && ok_global && out->nonfinite == 0;
    snprintf(out->why, sizeof out->why, "%s%s%s%s", out->pass ? "ok" : "",
             ok_pixels ? "" : "too many pixels fail their z-test; ",
             ok_global ? "" : "the mean z is off (a bias across the image); ",
             out->nonfinite ? "NaN/Inf pixels; " : "");
    return 0;
}

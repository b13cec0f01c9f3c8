/* gradetest.h - noise-aware grading: is a noisy render a correct estimate of a reference?
 * Each pixel is a z-test of the image's mean against the reference's (docs/teaching.md):
 *
 *     gradetest_params p = gradetest_defaults();
 *     gradetest_result r;
 *     if (gradetest_run(&img, &ref, &var, &p, &r, NULL, &err)) ...   // sizes differ, ...
 *     puts(r.pass ? "PASS" : "FAIL");
 *
 *   z = (img - ref) / sqrt(var_img + var_ref + floor^2)     per pixel, on the channel average
 *   var_img = V var_spp / img_spp,  var_ref = V var_spp / ref_spp
 * VAR: `envtex render --variance` (sample variance / var_spp); V: VAR's largest in the pixel's
 * 3 x 3 neighbourhood; floor = rel_floor max(|ref|, 1e-3).  A pixel fails when its two-sided
 * p-value is below alpha / N (N pixels).  The render passes if at most
 * max_fail_fraction of the pixels fail, no pixel of img is NaN or Inf, and the image total
 *   Z = sum (img - ref) / sqrt(sum (var_img + var_ref + floor^2))   (each pixel's own VAR)
 * has |Z| <= global_z.
 */
#ifndef ENVTEX_GRADETEST_H
#define ENVTEX_GRADETEST_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"

typedef struct gradetest_params {
    double alpha;             /* family-wise significance, default 0.01 */
    double max_fail_fraction; /* pixels allowed to fail, default 0.005 */
    double global_z;          /* bound on |Z| of the image total, default 5 */
    double img_spp, ref_spp;  /* sample counts (only ratios matter); default equal */
    double var_spp;           /* VAR's sample count; 0 (default): ref_spp */
    /* the floor on the standard deviation, relative to the reference: 1e-4 */
    double rel_floor;
} gradetest_params;

gradetest_params gradetest_defaults(void);

typedef struct gradetest_result {
    int pass;
    long pixels;
    long failed; /* pixels whose p-value is below alpha / N */
    double failed_fraction;
    double mean_z;      /* Z of the image total (signed) */
    double global_stat; /* |Z| */
    double z_threshold; /* |z| above which a pixel fails */
    long nonfinite;     /* NaN or Inf pixels of img (any fails) */
    char why[256];      /* one line */
} gradetest_result;

/* 0 with the verdict in *out, or -1 with *err when it cannot run (sizes differ, a sample count
 * <= 0, a ref or var channel average not finite or negative, memory; fail_map then empty).
 * fail_map (may be NULL): w x h, red a failed pixel too bright, blue too dark, magenta NaN /
 * Inf, grey elsewhere (free with image_free). */
int gradetest_run(const image *img, const image *ref, const image *var, const gradetest_params *p,
                  gradetest_result *out, image *fail_map, error *err);

/* |z| threshold of a two-sided test at significance a: Phi^-1(1 - a / 2). */
double gradetest_z_for_alpha(double a);

#endif

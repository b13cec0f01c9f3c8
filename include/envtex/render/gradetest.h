/* gradetest.h - noise-aware grading: is a noisy render a correct estimate of a reference?
 *
 * A student's path tracer uses its own random numbers, so its image never matches a golden
 * image pixel for pixel.  Instead (in the style of Mitsuba's render tests) each pixel is a
 * z-test of the student's mean against the reference mean, knowing the variance of the mean:
 *
 *   z = (img - ref) / sqrt(var_img + var_ref + floor^2)     per pixel, on the channel average
 *   var_img = V * var_spp / img_spp      (the same estimator at the image's sample count)
 *   var_ref = V * var_spp / ref_spp      (and at the reference's)
 *
 * VAR is what `envtex render --variance` writes: the per-pixel sample variance of a render of
 * var_spp samples divided by var_spp (usually the reference's render, var_spp = ref_spp);
 * V is its largest value in the pixel's 3 x 3 neighbourhood (an estimate from
 * few samples is 0 wherever they happened to agree, e.g. at an object's edge).  Two-sided
 * p-values are compared with alpha / N (Bonferroni over the N pixels); the render passes if at
 * most `max_fail_fraction` of the pixels fail (variance estimates are themselves noisy, and
 * fireflies exist) AND the image total passes its own z-test AND no pixel of img is NaN or
 * infinite (one is enough to fail the whole render: a student's NaN is a bug, not noise),
 *   Z = sum (img - ref) / sqrt(sum (var_img + var_ref + floor^2)),   |Z| <= global_z,
 * with each pixel's own VAR here, not the neighbourhood's largest V: a bias spread thinly over
 * the whole image (a missing 1/pi, a pdf off by sin theta) adds up there even when no single
 * pixel fails.  floor = rel_floor max(|ref|, 1e-3) (a black pixel still gets a floor).
 *
 *     gradetest_params p = gradetest_defaults();
 *     gradetest_result r;
 *     if (gradetest_run(&img, &ref, &var, &p, &r, NULL, &err)) ...   // sizes differ, ...
 *     puts(r.pass ? "PASS" : "FAIL");
 */
#ifndef ENVTEX_GRADETEST_H
#define ENVTEX_GRADETEST_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"

typedef struct gradetest_params {
    double alpha;             /* family-wise significance, default 0.01 */
    double max_fail_fraction; /* pixels allowed to fail, default 0.005 (0.5%) */
    double global_z;          /* bound on |Z| of the image total, default 5 */
    double img_spp, ref_spp;  /* sample counts (only their ratios matter); default equal */
    double var_spp;           /* VAR's render's sample count; 0 (default): VAR is REF's */
    /* Absolute floor added to the standard deviation so a pixel of zero variance (a constant
     * background) tolerates float rounding, relative to the reference value: 1e-4. */
    double rel_floor;
} gradetest_params;

gradetest_params gradetest_defaults(void);

typedef struct gradetest_result {
    int pass;
    long pixels;
    long failed;              /* pixels whose p-value is below alpha / N */
    double failed_fraction;
    double mean_z;            /* Z of the image total (signed) */
    double global_stat;       /* |Z| */
    double z_threshold;       /* |z| above which a pixel fails */
    long nonfinite;           /* pixels of img that are NaN or Inf: any fails the render */
    char why[256];            /* one line */
} gradetest_result;

/* Run the test: 0 with the verdict in *out (pass or fail), or -1 with *err set when it cannot
 * run (sizes differ, a sample count <= 0 (var_spp < 0), a reference or variance pixel whose
 * channel average is not finite or is negative, out of memory; fail_map then holds nothing).
 * `fail_map` (may be
 * NULL) receives a w x h image: red where a pixel failed with img too bright, blue where too
 * dark, magenta where img is NaN or Inf, grey elsewhere (allocated; free with image_free). */
int gradetest_run(const image *img, const image *ref, const image *var, const gradetest_params *p,
                  gradetest_result *out, image *fail_map, error *err);

/* |z| threshold of a two-sided test at significance a: Phi^-1(1 - a / 2). */
double gradetest_z_for_alpha(double a);

#endif

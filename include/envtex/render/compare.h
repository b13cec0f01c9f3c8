/* compare.h - comparing two images: error metrics, pass/fail thresholds for golden-image tests,
 * and a false-colour difference picture (the unit tests, the golden harness, `envtex compare`).
 *
 *     compare_result m;
 *     if (compare_metrics(&render, &ref, &m, &err)) return -1;   // sizes differ
 *     printf("rmse %g relmse %g psnr %g dB\n", m.rmse, m.relmse, m.psnr);
 *
 *     compare_thresholds_params p = compare_thresholds_defaults();
 *     compare_verdict v;
 *     if (compare_thresholds(&render, &ref, &p, &v)) puts(v.why);   // failed: why
 *     compare_diff_image(&render, &ref, &diff, &err);              // where (false colour)
 *
 * Both images are linear RGB.  `a` is the image under test, `ref` the reference.
 */
#ifndef ENVTEX_COMPARE_H
#define ENVTEX_COMPARE_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* relMSE = mean of (a - ref)^2 / (ref^2 + COMPARE_RELMSE_EPSILON) */
#define COMPARE_RELMSE_EPSILON 1e-2

/* relmse_trim leaves out this fraction of the pixels, those with the largest errors (rounded
 * down: images under 1000 pixels leave out none). */
#define COMPARE_RELMSE_TRIM 1e-3

typedef struct compare_result {
    double rmse;        /* sqrt(mean over pixels and channels of (a - ref)^2) */
    double relmse;      /* mean over pixels and channels of (a - ref)^2 / (ref^2 + epsilon) */
    double relmse_trim; /* relmse without the COMPARE_RELMSE_TRIM largest pixels */
    double psnr;        /* 10 log10(1 / mse) in dB (peak 1.0); +INFINITY when equal */
    double max_abs;     /* largest channel |a - ref| */
    int max_x, max_y;   /* where max_abs occurs (-1, -1 if none) */
    long nonfinite;     /* pixels of `a` with a NaN or Inf channel */
    long ref_nonfinite; /* ... of `ref` */
    long pixels;        /* pixels compared: those finite in both images */
} compare_result;

/* Metrics of `a` against `ref`; pixels not finite in either are counted and left out (none
 * left: the metrics are NaN).  -1 with a message if the sizes differ, an image is empty, or
 * there is no memory. */
int compare_metrics(const image *a, const image *ref, compare_result *out, error *err);

/* A pixel fails if its largest channel |a - ref| exceeds fail_thresh and (fail_relative > 0)
 * fail_relative * (|a| + |ref|) / 2.  The images fail if over fail_percent % of the pixels
 * fail, any differs by over hard_thresh, any is NaN / Inf, or the sizes differ. */
typedef struct compare_thresholds_params {
    double fail_thresh;   /* absolute difference a pixel may have */
    double fail_relative; /* 0: off; else the relative difference a pixel may also have */
    double fail_percent;  /* % of pixels allowed to fail */
    double hard_thresh;   /* no pixel may differ more; INFINITY: off */
} compare_thresholds_params;

/* Strict defaults, loosened per test: fail_thresh 0.004, fail_relative 0 (off), fail_percent
 * 0.02 (%), hard_thresh INFINITY (off). */
compare_thresholds_params compare_thresholds_defaults(void);

typedef struct compare_verdict {
    int pass;              /* 1 if the images pass */
    long pixels;           /* pixels compared (0 if the sizes differ) */
    long failed;           /* pixels that fail */
    double failed_percent; /* 100 * failed / pixels */
    long hard_failed;      /* pixels over hard_thresh */
    long nonfinite;        /* pixels with a NaN / Inf in a or ref */
    double max_diff;       /* largest finite pixel difference */
    int max_x, max_y;      /* where (-1, -1 if none) */
    char why[256];         /* one line: "ok" or the reasons it failed */
} compare_verdict;

/* Judge `a` against `ref` into *v: 0 pass, -1 fail (any reason, sizes too: v->why says). */
int compare_thresholds(const image *a, const image *ref, const compare_thresholds_params *p,
                       compare_verdict *v);

/* The difference picture of d = largest channel |a - ref|, linear in log10(d): <= 1e-4 black,
 * 1e-3 blue, 1e-2 green, 1e-1 yellow, >= 1 red; NaN / Inf magenta. */
#define COMPARE_DIFF_MIN 1e-4
#define COMPARE_DIFF_MAX 1.0

/* The false-colour difference image of `a` against `ref` into *out (allocated; free with
 * image_free), in linear values that the default tone mapping writes as the palette exactly.
 * -1 with a message if the sizes differ. */
int compare_diff_image(const image *a, const image *ref, image *out, error *err);

#endif

/* cmd_compare.c - `envtex compare A B [--diff D.png] [--fail-percent P --fail T --hard H]`
 * (compare.h) and `envtex compare --test IMG REF VAR` (gradetest.h, the noise-aware test). */
#include <stdio.h>
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/io/imageio.h"
#include "envtex/render/compare.h"
#include "envtex/render/gradetest.h"

/* envtex compare --test IMG REF VAR: the noise-aware test (gradetest.h) */
static int cmd_compare_test(int argc, char **argv)
{
    const char *paths[3] = {NULL, NULL, NULL}, *map_path = NULL;
    int np = 0;
    double mem_limit = BUDGET_DEFAULT;
    gradetest_params p = gradetest_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--diff")) {
            if (!(map_path = cli_opt_value(argc, argv, &i))) return 1;
            continue;
        }
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &mem_limit)) return 1;
            continue;
        }
        if (!strcmp(a, "--img-spp")) target = &p.img_spp;
        else if (!strcmp(a, "--ref-spp")) target = &p.ref_spp;
        else if (!strcmp(a, "--alpha")) target = &p.alpha;
        else if (!strcmp(a, "--max-fail")) target = &p.max_fail_fraction;
        if (target) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, target) || !(*target > 0)) return cli_usage_error("option needs a number > 0, got '%s'", v);
            /* significance and share of pixels are fractions: --max-fail 0.5 means half the pixels
             * (not 0.5%), and 5 would let every pixel fail */
            if (target == &p.alpha && !(*target < 1))
                return cli_usage_error("--alpha is a significance level in (0, 1), got '%s'", v);
            if (target == &p.max_fail_fraction && !(*target <= 1))
                return cli_usage_error("--max-fail is a fraction of the pixels in (0, 1] (0.005 is 0.5%%), got '%s'", v);
        } else if (a[0] == '-' && a[1]) return cli_usage_error("unknown option '%s'", a);
        else if (np < 3) paths[np++] = a;
        else return cli_usage_error("unexpected argument '%s'", a);
    }
    if (np < 3) return cli_usage_error("%s", "compare --test needs IMG REF VAR (VAR from 'envtex render --variance')");
    error err = {0};
    image im[3] = {{0}}, map = {0};
    int status = 1;
    budget mb, *mem = cli_run_budget(&mb, mem_limit);
    if (map_path && (cli_check_output(map_path, &err) || cli_check_not_replacing(map_path, paths, 3, &err))) goto done;
    for (int k = 0; k < 3; k++)
        if (imageio_read(paths[k], &im[k], mem, &err)) goto done;
    /* A PNG (the course skeleton's raytrace.png) is clamped to [0, 1] and rounded to 8 bits: every
     * pixel brighter than 1 would fail as a bias and the verdict say nothing about the code */
    static const char *const roles[3] = {"image", "reference", "variance"};
    for (int k = 0; k < 3; k++)
        if (imageio_detect(paths[k]) == IMAGEIO_PNG) {
            error_set(&err, paths[k], 0, "the %s is a PNG (8 bits clamped to [0, 1]): the noise-aware test needs "
                      "the linear render (.exr, .pfm or .hdr)", roles[k]);
            goto done;
        }
    gradetest_result r;
    if (gradetest_run(&im[0], &im[1], &im[2], &p, &r, map_path ? &map : NULL, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err: they overlap */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, paths[0], 0, "%s", msg);
        goto done;
    }
    if (map_path && imageio_write(map_path, &map, NULL, &err)) goto done;
    printf("%s: %ld of %ld pixels (%.4f%%, allowed %.4f%%) fail |z| > %.2f; image total Z = %.2f "
           "(allowed |Z| <= %.2f); %ld NaN/Inf: %s\n",
           r.pass ? "PASS" : "FAIL", r.failed, r.pixels, 100 * r.failed_fraction, 100 * p.max_fail_fraction,
           r.z_threshold, r.mean_z, p.global_z, r.nonfinite, r.why);
    status = r.pass ? 0 : 2;
done:
    if (status == 1) error_print(&err, stderr);
    for (int k = 0; k < 3; k++) image_free(&im[k]);
    image_free(&map);
    return status;
}

int cmd_compare(int argc, char **argv)
{
    if (argc > 0 && !strcmp(argv[0], "--test")) return cmd_compare_test(argc - 1, argv + 1);
    const char *a_path = NULL, *b_path = NULL, *diff_path = NULL;
    compare_thresholds_params th = compare_thresholds_defaults();
    int use_thresholds = 0;
    double mem_limit = BUDGET_DEFAULT;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--diff")) {
            if (!(diff_path = cli_opt_value(argc, argv, &i))) return 1;
            continue;
        }
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &mem_limit)) return 1;
            continue;
        }
        if (!strcmp(a, "--fail-percent")) target = &th.fail_percent;
        else if (!strcmp(a, "--fail")) target = &th.fail_thresh;
        else if (!strcmp(a, "--hard")) target = &th.hard_thresh;
        if (target) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, target) || *target < 0) return cli_usage_error("a threshold must be a number >= 0, got '%s'", v);
            use_thresholds = 1;
        } else if (a[0] == '-' && a[1]) return cli_usage_error("unknown option '%s'", a);
        else if (!a_path) a_path = a;
        else if (!b_path) b_path = a;
        else return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!b_path) return cli_usage_error("%s", "compare needs two images: A (tested) and B (reference)");
    error err = {0};
    image a = {0}, b = {0}, d = {0};
    int status = 1;
    const char *inputs[2] = {a_path, b_path};
    if (diff_path && (cli_check_output(diff_path, &err) || cli_check_not_replacing(diff_path, inputs, 2, &err))) goto done;
    budget mb, *mem = cli_run_budget(&mb, mem_limit);
    if (imageio_read(a_path, &a, mem, &err) || imageio_read(b_path, &b, mem, &err)) goto done;
    compare_result cr;
    if (compare_metrics(&a, &b, &cr, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err: they overlap */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, a_path, 0, "%s (against %s)", msg, b_path);
        goto done;
    }
    /* nan: A's NaN/Inf pixels; ref_nan: B's.  Either pixel non-finite leaves it out of the sums */
    printf("rmse=%.6g relmse=%.6g psnr=%.3f max_abs=%.6g nan=%ld relmse_trim=%.6g ref_nan=%ld\n", cr.rmse, cr.relmse,
           cr.psnr, cr.max_abs, cr.nonfinite, cr.relmse_trim, cr.ref_nonfinite);
    if (diff_path) {
        if (compare_diff_image(&a, &b, &d, &err) || imageio_write(diff_path, &d, NULL, &err)) goto done;
    }
    status = 0;
    if (use_thresholds) {
        compare_verdict v;
        compare_thresholds(&a, &b, &th, &v);
        char where[64] = ""; /* where the largest difference is; none when every pixel agrees */
        if (v.max_x >= 0) snprintf(where, sizeof where, " at (%d, %d)", v.max_x, v.max_y);
        printf("%s: %ld of %ld pixels (%.3f%%) differ by more than %g (allowed %g%%), max %.6g%s (hard limit %g), %ld NaN/Inf: %s\n",
               v.pass ? "PASS" : "FAIL", v.failed, v.pixels, v.failed_percent, th.fail_thresh,
               th.fail_percent, v.max_diff, where, th.hard_thresh, v.nonfinite, v.why);
        if (!v.pass) status = 2; /* a failed comparison is not an error: status 2 */
    }
done:
    if (status == 1) error_print(&err, stderr);
    image_free(&a);
    image_free(&b);
    image_free(&d);
    return status;
}

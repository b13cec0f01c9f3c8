/* cmd_compare.c - `envtex compare A B [--diff D.png] [--fail-percent P --fail T --hard H]`
 * (compare.h) and `envtex compare --test IMG REF VAR [--img-spp N --ref-spp M --var-spp V]`
 * (gradetest.h, the noise-aware test; the counts default to the files' envtex:spp). */
#include <stdio.h>
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/io/exrfile.h"
#include "envtex/io/imageio.h"
#include "envtex/render/compare.h"
#include "envtex/render/gradetest.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const test_options[] = {
    "--test", "--diff", "--memory-budget", "--img-spp", "--ref-spp", "--var-spp", "--alpha",
    "--max-fail", NULL};

/* the options, for "did you mean" (cli_unknown) */
static const char *const compare_options[] = {
    "--test", "--diff", "--memory-budget", "--fail-percent", "--fail", "--hard", NULL};

/* The sample counts of IMG, REF and VAR: a flag (> 0) wins, else the file's envtex:spp
 * (exrfile.h; an OpenEXR render of envtex has it).  IMG and REF must end with one: the test
 * cannot assume two counts equal, and a 64-spp render against a 1024-spp reference taken as
 * equal fails for its honest noise.  VAR without one is REF's variance (gradetest.h). */
static int resolve_spp(const char *const paths[3], gradetest_params *p, error *err)
{
    double *spp[3] = {&p->img_spp, &p->ref_spp, &p->var_spp};
    for (int k = 0; k < 3; k++) {
        if (*spp[k] > 0 || imageio_detect(paths[k]) != IMAGEIO_EXR) continue;
        exrfile_attrs at;
        if (exrfile_read_attrs(paths[k], &at, err)) return -1;
        *spp[k] = at.spp;
    }
    if (p->img_spp > 0 && p->ref_spp > 0) return 0;
    if (!(p->img_spp > 0) && !(p->ref_spp > 0))
        return error_set(err, paths[0], 0,
                         "no sample counts: neither the image nor the reference "
                         "%s says its spp (no envtex:spp attribute): give --img-spp N --ref-spp M",
                         paths[1]);
    int k = p->img_spp > 0;
    return error_set(err, paths[k], 0,
                     "no sample count: the %s says no spp (no envtex:spp "
                     "attribute): give %s N",
                     k ? "reference" : "image", k ? "--ref-spp" : "--img-spp");
}

/* envtex compare --test IMG REF VAR: the noise-aware test (gradetest.h) */
/* The command line of compare --test. */
typedef struct test_args {
    const char *paths[3]; /* IMG REF VAR */
    const char *map_path; /* --diff, or NULL */
    double mem_limit;
    gradetest_params p;
} test_args;

/* 0, or 1 with the usage line printed */
static int parse_test_args(int argc, char **argv, test_args *t)
{
    int np = 0;
    memset(t, 0, sizeof *t);
    t->mem_limit = BUDGET_DEFAULT;
    t->p = gradetest_defaults();
    t->p.img_spp = t->p.ref_spp = 0; /* unknown until a flag or the files say (resolve_spp) */
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--diff")) {
            if (!(t->map_path = cli_opt_value(argc, argv, &i))) return 1;
            continue;
        }
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &t->mem_limit)) return 1;
            continue;
        }
        if (!strcmp(a, "--img-spp"))
            target = &t->p.img_spp;
        else if (!strcmp(a, "--ref-spp"))
            target = &t->p.ref_spp;
        else if (!strcmp(a, "--var-spp"))
            target = &t->p.var_spp;
        else if (!strcmp(a, "--alpha"))
            target = &t->p.alpha;
        else if (!strcmp(a, "--max-fail"))
            target = &t->p.max_fail_fraction;
        if (target) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, target) || !(*target > 0))
                return cli_usage_error("option needs a number > 0, got '%s'", v);
            /* significance and share of pixels are fractions: --max-fail 0.5 means half the
             * pixels (not 0.5%), and 5 would let every pixel fail */
            if (target == &t->p.alpha && !(*target < 1))
                return cli_usage_error("--alpha is a significance level in (0, 1), got '%s'", v);
            if (target == &t->p.max_fail_fraction && !(*target <= 1))
                return cli_usage_error("--max-fail is a fraction of the pixels in (0, 1] (0.005 "
                                       "is 0.5%%), got '%s'",
                                       v);
        } else if (a[0] == '-' && a[1])
            return cli_unknown("option", a, test_options);
        else if (np < 3)
            t->paths[np++] = a;
        else
            return cli_usage_error("unexpected argument '%s'", a);
    }
    if (np < 3)
        return cli_usage_error("%s", "compare --test needs IMG REF VAR (VAR from 'envtex render "
                                     "--variance')");
    return 0;
}

/* envtex compare --test IMG REF VAR: the noise-aware test (gradetest.h) */
static int cmd_compare_test(int argc, char **argv)
{
    test_args t;
    if (parse_test_args(argc, argv, &t)) return 1;
    const char *const *paths = t.paths, *map_path = t.map_path;
    gradetest_params p = t.p;
    error err = {0};
    image im[3] = {{0}}, map = {0};
    int status = 1;
    budget mb, *mem = cli_run_budget(&mb, t.mem_limit);
    if (map_path &&
        (cli_check_output(map_path, &err) || cli_check_not_replacing(map_path, paths, 3, &err)))
        goto done;
    for (int k = 0; k < 3; k++)
        if (imageio_read(paths[k], &im[k], mem, &err)) goto done;
    /* A PNG (the course skeleton's raytrace.png) is clamped to [0, 1] and rounded to 8 bits: every
     * pixel brighter than 1 would fail as a bias and the verdict say nothing about the code */
    static const char *const roles[3] = {"image", "reference", "variance"};
    for (int k = 0; k < 3; k++)
        if (imageio_detect(paths[k]) == IMAGEIO_PNG) {
            error_set(&err, paths[k], 0,
                      "the %s is a PNG (8 bits clamped to [0, 1]): the noise-aware test needs "
                      "the linear render (.exr, .pfm or .hdr)",
                      roles[k]);
            goto done;
        }
    if (resolve_spp(paths, &p, &err)) goto done;
    gradetest_result r;
    if (gradetest_run(&im[0], &im[1], &im[2], &p, &r, map_path ? &map : NULL, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, paths[0], 0, "%s", msg);
        goto done;
    }
    if (map_path && imageio_write(map_path, &map, NULL, &err)) goto done;
    printf("%s: %ld of %ld pixels (%.4f%%, allowed %.4f%%) fail |z| > %.2f; image total Z = %.2f "
           "(allowed |Z| <= %.2f); %ld NaN/Inf; spp %g against %g (variance of %g): %s\n",
           r.pass ? "PASS" : "FAIL", r.failed, r.pixels, 100 * r.failed_fraction,
           100 * p.max_fail_fraction, r.z_threshold, r.mean_z, p.global_z, r.nonfinite, p.img_spp,
           p.ref_spp, p.var_spp > 0 ? p.var_spp : p.ref_spp, r.why);
    status = r.pass ? 0 : 2;
done:
    if (status == 1) error_print(&err, stderr);
    for (int k = 0; k < 3; k++) image_free(&im[k]);
    image_free(&map);
    return status;
}

/* compare's PASS / FAIL line against the thresholds: 0 pass, 2 fail (a failed comparison is
 * not an error) */
static int print_thresholds(const image *a, const image *b, const compare_thresholds_params *th)
{
    compare_verdict v;
    compare_thresholds(a, b, th, &v);
    char where[64] = ""; /* where the largest difference is; none when every pixel agrees */
    if (v.max_x >= 0) snprintf(where, sizeof where, " at (%d, %d)", v.max_x, v.max_y);
    printf("%s: %ld of %ld pixels (%.3f%%) differ by more than %g (allowed %g%%), max %.6g%s "
           "(hard limit %g), %ld NaN/Inf: %s\n",
           v.pass ? "PASS" : "FAIL", v.failed, v.pixels, v.failed_percent, th->fail_thresh,
           th->fail_percent, v.max_diff, where, th->hard_thresh, v.nonfinite, v.why);
    return v.pass ? 0 : 2;
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
        if (!strcmp(a, "--fail-percent"))
            target = &th.fail_percent;
        else if (!strcmp(a, "--fail"))
            target = &th.fail_thresh;
        else if (!strcmp(a, "--hard"))
            target = &th.hard_thresh;
        if (target) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, target) || *target < 0)
                return cli_usage_error("a threshold must be a number >= 0, got '%s'", v);
            use_thresholds = 1;
        } else if (a[0] == '-' && a[1])
            return cli_unknown("option", a, compare_options);
        else if (!a_path)
            a_path = a;
        else if (!b_path)
            b_path = a;
        else
            return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!b_path)
        return cli_usage_error("%s", "compare needs two images: A (tested) and B (reference)");
    error err = {0};
    image a = {0}, b = {0}, d = {0};
    int status = 1;
    const char *inputs[2] = {a_path, b_path};
    if (diff_path &&
        (cli_check_output(diff_path, &err) || cli_check_not_replacing(diff_path, inputs, 2, &err)))
        goto done;
    budget mb, *mem = cli_run_budget(&mb, mem_limit);
    if (imageio_read(a_path, &a, mem, &err) || imageio_read(b_path, &b, mem, &err)) goto done;
    compare_result cr;
    if (compare_metrics(&a, &b, &cr, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, a_path, 0, "%s (against %s)", msg, b_path);
        goto done;
    }
    /* nan: A's NaN/Inf pixels; ref_nan: B's.  Either pixel non-finite leaves it out of the sums */
    printf("rmse=%.6g relmse=%.6g psnr=%.3f max_abs=%.6g nan=%ld relmse_trim=%.6g ref_nan=%ld\n",
           cr.rmse, cr.relmse, cr.psnr, cr.max_abs, cr.nonfinite, cr.relmse_trim, cr.ref_nonfinite);
    if (diff_path) {
        if (compare_diff_image(&a, &b, &d, &err) || imageio_write(diff_path, &d, NULL, &err))
            goto done;
    }
    status = 0;
    if (use_thresholds) status = print_thresholds(&a, &b, &th);
done:
    if (status == 1) error_print(&err, stderr);
    image_free(&a);
    image_free(&b);
    image_free(&d);
    return status;
}

/* cmd_strata.c - `envtex strata MAP OUT [-n N] [--exposure EV] [--memory-budget SIZE]`:
 * structured importance sampling's strata of a lat-long map as a picture (sis.h): the map with
 * each stratum outlined in magenta and each sample marked in green, and on stdout one line of
 * the layers (thresholds, regions, samples). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/envlight/sis.h"
#include "envtex/io/imageio.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {"--memory-budget", "-n", "--exposure", NULL};

/* the layers as `strata:` line fields, comma-separated a layer each */
static void print_layers(const sis_strata *s)
{
    printf("strata: n=%d layers=%d sigma=%.6g gamma_4pi=%.6g radius_deg=%.4g", s->n, s->n_layers,
           s->sigma, s->gamma_4pi, s->radius * 180 / M_PI);
    const char *names[4] = {"threshold", "regions", "total", "new"};
    for (int f = 0; f < 4; f++) {
        printf(" %s=", names[f]);
        for (int i = 0; i < s->n_layers; i++) {
            if (i) putchar(',');
            if (f == 0)
                printf("%.6g", s->threshold[i]);
            else
                printf("%d", f == 1 ? s->regions[i] : f == 2 ? s->layer_total[i] : s->layer_new[i]);
        }
    }
    putchar('\n');
}

int cmd_strata(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *v;
    long n = 64;
    double ev = 0, mem_limit = BUDGET_DEFAULT;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &mem_limit)) return 1;
        } else if (!strcmp(a, "-n")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, SIS_MAX_LIGHTS, &n))
                return cli_usage_error("-n needs a whole number from 1 to %d, got '%s'",
                                       SIS_MAX_LIGHTS, v);
        } else if (!strcmp(a, "--exposure")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, &ev))
                return cli_usage_error("--exposure needs a number, got '%s'", v);
        } else if (a[0] == '-' && a[1])
            return cli_unknown("option", a, options);
        else if (!in)
            in = a;
        else if (!out)
            out = a;
        else
            return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!out) return cli_usage_error("%s", "strata needs MAP (lat-long) and OUT");
    error err = {0};
    image map = {0}, pic = {0};
    sis_strata s = {0};
    double *lum = NULL;
    int status = 1;
    budget mb, *mem = cli_run_budget(&mb, mem_limit);
    if (cli_check_output(out, &err) || cli_check_not_replacing(out, &in, 1, &err)) goto done;
    if (imageio_read(in, &map, mem, &err)) goto done;
    if (!(lum = sis_luminance(&map, 1.0))) {
        error_set(&err, in, 0, "out of memory for the luminance of a %d x %d map", map.w, map.h);
        goto done;
    }
    if (sis_stratify(lum, map.w, map.h, (int)n, mem, &s, &err)) {
        error_prefix(&err, "%s", in);
        goto done;
    }
    if (sis_strata_picture(&s, &map, pow(2, ev), rgb_make(1, 0, 1), rgb_make(0, 1, 0), &pic, &err))
        goto done;
    if (imageio_write(out, &pic, NULL, &err)) goto done;
    print_layers(&s);
    status = 0;
done:
    if (status) error_print(&err, stderr);
    free(lum);
    sis_strata_free(&s);
    image_free(&map);
    image_free(&pic);
    return status;
}

/* cmd_prefilter.c - `envtex prefilter`: illumination maps from the command line (prefilter.h,
 * docs/illumination-maps.md).
 *
 *   envtex prefilter IN --sh9 [--from KIND]           the 9 coefficients, one `l m R G B` a line
 *   envtex prefilter IN OUT --irradiance [--method sh9|exact] [--width W] [--from KIND]
 *   envtex prefilter IN OUT --phong S [--width W] [--from KIND]
 *
 * OUT is a W x W/2 lat-long map (default 64), written atomically (imageio.h); a map mode prints
 * one summary line.  Bad arguments get one line `envtex: ...` and exit status 1, with nothing
 * written.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/cli/cli.h"
#include "envtex/envlight/prefilter.h"
#include "envtex/envmaps/convert.h"
#include "envtex/io/imageio.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {
    "--memory-budget", "--sh9", "--irradiance", "--phong", "--method", "--width", "--from", NULL};

typedef enum mode { MODE_NONE, MODE_SH9, MODE_IRRADIANCE, MODE_PHONG } mode;

typedef struct args {
    const char *in, *out, *from, *method;
    mode mode;
    int modes;        /* how many of --sh9, --irradiance, --phong were given */
    long width;       /* 0: not given */
    double s;         /* --phong S */
    double mem_limit; /* --memory-budget */
} args;

static int parse_args(int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    a->mem_limit = BUDGET_DEFAULT;
    for (int i = 0; i < argc; i++) {
        const char *o = argv[i], *v;
        char *end;
        if (!strcmp(o, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &a->mem_limit)) return 1;
        } else if (!strcmp(o, "--sh9") || !strcmp(o, "--irradiance")) {
            a->mode = o[2] == 's' ? MODE_SH9 : MODE_IRRADIANCE;
            a->modes++;
        } else if (!strcmp(o, "--phong")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            errno = 0;
            a->s = strtod(v, &end);
            int bad = end == v || *end || errno == ERANGE;
            if (bad || !(a->s >= 0 && a->s <= PREFILTER_MAX_SHININESS))
                return cli_usage_error("--phong needs an exponent from 0 to %g, got '%s'",
                                       PREFILTER_MAX_SHININESS, v);
            a->mode = MODE_PHONG;
            a->modes++;
        } else if (!strcmp(o, "--method")) {
            if (!(a->method = cli_opt_value(argc, argv, &i))) return 1;
            if (strcmp(a->method, "sh9") && strcmp(a->method, "exact"))
                return cli_usage_error("--method must be sh9 or exact, got '%s'", a->method);
        } else if (!strcmp(o, "--width")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            errno = 0;
            a->width = strtol(v, &end, 10);
            if (end == v || *end || errno == ERANGE || prefilter_check_width(a->width, NULL))
                return cli_usage_error("--width needs an even number from 2 to %d, got '%s'",
                                       PREFILTER_MAX_WIDTH, v);
        } else if (!strcmp(o, "--from")) {
            convert_kind k;
            if (!(a->from = cli_opt_value(argc, argv, &i))) return 1;
            if (convert_kind_parse(a->from, &k))
                return cli_usage_error("--from must be latlong, cube, cross, mirrorball, angular, "
                                       "cylindrical or equalarea, got '%s'",
                                       a->from);
        } else if (o[0] == '-' && o[1])
            return cli_unknown("option", o, options);
        else if (!a->in)
            a->in = o;
        else if (!a->out)
            a->out = o;
        else
            return cli_usage_error("unexpected argument '%s'", o);
    }
    if (!a->in) return cli_usage_error("%s", "prefilter needs IN");
    if (a->modes != 1)
        return cli_usage_error("%s", "prefilter needs one of --sh9, --irradiance or --phong S");
    if (a->mode == MODE_SH9 && a->out)
        return cli_usage_error("--sh9 prints the coefficients and writes no map: unexpected "
                               "argument '%s'",
                               a->out);
    if (a->mode == MODE_SH9 && a->width)
        return cli_usage_error("%s", "--sh9 writes no map: --width does not apply");
    if (a->mode != MODE_SH9 && !a->out)
        return cli_usage_error("%s", "prefilter --irradiance or --phong needs IN and OUT");
    if (a->method && a->mode != MODE_IRRADIANCE)
        return cli_usage_error("%s", "--method applies to --irradiance only");
    return 0;
}

/* The map of a map mode into *map; the method's name in *how. */
static int make_map(const args *a, const convert_env *env, image *map, const char **how, error *err)
{
    int width = a->width ? (int)a->width : 64;
    if (a->mode == MODE_PHONG) {
        *how = "exact";
        return prefilter_phong(env, a->s, width, map, err);
    }
    if (a->method && !strcmp(a->method, "sh9")) {
        prefilter_sh9 sh;
        *how = "sh9";
        if (prefilter_sh9_project(env, &sh, err)) return -1;
        return prefilter_irradiance_sh9(&sh, width, map, err);
    }
    *how = "exact";
    return prefilter_irradiance_exact(env, width, map, err);
}

static void print_sh9(const prefilter_sh9 *sh)
{
    for (int k = 0; k < PREFILTER_SH9; k++)
        printf("%d %d %.9g %.9g %.9g\n", prefilter_sh9_l(k), prefilter_sh9_m(k), sh->L[k][0],
               sh->L[k][1], sh->L[k][2]);
}

int cmd_prefilter(int argc, char **argv)
{
    args a;
    if (parse_args(argc, argv, &a)) return 1;
    error err = {0};
    convert_map src = {0};
    image map = {0};
    int status = 1;
    /* the inputs: IN, or IN's six faces when it is read as a cube */
    char faces[CUBEMAP_FACES][ERROR_FILE_MAX];
    const char *inputs[CUBEMAP_FACES] = {a.in};
    int n_inputs = 1;
    if (a.from && !strcmp(a.from, "cube")) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            if (convert_face_path(a.in, f, faces[f], sizeof faces[f], &err)) goto done;
            inputs[f] = faces[f];
        }
        n_inputs = CUBEMAP_FACES;
    }
    if (a.out &&
        (cli_check_output(a.out, &err) || cli_check_not_replacing(a.out, inputs, n_inputs, &err)))
        goto done;
    budget mb;
    if (convert_read(a.in, a.from, &src, cli_run_budget(&mb, a.mem_limit), &err)) goto done;
    if (src.bad_texels)
        fprintf(stderr,
                "envtex: warning: %s: %ld NaN, infinite or negative texel value%s "
                "(used as 0)\n",
                a.in, src.bad_texels, src.bad_texels == 1 ? "" : "s");
    convert_env env = convert_view(&src);
    clock_t t0 = clock();
    if (a.mode == MODE_SH9) {
        prefilter_sh9 sh;
        if (prefilter_sh9_project(&env, &sh, &err)) goto done;
        print_sh9(&sh);
        status = 0;
        goto done;
    }
    const char *how;
    if (make_map(&a, &env, &map, &how, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, a.in, 0, "%s", msg);
        goto done;
    }
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    if (imageio_write(a.out, &map, NULL, &err)) goto done;
    const image *si = convert_face_image(&env, 0);
    printf("from=%s %dx%d%s to=%s %dx%d method=%s", convert_kind_name(src.kind), si->w, si->h,
           src.kind == CONVERT_CUBE ? "x6" : "", a.mode == MODE_PHONG ? "phong" : "irradiance",
           map.w, map.h, how);
    if (a.mode == MODE_PHONG) printf(" s=%g", a.s);
    printf(" cpu_s=%.3f\n", secs);
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&map);
    convert_map_free(&src);
    return status;
}

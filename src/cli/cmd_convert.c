/* cmd_convert.c - `envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]`:
 * an environment resampled into another representation (convert.h). */
#include <stdio.h>
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/envmaps/convert.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {
    "--memory-budget", "--to", "--from", "--width", "--samples", NULL};

/* The command line of `envtex convert`. */
typedef struct convert_args {
    const char *in, *out, *to, *from;
    long width, samples; /* 0: the defaults */
    double mem_limit;
    convert_kind kind; /* what --to names */
} convert_args;

/* Parse argv into *a: 0, or the exit status (1) with the usage line printed. */
static int parse_args(int argc, char **argv, convert_args *a)
{
    *a = (convert_args){.mem_limit = BUDGET_DEFAULT};
    for (int i = 0; i < argc; i++) {
        const char *o = argv[i], *v;
        if (!strcmp(o, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &a->mem_limit)) return 1;
        } else if (!strcmp(o, "--to")) {
            if (!(a->to = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(o, "--from")) {
            if (!(a->from = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(o, "--width")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, IMAGE_MAX_SIDE, &a->width))
                return cli_usage_error("--width needs a whole number from 1 to 32768, got '%s'", v);
        } else if (!strcmp(o, "--samples")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, CONVERT_MAX_SAMPLES, &a->samples))
                return cli_usage_error("--samples needs a whole number from 1 to 64, got '%s'", v);
        } else if (o[0] == '-' && o[1])
            return cli_unknown("option", o, options);
        else if (!a->in)
            a->in = o;
        else if (!a->out)
            a->out = o;
        else
            return cli_usage_error("unexpected argument '%s'", o);
    }
    if (!a->out) return cli_usage_error("%s", "convert needs IN and OUT");
    convert_kind from_kind;
    if (!a->to)
        return cli_usage_error(
            "%s", "convert needs --to latlong|cube|cross|mirrorball|angular|cylindrical|equalarea");
    if (convert_kind_parse(a->to, &a->kind))
        return cli_usage_error("--to must be latlong, cube, cross, mirrorball, angular, "
                               "cylindrical or equalarea, got '%s'",
                               a->to);
    if (a->from && convert_kind_parse(a->from, &from_kind))
        return cli_usage_error("--from must be latlong, cube, cross, mirrorball, angular, "
                               "cylindrical or equalarea, got '%s'",
                               a->from);
    return 0;
}

/* Every output file must be writable, and none an input, before the work starts: the input
 * is IN, or IN's six faces when it is read as a cube; `six`: OUT is written as six faces.
 * 0, or -1 with *err. */
static int check_outputs(const convert_args *a, int six, error *err)
{
    char in_faces[CUBEMAP_FACES][ERROR_FILE_MAX];
    const char *inputs[CUBEMAP_FACES] = {a->in};
    int n_inputs = 1;
    if (a->from && !strcmp(a->from, "cube")) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            if (convert_face_path(a->in, f, in_faces[f], sizeof in_faces[f], err)) return -1;
            inputs[f] = in_faces[f];
        }
        n_inputs = CUBEMAP_FACES;
    }
    for (int f = 0; f < (six ? CUBEMAP_FACES : 1); f++) {
        char name[ERROR_FILE_MAX];
        if (six && convert_face_path(a->out, f, name, sizeof name, err)) return -1;
        if (cli_check_output(six ? name : a->out, err) ||
            cli_check_not_replacing(six ? name : a->out, inputs, n_inputs, err))
            return -1;
    }
    return 0;
}

/* The one summary line: sizes, samples, and the power (luminance of sum L Omega) kept. */
static void print_summary(const convert_args *a, int six, const convert_map *src,
                          const convert_map *dst)
{
    convert_env sv = convert_view(src), dv = convert_view(dst);
    double p0 = rgb_luminance(convert_power(&sv)), p1 = rgb_luminance(convert_power(&dv));
    const image *si = convert_face_image(&sv, 0), *di = convert_face_image(&dv, 0);
    printf("from=%s %dx%d%s to=%s %dx%d%s samples=%d power_in=%.6g power_out=%.6g "
           "power_change=%+.4f%%\n",
           convert_kind_name(src->kind), si->w, si->h, src->kind == CONVERT_CUBE ? "x6" : "",
           six ? "cube" : a->to, di->w, di->h, a->kind == CONVERT_CUBE ? "x6" : "",
           a->samples > 0 ? (int)a->samples : convert_default_samples(&sv, a->kind, di->w), p0, p1,
           p0 > 0 ? 100.0 * (p1 / p0 - 1.0) : 0.0);
}

/* envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]: resample an
 * environment into another representation (convert.h).  `cube` reads or writes six files
 * IN_px.EXT ... IN_nz.EXT; `cross` one horizontal cross image.  Prints one summary line. */
int cmd_convert(int argc, char **argv)
{
    convert_args a;
    int bad = parse_args(argc, argv, &a);
    if (bad) return bad;
    int six = !strcmp(a.to, "cube");
    error err = {0};
    convert_map src = {0}, dst = {0};
    int status = 1;
    if (check_outputs(&a, six, &err)) goto done;
    budget mb;
    if (convert_read(a.in, a.from, &src, cli_run_budget(&mb, a.mem_limit), &err)) goto done;
    if (src.bad_texels)
        fprintf(stderr,
                "envtex: warning: %s: %ld NaN, infinite or negative texel value%s (used as 0)\n",
                a.in, src.bad_texels, src.bad_texels == 1 ? "" : "s");
    convert_env sv = convert_view(&src);
    if (convert_resample(&sv, a.kind, (int)a.width, (int)a.samples, &dst, &err)) {
        char msg[ERROR_MSG_MAX];
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, a.out, 0, "%s", msg);
        goto done;
    }
    if (a.kind == CONVERT_CUBE && !six ? convert_write_cross(a.out, &dst, &err)
                                       : convert_write(a.out, &dst, &err))
        goto done;
    print_summary(&a, six, &src, &dst);
    status = 0;
done:
    if (status) error_print(&err, stderr);
    convert_map_free(&src);
    convert_map_free(&dst);
    return status;
}

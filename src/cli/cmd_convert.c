/* cmd_convert.c - `envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]`:
 * an environment resampled into another representation (convert.h). */
#include <stdio.h>
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/envmaps/convert.h"

/* envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]: resample an
 * environment into another representation (convert.h).  `cube` reads or writes six files
 * IN_px.EXT ... IN_nz.EXT; `cross` one horizontal cross image.  Prints one summary line. */
int cmd_convert(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *to = NULL, *from = NULL;
    long width = 0, samples = 0;
    double mem_limit = BUDGET_DEFAULT;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &mem_limit)) return 1;
        } else if (!strcmp(a, "--to")) {
            if (!(to = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--from")) {
            if (!(from = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--width")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, IMAGE_MAX_SIDE, &width)) return cli_usage_error("--width needs a whole number from 1 to 32768, got '%s'", v);
        } else if (!strcmp(a, "--samples")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, CONVERT_MAX_SAMPLES, &samples)) return cli_usage_error("--samples needs a whole number from 1 to 64, got '%s'", v);
        } else if (a[0] == '-' && a[1]) return cli_usage_error("unknown option '%s'", a);
        else if (!in) in = a;
        else if (!out) out = a;
        else return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!out) return cli_usage_error("%s", "convert needs IN and OUT");
    convert_kind kind, from_kind;
    if (!to) return cli_usage_error("%s", "convert needs --to latlong|cube|cross|mirrorball|angular|cylindrical|equalarea");
    if (convert_kind_parse(to, &kind)) return cli_usage_error("--to must be latlong, cube, cross, mirrorball, angular, cylindrical or equalarea, got '%s'", to);
    if (from && convert_kind_parse(from, &from_kind)) return cli_usage_error("--from must be latlong, cube, cross, mirrorball, angular, cylindrical or equalarea, got '%s'", from);
    int six = !strcmp(to, "cube");
    error err = {0};
    convert_map src = {0}, dst = {0};
    int status = 1;
    /* every output file must be writable, and none an input, before the work starts: the
     * input is IN, or IN's six faces when it is read as a cube */
    char in_faces[CUBEMAP_FACES][ERROR_FILE_MAX];
    const char *inputs[CUBEMAP_FACES] = {in};
    int n_inputs = 1;
    if (from && !strcmp(from, "cube")) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            if (convert_face_path(in, f, in_faces[f], sizeof in_faces[f], &err)) goto done;
            inputs[f] = in_faces[f];
        }
        n_inputs = CUBEMAP_FACES;
    }
    for (int f = 0; f < (six ? CUBEMAP_FACES : 1); f++) {
        char name[ERROR_FILE_MAX];
        if (six && convert_face_path(out, f, name, sizeof name, &err)) goto done;
        if (cli_check_output(six ? name : out, &err) || cli_check_not_replacing(six ? name : out, inputs, n_inputs, &err))
            goto done;
    }
    budget mb;
    if (convert_read(in, from, &src, cli_run_budget(&mb, mem_limit), &err)) goto done;
    if (src.bad_texels)
        fprintf(stderr, "envtex: warning: %s: %ld NaN, infinite or negative texel value%s (used as 0)\n",
                in, src.bad_texels, src.bad_texels == 1 ? "" : "s");
    convert_env sv = convert_view(&src);
    if (convert_resample(&sv, kind, (int)width, (int)samples, &dst, &err)) {
        char msg[ERROR_MSG_MAX];
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, out, 0, "%s", msg);
        goto done;
    }
    if (kind == CONVERT_CUBE && !six ? convert_write_cross(out, &dst, &err) : convert_write(out, &dst, &err)) goto done;
    convert_env dv = convert_view(&dst);
    double p0 = rgb_luminance(convert_power(&sv)), p1 = rgb_luminance(convert_power(&dv));
    const image *si = convert_face_image(&sv, 0), *di = convert_face_image(&dv, 0);
    printf("from=%s %dx%d%s to=%s %dx%d%s samples=%d power_in=%.6g power_out=%.6g power_change=%+.4f%%\n",
           convert_kind_name(src.kind), si->w, si->h, src.kind == CONVERT_CUBE ? "x6" : "",
           six ? "cube" : to, di->w, di->h, kind == CONVERT_CUBE ? "x6" : "",
           samples > 0 ? (int)samples : convert_default_samples(&sv, kind, di->w), p0, p1,
           p0 > 0 ? 100.0 * (p1 / p0 - 1.0) : 0.0);
    status = 0;
done:
    if (status) error_print(&err, stderr);
    convert_map_free(&src);
    convert_map_free(&dst);
    return status;
}

/* cmd_tonemap.c - `envtex tonemap IN OUT.png [--exposure EV] [--op clamp|reinhard|aces]
 * [--gamma G]`: an HDR image as an 8-bit PNG (tonemap.h). */
#include <string.h>
#include <strings.h>

#include "envtex/cli/cli.h"
#include "envtex/io/imageio.h"
#include "envtex/io/tonemap.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {"--memory-budget", "--exposure", "--op", "--gamma", NULL};

int cmd_tonemap(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    tonemap_params tm = tonemap_defaults();
    double mem_limit = BUDGET_DEFAULT;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &mem_limit)) return 1;
        } else if (!strcmp(a, "--exposure")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, &tm.exposure))
                return cli_usage_error("--exposure needs a number, got '%s'", v);
        } else if (!strcmp(a, "--op")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (tonemap_op_parse(v, &tm.op))
                return cli_usage_error("--op must be clamp, reinhard or aces, got '%s'", v);
        } else if (!strcmp(a, "--gamma")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, &tm.gamma) || !(tm.gamma > 0))
                return cli_usage_error("--gamma needs a number > 0, got '%s'", v);
        } else if (a[0] == '-' && a[1])
            return cli_unknown("option", a, options);
        else if (!in)
            in = a;
        else if (!out)
            out = a;
        else
            return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!out) return cli_usage_error("%s", "tonemap needs IN and OUT.png");
    error err = {0};
    image img = {0};
    int status = 1;
    /* exposure, operator and gamma act only on the 8-bit PNG: an .exr, .hdr or .pfm OUT was
     * written as an unchanged copy of IN, the options silently ignored */
    const char *dot = strrchr(out, '.');
    if (!dot || strchr(dot, '/') || strcasecmp(dot, ".png")) {
        error_set(&err, out, 0,
                  "tonemap writes an 8-bit PNG: name the output .png (an HDR "
                  "output would be IN unchanged, without the tone mapping)");
        goto done;
    }
    if (cli_check_output(out, &err) || cli_check_not_replacing(out, &in, 1, &err)) goto done;
    budget mb;
    if (imageio_read(in, &img, cli_run_budget(&mb, mem_limit), &err)) goto done;
    if (imageio_write(out, &img, &tm, &err)) goto done;
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&img);
    return status;
}

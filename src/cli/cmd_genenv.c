/* cmd_genenv.c - `envtex gen-env constant|sky|sun|axes OUT [--width W] ...`: procedural
 * environments (genenv.h). */
#include <string.h>

#include "envtex/cli/cli.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/io/imageio.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {
    "--width", "--value", "--sun-ratio", "--sun-radius", "--sun-elevation", "--sun-azimuth", NULL};

int cmd_gen_env(int argc, char **argv)
{
    const char *kind_name = NULL, *out = NULL;
    genenv_params p = genenv_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--width")) {
            long n;
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 2, IMAGE_MAX_SIDE, &n))
                return cli_usage_error("--width needs a whole number from 2 to 32768, got '%s'", v);
            p.width = (int)n;
            continue;
        }
        if (!strcmp(a, "--value"))
            target = &p.value;
        else if (!strcmp(a, "--sun-ratio"))
            target = &p.sun_ratio;
        else if (!strcmp(a, "--sun-radius"))
            target = &p.sun_radius_deg;
        else if (!strcmp(a, "--sun-elevation"))
            target = &p.sun_elevation_deg;
        else if (!strcmp(a, "--sun-azimuth"))
            target = &p.sun_azimuth_deg;
        if (target) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_double(v, target))
                return cli_usage_error("%s needs a finite number, got '%s'", a, v);
        } else if (a[0] == '-' && a[1])
            return cli_unknown("option", a, options);
        else if (!kind_name)
            kind_name = a;
        else if (!out)
            out = a;
        else
            return cli_usage_error("unexpected argument '%s'", a);
    }
    if (!out) return cli_usage_error("%s", "gen-env needs KIND and OUT");
    genenv_kind kind;
    if (genenv_kind_parse(kind_name, &kind))
        return cli_usage_error("unknown environment kind '%s' (constant, sky, sun, axes)",
                               kind_name);
    error err = {0};
    image img = {0};
    int status = 1;
    if (cli_check_output(out, &err)) goto done;
    if (genenv_make(kind, &p, &img, &err)) {
        error_prefix(&err, "gen-env %s", kind_name);
        goto done;
    }
    if (imageio_write(out, &img, NULL, &err)) goto done;
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&img);
    return status;
}

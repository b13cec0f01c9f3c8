/* main.c - the envtex command line: picks the subcommand (cmd_NAME.c, cli.h).
 * Every failure prints one line `envtex: FILE:LINE: what is wrong` and exits with status 1; a
 * comparison that runs and finds the images differ (`compare` with thresholds, `compare --test`)
 * prints FAIL and exits with status 2.
 *
 *   envtex SCENE                    same as `envtex render SCENE`
 *   envtex render SCENE [-o OUT] [--spp N] [--seed N] [--ref REF] [--variance VAR] [--quiet]
 *                       [--verbose] [--strict]
 *   envtex compare A B [--diff D.png] [--fail-percent P] [--fail T] [--hard H]
 *   envtex compare --test IMG REF VAR [--img-spp N] [--ref-spp M] [--var-spp V]
 *                                     [--alpha A] [--max-fail F] [--diff MAP.png]
 *   envtex tonemap IN OUT.png [--exposure EV] [--op clamp|reinhard|aces] [--gamma G]
 *   envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]
 *   (render, compare, tonemap and convert also take --memory-budget SIZE: budget.h)
 *   envtex gen-env KIND OUT [--width W] [--value V] [--sun-ratio R] [--sun-radius DEG]
 *                           [--sun-elevation DEG] [--sun-azimuth DEG]
 *   envtex prefilter IN --sh9 | IN OUT --irradiance [--method sh9|exact] | IN OUT --phong S
 *                           [--width W] [--from KIND]
 *   envtex noise X Y Z              Perlin's improved noise at (X, Y, Z), 9 significant digits
 *   envtex strata MAP OUT [-n N] [--exposure EV]   structured importance sampling's strata
 */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "envtex/cli/cli.h"

static const char *usage_text =
    "usage: envtex SCENE                         (same as: envtex render SCENE)\n"
    "       envtex render SCENE [-o OUT.exr|.png|.pfm|.hdr] [--spp N] [--seed N] [--ref REF]"
    " [--variance VAR.exr]\n"
    "                           [--quiet] [--verbose] [--strict]\n"
    "       envtex compare A B [--diff DIFF.png] [--fail-percent P] [--fail T] [--hard H]\n"
    "       envtex compare --test IMG REF VAR [--img-spp N] [--ref-spp M] [--var-spp V]\n"
    "                      [--alpha A] [--max-fail F] [--diff MAP.png]"
    "   (spp from the EXR files' envtex:spp)\n"
    "       envtex tonemap IN OUT.png [--exposure EV] [--op clamp|reinhard|aces] [--gamma G]\n"
    "       envtex convert IN OUT"
    " --to latlong|cube|cross|mirrorball|angular|cylindrical|equalarea\n"
    "                      [--from KIND] [--width W] [--samples K]"
    "   (cube: OUT_px.exr ... OUT_nz.exr)\n"
    "       render, compare, tonemap and convert take --memory-budget SIZE (512M, 8G, ...;\n"
    "       default 2G; 'none': only the hard limits)\n"
    "       envtex gen-env constant|sky|sun|axes OUT [--width W] [--value V] [--sun-ratio R]\n"
    "                      [--sun-radius DEG] [--sun-elevation DEG] [--sun-azimuth DEG]\n"
    "       envtex prefilter IN --sh9 [--from KIND]       (9 lines: l m R G B)\n"
    "       envtex prefilter IN OUT --irradiance [--method sh9|exact] [--width W] [--from KIND]\n"
    "       envtex prefilter IN OUT --phong S [--width W] [--from KIND]\n"
    "       envtex noise X Y Z                   (Perlin's improved noise, 9 significant digits)\n"
    "       envtex strata MAP OUT [-n N] [--exposure EV] [--memory-budget SIZE]\n"
    "                      (structured importance sampling's strata of a lat-long map)\n";

static const char *const subcommands[] = {"render",    "compare", "tonemap", "gen-env", "convert",
                                          "prefilter", "noise",   "strata",  "help",    NULL};

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage_text, stderr);
        return 1;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
        fputs(usage_text, stdout);
        return 0;
    }
    if (!strcmp(cmd, "render")) return cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "compare")) return cmd_compare(argc - 2, argv + 2);
    if (!strcmp(cmd, "tonemap")) return cmd_tonemap(argc - 2, argv + 2);
    if (!strcmp(cmd, "gen-env")) return cmd_gen_env(argc - 2, argv + 2);
    if (!strcmp(cmd, "convert")) return cmd_convert(argc - 2, argv + 2);
    if (!strcmp(cmd, "prefilter")) return cmd_prefilter(argc - 2, argv + 2);
    if (!strcmp(cmd, "noise")) return cmd_noise(argc - 2, argv + 2);
    if (!strcmp(cmd, "strata")) return cmd_strata(argc - 2, argv + 2);
    /* a word that names no file but is a near miss of a subcommand is a typo, not a scene */
    if (cmd[0] != '-' && access(cmd, F_OK) != 0 && cli_closest(cmd, subcommands))
        return cli_unknown("command", cmd, subcommands);
    return cmd_render(argc - 1, argv + 1); /* envtex SCENE [options] */
}

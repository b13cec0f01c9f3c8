/* bench_prefilter.c - what illumination maps cost (prefilter.h; make bench runs it through
 * tools/bench/bench_prefilter), CPU seconds, medians of RUNS (the slow plain sums once):
 *   1. the 9 SH coefficients of a 4096 x 2048 map (one pass, the trigonometry tabulated);
 *   2. an exact 64 x 32 irradiance map of a 1024 x 512 map: the arc sums against the plain sum
 *      over every texel pair, and the arc sums of a 4096 x 2048 map;
 *   3. Phong maps of a 1024 x 512 map, S = 1, 10, 100, 1000, at 64 x 32 and at the width the
 *      integrator picks (prefilter_phong_width), and of a 4096 x 2048 map at 64 x 32, S = 10;
 *   4. an exact 64 x 32 irradiance map of a cube map of 6 x 256 x 256 texels (the plain sum).
 * The maps are genenv's sun (10^5 times the sky).
 *     build/tools/bench_prefilter [--runs N] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/envlight/prefilter.h"

static double cpu(void) { return (double)clock() / CLOCKS_PER_SEC; }

static convert_map sun_map(int w)
{
    convert_map m;
    memset(&m, 0, sizeof m);
    genenv_params p = genenv_defaults();
    p.width = w;
    error err = {0};
    if (genenv_make(GENENV_SUN, &p, &m.img, &err)) {
        error_print(&err, stderr);
        exit(1);
    }
    return m;
}

typedef int (*map_fn)(const convert_env *env, double s, int width, image *out, error *err);
static int irr_arcs(const convert_env *e, double s, int w, image *o, error *err)
{
    (void)s;
    return prefilter_irradiance_arcs(e, w, o, err);
}
static int irr_brute(const convert_env *e, double s, int w, image *o, error *err)
{
    (void)s;
    return prefilter_irradiance_brute(e, w, o, err);
}

/* median CPU seconds of `runs` calls of f */
static double time_map(map_fn f, const convert_env *env, double s, int width, int runs)
{
    double t[16];
    if (runs > 16) runs = 16;
    for (int i = 0; i < runs; i++) {
        image out = {0};
        error err = {0};
        double t0 = cpu();
        if (f(env, s, width, &out, &err)) {
            error_print(&err, stderr);
            exit(1);
        }
        t[i] = cpu() - t0;
        image_free(&out);
    }
    return median(t, runs);
}

int main(int argc, char **argv)
{
    int runs = 5;
    if (argc == 3 && !strcmp(argv[1], "--runs")) runs = atoi(argv[2]);
    if (runs < 1) runs = 1;
    convert_map big = sun_map(4096), mid = sun_map(1024);
    convert_env eb = convert_view(&big), em = convert_view(&mid);
    double t[16];
    for (int i = 0; i < runs && i < 16; i++) {
        prefilter_sh9 sh;
        error err = {0};
        double t0 = cpu();
        prefilter_sh9_project(&eb, &sh, &err);
        t[i] = cpu() - t0;
    }
    printf("prefilter: SH9 of 4096 x 2048                      %8.3f s (median of %d)\n",
           median(t, runs < 16 ? runs : 16), runs);
    double arcs = time_map(irr_arcs, &em, 0, 64, runs), brute = time_map(irr_brute, &em, 0, 64, 1);
    printf("prefilter: exact irradiance 64 x 32 of 1024 x 512:  arc sums %.3f s, plain sum %.2f s "
           "(%.0fx)\n",
           arcs, brute, brute / arcs);
    printf("prefilter: exact irradiance 64 x 32 of 4096 x 2048: arc sums %.3f s\n",
           time_map(irr_arcs, &eb, 0, 64, runs));
    const double s[] = {1, 10, 100, 1000};
    for (int i = 0; i < 4; i++) {
        int w = prefilter_phong_width(s[i]);
        printf("prefilter: Phong S = %-4g of 1024 x 512: 64 x 32 %.3f s, %d x %d %.3f s\n", s[i],
               time_map(prefilter_phong, &em, s[i], 64, runs), w, w / 2,
               time_map(prefilter_phong, &em, s[i], w, 1));
    }
    printf("prefilter: Phong S = 10 of 4096 x 2048 at 64 x 32:  %.2f s\n",
           time_map(prefilter_phong, &eb, 10, 64, 1));
    convert_map cube;
    error err = {0};
    if (convert_resample(&em, CONVERT_CUBE, 256, 0, &cube, &err)) {
        error_print(&err, stderr);
        return 1;
    }
    convert_env ec = convert_view(&cube);
    printf("prefilter: exact irradiance 64 x 32 of a 6 x 256^2 cube (plain sum): %.2f s\n",
           time_map(irr_brute, &ec, 0, 64, 1));
    convert_map_free(&cube);
    convert_map_free(&big);
    convert_map_free(&mid);
    return 0;
}

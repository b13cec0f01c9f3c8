/* bench_envmap.c - what the environment-map representations cost (make bench runs it through
 * tools/bench/bench_envmap):
 *   1. ns per direction -> image coordinates (the maths of each representation's header) and
 *      per bilinear lookup (convert_lookup, what the renderer calls), median of RUNS repeats of
 *      2^20 random directions;
 *   2. seconds per conversion of a 1024 x 512 lat-long map into each representation at its
 *      default size and samples (convert_resample), median of RUNS;
 *   3. the power kept by lat-long -> cube -> lat-long and lat-long -> mirror ball -> lat-long on
 *      every map named on the command line (the CC0 maps of ../shared/hdri): exit status 1 if
 *      one loses more than 0.5%, so the bench doubles as the slow acceptance check that the unit
 *      tests leave out (each round trip of a 1024 x 512 map takes about 1.5 s).
 *
 *     build/tools/bench_envmap [--runs N] [MAP.exr ...]
 * Without maps the 1024 x 512 map of part 2 is genenv's sun (10^5 times the sky); with maps, the
 * first one.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "envtex/envmaps/angular.h"
#include "envtex/envmaps/convert.h"
#include "envtex/envmaps/cubemap.h"
#include "envtex/envmaps/cylindrical.h"
#include "envtex/envmaps/equalarea.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/envmaps/mirrorball.h"
#include "envtex/core/rng.h"

#define N_DIRS    (1 << 20)
#define POWER_TOL 0.005

/* The representation's direction -> image coordinates; the face index counts for cubes. */
static double to_uv(convert_kind k, vec3 d, double h)
{
    uv2 uv = {0, 0};
    int face = 0;
    switch (k) {
    case CONVERT_LATLONG: latlong_dir_to_uv(d, &uv); break;
    case CONVERT_CUBE: cubemap_dir_to_face(d, &face, &uv); break;
    case CONVERT_MIRRORBALL: mirrorball_dir_to_uv(d, &uv); break;
    case CONVERT_ANGULAR: angular_dir_to_uv(d, &uv); break;
    case CONVERT_CYLINDRICAL: cylindrical_dir_to_uv(d, h, &uv); break;
    case CONVERT_EQUALAREA: equalarea_dir_to_uv(d, &uv); break;
    default: break;
    }
    return uv.u + uv.v + face;
}

static double power_change(const convert_map *a, const convert_map *b)
{
    convert_env va = convert_view(a), vb = convert_view(b);
    double p0 = rgb_luminance(convert_power(&va)), p1 = rgb_luminance(convert_power(&vb));
    return p0 > 0 ? p1 / p0 - 1.0 : 0.0;
}

int main(int argc, char **argv)
{
    int runs = 3, first_map = argc;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--runs") && i + 1 < argc) {
            runs = atoi(argv[++i]);
            if (runs < 1 || runs > 100) runs = 3;
        } else {
            first_map = i;
            break;
        }
    }
    error err = {0};
    convert_map src = {0};
    const char *src_name = "genenv sun";
    if (first_map < argc) {
        if (convert_read(argv[first_map], "latlong", &src, NULL, &err)) goto fail;
        src_name = argv[first_map];
    } else {
        genenv_params p = genenv_defaults();
        p.width = 1024;
        if (genenv_make(GENENV_SUN, &p, &src.img, &err)) goto fail;
    }
    convert_env sv = convert_view(&src);
    double *t = malloc(sizeof(double) * (size_t)runs);
    vec3 *dirs = malloc(sizeof(vec3) * N_DIRS);
    if (!t || !dirs) return 1;
    rng r;
    rng_seed(&r, 1, 0);
    for (int i = 0; i < N_DIRS; i++) {
        double z = 1.0 - 2.0 * rng_uniform(&r), phi = 2.0 * M_PI * rng_uniform(&r),
               s = sqrt(fmax(0.0, 1.0 - z * z));
        dirs[i] = vec3_make(s * cos(phi), s * sin(phi), z);
    }
    printf("envmap representations (%s, %d x %d; medians of %d runs)\n", src_name, src.img.w,
           src.img.h, runs);
    printf("  %-12s %10s %12s %12s %12s\n", "to", "size", "dir->uv ns", "lookup ns", "convert s");
    convert_map m[CONVERT_KINDS];
    memset(m, 0, sizeof m);
    double sink = 0;
    for (int k = 0; k < CONVERT_KINDS; k++) {
        for (int i = 0; i < runs; i++) {
            convert_map_free(&m[k]);
            double t0 = now();
            if (convert_resample(&sv, (convert_kind)k, 0, 0, &m[k], &err)) goto fail;
            t[i] = now() - t0;
        }
        double conv_s = median(t, runs);
        convert_env v = convert_view(&m[k]);
        for (int i = 0; i < runs; i++) {
            double t0 = now();
            for (int j = 0; j < N_DIRS; j++) sink += to_uv((convert_kind)k, dirs[j], v.max_height);
            t[i] = (now() - t0) * 1e9 / N_DIRS;
        }
        double uv_ns = median(t, runs);
        for (int i = 0; i < runs; i++) {
            double t0 = now();
            for (int j = 0; j < N_DIRS; j++) sink += convert_lookup(&v, dirs[j]).g;
            t[i] = (now() - t0) * 1e9 / N_DIRS;
        }
        double lookup_ns = median(t, runs);
        const image *im = convert_face_image(&v, 0);
        char size[32];
        snprintf(size, sizeof size, "%dx%d%s", im->w, im->h, k == CONVERT_CUBE ? "x6" : "");
        printf("  %-12s %10s %12.1f %12.1f %12.3f\n", convert_kind_name((convert_kind)k), size,
               uv_ns, lookup_ns, conv_s);
    }
    for (int k = 0; k < CONVERT_KINDS; k++) convert_map_free(&m[k]);
    if (sink == 42.0) printf(" \n"); /* keep the loops */

    /* power kept by the two round trips on every map given */
    int bad = 0;
    for (int i = first_map; i < argc; i++) {
        convert_map a = {0}, mid = {0}, back = {0};
        if (convert_read(argv[i], "latlong", &a, NULL, &err)) goto fail;
        convert_env av = convert_view(&a);
        static const convert_kind via[] = {CONVERT_CUBE, CONVERT_MIRRORBALL};
        printf("  power %s:", argv[i]);
        for (int j = 0; j < 2; j++) {
            if (convert_resample(&av, via[j], 0, 0, &mid, &err)) goto fail;
            convert_env mv = convert_view(&mid);
            if (convert_resample(&mv, CONVERT_LATLONG, a.img.w, 0, &back, &err)) goto fail;
            double there = power_change(&a, &mid), round = power_change(&a, &back);
            int ok = fabs(there) < POWER_TOL && fabs(round) < POWER_TOL;
            bad += !ok;
            printf(" via %s %+.4f%% (there %+.4f%%)%s", convert_kind_name(via[j]), 100 * round,
                   100 * there, ok ? "" : " FAIL");
            convert_map_free(&mid);
            convert_map_free(&back);
        }
        printf("\n");
        convert_map_free(&a);
    }
    free(t);
    free(dirs);
    convert_map_free(&src);
    if (bad)
        fprintf(stderr, "bench_envmap: %d round trips lost more than 0.5%% of the power\n", bad);
    return bad ? 1 : 0;
fail:
    error_print(&err, stderr);
    return 1;
}

/* bench_texture.c - microbenchmarks of texture lookups (make bench, tools/bench/bench_texture):
 *   - ns per texture_eval of a 512 x 512 image texture for each filter (nearest, bilinear,
 *     trilinear, EWA), median of repeats made in rounds (below).  The queries come in scanlines, as a renderer makes
 *     them: along a row of 512 "pixels" (s, t) advances by one footprint per pixel (dst/dx);
 *     each patch of rows has its own footprint, from 1/4 to 16 texels wide (log-uniform), its
 *     own direction and up to 4:1 anisotropy (a receding plane's range).  Two orders:
 *       "lookup"      16 ADJACENT rows per patch, row j starting at st0 + j dst/dy: a 512 x 16
 *                     block of pixels of one textured surface, in a renderer's scanline order
 *                     (what a row reads, the next row reads again);
 *       "lookup-rows" every row on its own (st0 random): no row reuses another's texels, the
 *                     pessimistic case, bound by cache misses at large footprints.
 *     Random (s, t) for every query would measure cache misses instead of the filter;
 *   - ns per perlin_noise evaluation, 512 steps of 0.37 along each scanline's line, from a random
 *     start in [-100, 100]^3 (a ray marching through a solid texture; the 16 rows of a patch
 *     share their line, so 32 lines are walked 16 times each).
 * The queries are made in the timed loop, from one small record per scanline made before the
 * clock starts, as a renderer makes them per pixel; a running sum keeps the compiler honest.
 * Output lines (parsed by the script):
 *     lookup FILTER NS
 *     lookup-rows FILTER NS
 *     perlin NS
 * Usage: bench_texture [REPEATS] (default 7). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "envtex/textures/perlin.h"
#include "envtex/core/rng.h"
#include "envtex/textures/texture.h"

#define N_QUERIES (1 << 18)
#define TEX_SIZE  512

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 7;
    if (repeats < 1) repeats = 1;
    if (repeats > 64) repeats = 64;
    error err = {0};
    image img = {0};
    texture tx;
    memset(&tx, 0, sizeof tx);
    /* Queries are made in the timed loop from one small record per scanline, as a renderer makes
     * them per pixel: an array of N_QUERIES full queries (176 bytes each, 46 MB) would make the
     * benchmark measure memory bandwidth instead of the lookups. */
    typedef struct line {
        uv2 st, st0, dx, dy;
        vec3 p, dp;
    } line; /* st0: the "rows" start */
    enum { N_LINES = N_QUERIES / TEX_SIZE, PATCH_ROWS = 16 };
    line *lines = malloc(N_LINES * sizeof *lines);
    if (!lines || image_alloc(&img, TEX_SIZE, TEX_SIZE, &err)) goto fail;
    rng g;
    rng_seed(&g, 7, 0);
    for (int y = 0; y < TEX_SIZE; y++)
        for (int x = 0; x < TEX_SIZE; x++)
            image_set(&img, x, y, rgb_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g)));
    texture_init_image(&tx, &img, WRAP_REPEAT);
    if (texture_prepare(&tx, TEXFILTER_EWA, NULL, &err) ||
        texture_prepare(&tx, TEXFILTER_TRILINEAR, NULL, &err))
        goto fail;
    for (int l = 0; l < N_LINES; l++) { /* a scanline: its start, footprint and direction */
        if (l % PATCH_ROWS) { /* patch order: the row below the previous one (kept for "rows") */
            lines[l] = lines[l - 1];
            lines[l].st.u += lines[l].dy.u;
            lines[l].st.v += lines[l].dy.v;
            lines[l].st0 = (uv2){rng_uniform(&g), rng_uniform(&g)};
            continue;
        }
        double w = pow(2.0, -2 + 6 * rng_uniform(&g)) / TEX_SIZE; /* 1/4 .. 16 texels */
        double a = 2 * M_PI * rng_uniform(&g), aniso = 1 + 3 * rng_uniform(&g);
        lines[l].st = lines[l].st0 = (uv2){rng_uniform(&g), rng_uniform(&g)};
        lines[l].dx = (uv2){w * cos(a), w * sin(a)};
        lines[l].dy = (uv2){-w / aniso * sin(a), w / aniso * cos(a)};
        lines[l].p = vec3_make(200 * rng_uniform(&g) - 100, 200 * rng_uniform(&g) - 100,
                               200 * rng_uniform(&g) - 100);
        lines[l].dp =
            vec3_scale(vec3_normalize(vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5,
                                                rng_uniform(&g) - 0.5)),
                       0.37);
    }
    /* Rounds: each times every pass once, back to back (the 8 lookup passes, then Perlin), and a
     * pass's figure is its median over the rounds.  The host runs slower part of the time, in
     * phases of a second or so; a pass's repeats made back to back (35 ms for trilinear) all
     * fell in one such phase now and then (45 ns for trilinear's usual 26), while rounds spread
     * them over the whole run, as speed_vs_error's timing rounds do. */
    enum { N_PASSES = 2 * (TEXFILTER_EWA + 1) + 1 }; /* (order, filter) pairs, then Perlin */
    static double t[N_PASSES][64];
    double sink = 0;
    for (int k = 0; k < repeats; k++) {
        int pass = 0;
        for (int order = 0; order < 2; order++) /* 0: patches of adjacent rows, 1: rows alone */
            for (int f = TEXFILTER_NEAREST; f <= TEXFILTER_EWA; f++, pass++) {
                texture_query q;
                memset(&q, 0, sizeof q);
                q.filter = (texture_filter)f;
                double t0 = 0;
                for (int warm = 1; warm >= 0; warm--) { /* the pass twice, the second timed */
                    t0 = now();
                    for (int l = 0; l < N_LINES; l++) {
                        q.st = order == 0 ? lines[l].st : lines[l].st0;
                        q.dst_dx = lines[l].dx;
                        q.dst_dy = lines[l].dy;
                        for (int i = 0; i < TEX_SIZE; i++) {
                            sink += texture_eval(&tx, &q).r;
                            q.st.u += q.dst_dx.u; /* the next pixel of the row */
                            q.st.v += q.dst_dx.v;
                        }
                    }
                }
                t[pass][k] = (now() - t0) / N_QUERIES * 1e9;
            }
        double t0 = 0;
        for (int warm = 1; warm >= 0; warm--) { /* as the lookups: twice, the second timed */
            t0 = now();
            for (int l = 0; l < N_LINES; l++) {
                vec3 p = lines[l].p, dp = lines[l].dp;
                for (int i = 0; i < TEX_SIZE; i++) {
                    sink += perlin_noise(p.x, p.y, p.z);
                    p = vec3_add(p, dp); /* marching through the solid texture */
                }
            }
        }
        t[pass][k] = (now() - t0) / N_QUERIES * 1e9;
    }
    int pass = 0;
    for (int order = 0; order < 2; order++)
        for (int f = TEXFILTER_NEAREST; f <= TEXFILTER_EWA; f++, pass++)
            printf("%s %s %.2f\n", order == 0 ? "lookup" : "lookup-rows",
                   texture_filter_name((texture_filter)f), median(t[pass], repeats));
    printf("perlin %.2f\n", median(t[pass], repeats));
    fprintf(stderr, "(checksum %g)\n", sink);
    texture_free(&tx);
    image_free(&img);
    free(lines);
    return 0;
fail:
    error_print(&err, stderr);
    texture_free(&tx);
    image_free(&img);
    free(lines);
    return 1;
}

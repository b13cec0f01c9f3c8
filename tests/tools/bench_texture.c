/* bench_texture.c - microbenchmarks of texture lookups (make bench, tests/bench/bench_texture):
 *   - ns per texture_eval of a 512 x 512 image texture for each filter (nearest, bilinear,
 *     trilinear, EWA), median of repeats.  The queries come in scanlines, as a renderer makes
 *     them: along a row of 512 "pixels" (s, t) advances by one footprint per pixel; each row
 *     has its own footprint, from 1/4 to 16 texels wide (log-uniform), its own direction and
 *     up to 4:1 anisotropy (a receding plane's range).  Random (s, t) for every query would
 *     measure cache misses instead of the filter;
 *   - ns per perlin_noise evaluation at random points in [-100, 100]^3.
 * The queries are made before the clock starts; a running sum keeps the compiler honest.
 * Output lines (parsed by the script):
 *     lookup FILTER NS
 *     perlin NS
 * Usage: bench_texture [REPEATS] (default 7). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/perlin.h"
#include "envtex/rng.h"
#include "envtex/texture.h"

#define N_QUERIES (1 << 18)
#define TEX_SIZE 512

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 7;
    if (repeats < 1) repeats = 1;
    if (repeats > 64) repeats = 64;
    error err = {0};
    image img = {0};
    texture tx;
    memset(&tx, 0, sizeof tx);
    texture_query *q = malloc(N_QUERIES * sizeof *q);
    vec3 *pts = malloc(N_QUERIES * sizeof *pts);
    if (!q || !pts || image_alloc(&img, TEX_SIZE, TEX_SIZE, &err)) goto fail;
    rng g;
    rng_seed(&g, 7, 0);
    for (int y = 0; y < TEX_SIZE; y++)
        for (int x = 0; x < TEX_SIZE; x++)
            image_set(&img, x, y, rgb_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g)));
    texture_init_image(&tx, &img, WRAP_REPEAT);
    if (texture_prepare(&tx, TEXFILTER_EWA, &err)) goto fail;
    double w = 0, a = 0, aniso = 1;
    uv2 st = {0, 0};
    for (int i = 0; i < N_QUERIES; i++) {
        if (i % TEX_SIZE == 0) { /* a new scanline: its start, footprint and direction */
            st = (uv2){rng_uniform(&g), rng_uniform(&g)};
            w = pow(2.0, -2 + 6 * rng_uniform(&g)) / TEX_SIZE; /* 1/4 .. 16 texels */
            a = 2 * M_PI * rng_uniform(&g);
            aniso = 1 + 3 * rng_uniform(&g);
        }
        memset(&q[i], 0, sizeof q[i]);
        q[i].dst_dx = (uv2){w * cos(a), w * sin(a)};
        q[i].dst_dy = (uv2){-w / aniso * sin(a), w / aniso * cos(a)};
        q[i].st = st;
        st.u += q[i].dst_dx.u; /* the next pixel of the row */
        st.v += q[i].dst_dx.v;
        pts[i] = vec3_make(200 * rng_uniform(&g) - 100, 200 * rng_uniform(&g) - 100,
                           200 * rng_uniform(&g) - 100);
    }
    double sink = 0;
    for (int f = TEXFILTER_NEAREST; f <= TEXFILTER_EWA; f++) {
        double t[64];
        for (int i = 0; i < N_QUERIES; i++) q[i].filter = (texture_filter)f;
        for (int k = 0; k < repeats; k++) {
            double t0 = now();
            for (int i = 0; i < N_QUERIES; i++) sink += texture_eval(&tx, &q[i]).r;
            t[k] = (now() - t0) / N_QUERIES * 1e9;
        }
        printf("lookup %s %.2f\n", texture_filter_name((texture_filter)f), median(t, repeats));
    }
    double t[64];
    for (int k = 0; k < repeats; k++) {
        double t0 = now();
        for (int i = 0; i < N_QUERIES; i++) sink += perlin_noise(pts[i].x, pts[i].y, pts[i].z);
        t[k] = (now() - t0) / N_QUERIES * 1e9;
    }
    printf("perlin %.2f\n", median(t, repeats));
    fprintf(stderr, "(checksum %g)\n", sink);
    texture_free(&tx);
    image_free(&img);
    free(q);
    free(pts);
    return 0;
fail:
    error_print(&err, stderr);
    texture_free(&tx);
    image_free(&img);
    free(q);
    free(pts);
    return 1;
}

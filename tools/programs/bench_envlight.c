/* bench_envlight.c - microbenchmarks of environment sampling (make bench):
 *   - sample + pdf of a 2048 x 1024 sun map, ns per call (median of repeats), alias and binary;
 *   - the same with alias on a 128 x 64 sun map, whose tables and texels stay in the cache: the
 *     arithmetic alone, without the big map's memory misses (the gap between the two is what
 *     memory costs; docs/environment-lighting.md);
 *   - table build time of a 4096 x 2048 map (cdf mode; alias tables on top).
 * The map is the procedural sun sky (a sun 10^5 times the sky), the case sampling is for. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench.h"
#include "envtex/envlight/envlight.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/core/rng.h"

static int make_env(int w, image *img, envmap *env, error *err)
{
    genenv_params p = genenv_defaults();
    p.width = w;
    if (genenv_make(GENENV_SUN, &p, img, err)) return -1;
    env->present = 1;
    env->img = img;
    env->scale = 1;
    env->to_env = mat4_identity();
    return 0;
}

/* median ns per envlight_sample (sample + pdf + L) over `repeats` runs of n samples */
static double time_samples(const envlight *el, int repeats, int n)
{
    double t[64], sink = 0;
    for (int k = 0; k < repeats && k < 64; k++) {
        rng g;
        rng_seed(&g, 1, (uint64_t)k);
        double t0 = now();
        for (int i = 0; i < n; i++) {
            envlight_sample_result r;
            envlight_sample(el, rng_uniform(&g), rng_uniform(&g), &r); /* sample + pdf + L */
            sink += r.pdf;
        }
        t[k] = (now() - t0) / n * 1e9;
    }
    if (sink < 0) printf("!"); /* keeps the loop */
    return median(t, repeats < 64 ? repeats : 64);
}

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 7;
    if (repeats < 1) repeats = 1;
    error err = {0};
    image img = {0};
    envmap env = {0};
    if (make_env(2048, &img, &env, &err)) goto fail;
    const int n = 1 << 20;
    static const char *names[] = {"binary", "alias"};
    double result[2];
    for (int s = 0; s < 2; s++) {
        envlight el;
        if (envlight_build(&el, &env, ENVSAMPLING_CDF, (envsampler_kind)s, 0, NULL, &err))
            goto fail;
        result[s] = time_samples(&el, repeats, n);
        printf("envlight sample+pdf 2048x1024 sun, %-6s: median %6.1f ns per sample (%d repeats of "
               "%d)\n",
               names[s], result[s], repeats, n);
        envlight_free(&el);
    }
    printf("envlight alias / binary time ratio: %.2f (target: alias <= 30 ns)\n",
           result[1] / result[0]);
    image_free(&img);
    if (make_env(128, &img, &env, &err)) goto fail;
    {
        envlight el;
        if (envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0, NULL, &err)) goto fail;
        double small = time_samples(&el, repeats, n);
        printf("envlight sample+pdf 128x64 sun (in cache), alias: median %6.1f ns per sample; "
               "the 2048x1024 map takes %.2fx that\n",
               small, result[1] / small);
        envlight_free(&el);
    }
    image_free(&img);
    if (make_env(4096, &img, &env, &err)) goto fail;
    for (int s = 0; s < 2; s++) {
        double t[64];
        for (int k = 0; k < repeats && k < 64; k++) {
            envlight el;
            double t0 = now();
            if (envlight_build(&el, &env, ENVSAMPLING_CDF, (envsampler_kind)s, 0, NULL, &err))
                goto fail;
            t[k] = now() - t0;
            envlight_free(&el);
        }
        printf("envlight tables 4096x2048, %-6s: median %.3f s to build (target <= 0.5 s)\n",
               names[s], median(t, repeats < 64 ? repeats : 64));
    }
    image_free(&img);
    return 0;
fail:
    error_print(&err, stderr);
    return 1;
}

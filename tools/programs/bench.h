/* bench.h - what the micro-benchmarks (bench_envlight, bench_envmap, bench_texture) share: a
 * monotonic clock and the median of repeated timings (make bench reports medians).
 * Header-only, static inline. */
#ifndef ENVTEX_BENCH_H
#define ENVTEX_BENCH_H

#include <stdlib.h>
#include <time.h>

/* seconds on a monotonic clock */
static inline double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* the median of v[0 .. n-1], n >= 1 (sorts v) */
static inline double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif

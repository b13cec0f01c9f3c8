/* bench_bvh - ray-tracing throughput of the BVH, in CPU time (the machines are shared).
 *
 *     bench_bvh primary SCENE [ROUNDS]   primary rays of SCENE (one a pixel, through the
 *                                        integrator: the scene's BVH with its quad lights),
 *                                        traced as renders trace them, a tile at a time
 *                                        (cpu_s), and one at a time (single_cpu_s)
 *     bench_bvh mesh sphere|soup N       build time, memory and closest-hit rays of a mesh of
 *                                        about N triangles made in memory (camera rays one at
 *                                        a time, and a tile at a time)
 *
 * Prints one key=value line per measurement.  The memory figure is what the allocator holds
 * after the build minus before it (glibc's mallinfo2): the same measure for any BVH layout.
 */
#define _GNU_SOURCE
#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/geometry/bvh.h"
#include "envtex/geometry/bvh_packet.h"
#include "envtex/integrators/integrator.h"
#include "envtex/core/rng.h"
#include "envtex/geometry/camera.h"
#include "envtex/scene/scene.h"
#include "envtex/render/render.h"
#include "envtex/scene/scene_load.h"

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double heap_bytes(void)
{
    struct mallinfo2 m = mallinfo2();
    return (double)m.uordblks + (double)m.hblkhd;
}

/* Every pixel's camera ray through the integrator as render.c traces them: a tile of pixels
 * at a time, their closest hits found together, then each made a scene_hit.  Returns the hits. */
static long primary_packets(integrator *it, const camera *cam, int w, int h)
{
    long hits = 0;
    const int size = RENDER_TILE;
    for (int y0 = 0; y0 < h; y0 += size)
        for (int x0 = 0; x0 < w; x0 += size) {
            int tw = w - x0 < size ? w - x0 : size, th = h - y0 < size ? h - y0 : size;
            int n = tw * th;
            ray r[BVH_PACKET];
            int got[BVH_PACKET];
            hit ht[BVH_PACKET];
            for (int i = 0; i < n; i++)
                r[i] = camera_ray(cam, x0 + i % tw + 0.5, y0 + i / tw + 0.5);
            bvh_intersect_packet(it->accel, r, n, got, ht);
            for (int i = 0; i < n; i++) {
                scene_hit sh;
                if (got[i]) sh.h = ht[i];
                integrator_scene_hit(it, &r[i], NULL, got[i], &sh);
                hits += sh.kind != SCENE_HIT_NOTHING;
            }
        }
    return hits;
}

/* The same one ray at a time (integrator_intersect). */
static long primary_single(integrator *it, const camera *cam, int w, int h)
{
    long hits = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            ray r = camera_ray(cam, x + 0.5, y + 0.5);
            scene_hit sh;
            integrator_intersect(it, &r, &sh);
            hits += sh.kind != SCENE_HIT_NOTHING;
        }
    return hits;
}

static int primary(const char *path, int rounds)
{
    scene sc;
    error err;
    if (scene_load(path, NULL, &sc, &err)) {
        fprintf(stderr, "bench_bvh: %s:%d: %s\n", err.file, err.line, err.msg);
        return 1;
    }
    bvh accel;
    integrator it;
    double t0 = cpu_seconds();
    if (lights_scene_bvh(&accel, &sc, NULL, &err) ||
        integrator_init(&it, &sc, &accel, NULL, &err)) {
        fprintf(stderr, "bench_bvh: %s: %s\n", path, err.msg);
        return 1;
    }
    printf("scene=%s triangles=%ld build_cpu_s=%.3f\n", path, sc.n_triangles, cpu_seconds() - t0);
    camera cam;
    camera_init(&cam, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
    for (int k = 0; k < rounds; k++) { /* the two ways, interleaved */
        double t1 = cpu_seconds();
        long hits = primary_packets(&it, &cam, sc.width, sc.height);
        double t2 = cpu_seconds();
        long hits1 = primary_single(&it, &cam, sc.width, sc.height);
        double s = t2 - t1, s1 = cpu_seconds() - t2, rays = (double)sc.width * sc.height;
        printf("round=%d rays=%.0f hits=%ld single_hits=%ld single_cpu_s=%.4f "
               "single_mrays_per_cpu_s=%.3f cpu_s=%.4f mrays_per_cpu_s=%.3f\n",
               k + 1, rays, hits, hits1, s1, rays / s1 * 1e-6, s, rays / s * 1e-6);
    }
    integrator_free(&it);
    bvh_free(&accel);
    scene_free(&sc);
    return 0;
}

static vec3 sphere_point(int i, int j, int rows, int cols)
{
    double theta = M_PI * i / rows, phi = 2 * M_PI * j / cols;
    return vec3_make(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
}

/* n triangles: a unit UV sphere (rows x 2 rows quads) or a soup in [-1, 1]^3 */
static triangle *make_mesh(const char *kind, long *n)
{
    int rows = (int)fmax(1, floor(sqrt(*n / 4.0))), cols = 2 * rows;
    int sphere = strcmp(kind, "sphere") == 0;
    if (sphere) *n = 2L * rows * cols;
    triangle *t = calloc((size_t)*n, sizeof *t);
    if (!t) return NULL;
    rng g;
    rng_seed(&g, 168, 0);
    for (long k = 0; k < *n; k++) {
        if (sphere) {
            int i = (int)(k / 2 / cols), j = (int)(k / 2 % cols), jn = (j + 1) % cols;
            vec3 a = sphere_point(i, j, rows, cols), b = sphere_point(i, jn, rows, cols);
            vec3 c = sphere_point(i + 1, j, rows, cols), d = sphere_point(i + 1, jn, rows, cols);
            t[k].p[0] = a, t[k].p[1] = k % 2 ? d : b, t[k].p[2] = k % 2 ? c : d;
        } else {
            vec3 c = vec3_make(2 * rng_uniform(&g) - 1, 2 * rng_uniform(&g) - 1,
                               2 * rng_uniform(&g) - 1);
            double size = 0.02 + 0.08 * rng_uniform(&g);
            for (int v = 0; v < 3; v++)
                t[k].p[v] = vec3_add(c, vec3_make(size * (rng_uniform(&g) - 0.5),
                                                  size * (rng_uniform(&g) - 0.5),
                                                  size * (rng_uniform(&g) - 0.5)));
        }
    }
    return t;
}

static int mesh(const char *kind, long n)
{
    triangle *t = make_mesh(kind, &n);
    if (!t) return 1;
    bvh b;
    error err;
    double m0 = heap_bytes(), t0 = cpu_seconds();
    if (bvh_build(&b, (bvh_prims){.triangles = t, .n_triangles = n, .name = kind}, NULL, &err)) {
        fprintf(stderr, "bench_bvh: %s\n", err.msg);
        return 1;
    }
    double build = cpu_seconds() - t0, bytes = heap_bytes() - m0;
    camera cam;
    int w = 640, h = 480;
    camera_init(&cam, vec3_make(0, 0.6, 3), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 45, w, h);
    long hits = 0, packet_hits = 0;
    double t1 = cpu_seconds();
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            ray r = camera_ray(&cam, x + 0.5, y + 0.5);
            hit ht;
            hits += bvh_intersect(&b, &r, &ht) != 0;
        }
    double t2 = cpu_seconds();
    for (int y0 = 0; y0 < h; y0 += RENDER_TILE) /* (RENDER_TILE divides 640 and 480) */
        for (int x0 = 0; x0 < w; x0 += RENDER_TILE) {
            ray r[BVH_PACKET];
            int got[BVH_PACKET], k = 0;
            hit ht[BVH_PACKET];
            for (int y = y0; y < y0 + RENDER_TILE; y++)
                for (int x = x0; x < x0 + RENDER_TILE; x++)
                    r[k++] = camera_ray(&cam, x + 0.5, y + 0.5);
            bvh_intersect_packet(&b, r, k, got, ht);
            for (int i = 0; i < k; i++) packet_hits += got[i] != 0;
        }
    double s = t2 - t1, sp = cpu_seconds() - t2, rays = (double)w * h;
    printf("mesh=%s triangles=%ld build_cpu_s=%.3f mbytes=%.1f bytes_per_tri=%.1f "
           "mrays_per_cpu_s=%.3f packet_mrays_per_cpu_s=%.3f hit_fraction=%.3f%s\n",
           kind, n, build, bytes / 1048576, bytes / (double)n, rays / s * 1e-6, rays / sp * 1e-6,
           (double)hits / rays, packet_hits == hits ? "" : " packet_hits_differ");
    bvh_free(&b);
    free(t);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 3 && !strcmp(argv[1], "primary"))
        return primary(argv[2], argc > 3 ? atoi(argv[3]) : 3);
    if (argc == 4 && !strcmp(argv[1], "mesh") &&
        (!strcmp(argv[2], "sphere") || !strcmp(argv[2], "soup")))
        return mesh(argv[2], atol(argv[3]));
    fprintf(stderr, "usage: bench_bvh primary SCENE [ROUNDS] | bench_bvh mesh sphere|soup N\n");
    return 2;
}

/* test_hardcases.c - the numerical hard cases of docs/robustness.md, through the public APIs:
 * envmaps with NaN / Inf / negative texels, 1 x 1 and 8192 x 4096 maps at the poles and the
 * seam; rays through shared triangle edges and vertices of a fan and a grid (exactly one
 * hit: no cracks, no double hits), a mesh moved to 1e7 and
 * scaled by 1e-4 .. 1e4 (no holes), grazing rays, degenerate triangles; reflection and
 * refraction far from the origin (no acne); a camera inside a sphere; textures of 1 x 1 and
 * 1 x N texels read far outside [0, 1] and with zero and whole-texture footprints; noise at
 * |x| = 1e6; tone mapping of Inf and NaN.  Each test names the bug it would catch.  Other
 * modules' own tests hold their own hard cases; this file collects the ones that cross
 * modules. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/mirrorball.h"
#include "envtex/envmaps/cubemap.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/textures/mipmap.h"
#include "envtex/textures/perlin.h"
#include "envtex/render/render.h"
#include "envtex/scene/scene.h"
#include "envtex/scene/scene_load.h"
#include "envtex/textures/texlookup.h"
#include "envtex/io/tonemap.h"
#include "envtex/geometry/bvh_packet.h"
#include "envtex/geometry/triangle.h"
#include "envtex/reflection/fresnel.h"
#include "unit.h"

#define PI 3.14159265358979323846

/* ---- helpers ------------------------------------------------------------------------------- */

static void load(scene *sc, const char *text)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(text, "hardcases.test", &o, sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
}

/* The scene's envmap becomes *map (taken over: *map is left empty), in the world's frame, at
 * scale 1. */
static void set_map(scene *sc, image *map)
{
    image_free(&sc->envmap.img);
    sc->envmap.img = *map;
    *map = (image){0};
    sc->envmap.present = 1;
    sc->envmap.scale = 1;
    sc->envmap.xf = sc->envmap.inv = mat4_identity();
}

/* The scene's envmap becomes a genenv sky (envmap frame = world frame, scale 1). */
static void set_sky(scene *sc)
{
    genenv_params p = genenv_defaults();
    p.width = 64;
    error err = {0};
    image sky = {0};
    ck_assert_int_eq(genenv_make(GENENV_SKY, &p, &sky, &err), 0);
    set_map(sc, &sky);
}

static void render_at(const scene *sc, int spp, image *out, render_stats *st)
{
    render_opts o = render_defaults();
    o.spp = spp;
    error err = {0};
    if (render_scene(sc, &o, out, st, &err)) ck_abort_msg("render: %s", err.msg);
}

static void render(const scene *sc, image *out, render_stats *st) { render_at(sc, 1, out, st); }

/* The mean of the green channel of sc rendered at spp samples a pixel; *bad: pixels that are not
 * finite. */
static double render_mean(const scene *sc, int spp, long *bad)
{
    image im = {0};
    render_stats st;
    render_at(sc, spp, &im, &st);
    double sum = 0;
    *bad = 0;
    for (int y = 0; y < im.h; y++)
        for (int x = 0; x < im.w; x++) {
            rgb c = image_get(&im, x, y);
            *bad += !rgb_is_finite(c);
            sum += c.g;
        }
    double n = (double)im.w * im.h;
    image_free(&im);
    return sum / n;
}

static long count_nonfinite(const image *im)
{
    long n = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++)
            if (!rgb_is_finite(image_get(im, x, y))) n++;
    return n;
}

/* Direction of the centre of texel (c, r) of a W x H lat-long map (latlong.h). */
static vec3 texel_dir(int c, int r, int w, int h)
{
    double th = PI * (r + 0.5) / h, ph = 2 * PI * (c + 0.5) / w;
    return vec3_make(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
}

/* ---- envmaps ------------------------------------------------------------------------------- */

/* A NaN, a +Inf and a negative texel in a constant map: lookups two texels or more away see
 * only the constant (catches a lookup that reads outside its 2 x 2 footprint, or a wrap bug
 * that lands on the bad texels), and the nearest lookup returns each bad texel as it is (the
 * lookup does not hide bad data; envlight and the renderer's NaN count report it). */
START_TEST(test_bad_texels_stay_local_and_are_returned_as_they_are)
{
    image m = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&m, 32, 16, &err), 0);
    for (size_t i = 0; i < (size_t)32 * 16 * 3; i++) m.px[i] = 0.5f;
    image_px(&m, 10, 8)[0] = NAN;
    image_px(&m, 11, 8)[1] = INFINITY;
    image_px(&m, 12, 8)[2] = -2.0f;
    int bad = 0;
    for (int r = 0; r < 16; r++)
        for (int c = 0; c < 32; c++) {
            if (r >= 6 && r <= 10 && c >= 8 && c <= 14) continue;
            rgb v = latlong_lookup_bilinear(&m, texel_dir(c, r, 32, 16));
            if (fabs(v.r - 0.5) > 1e-6 || fabs(v.g - 0.5) > 1e-6 || fabs(v.b - 0.5) > 1e-6) bad++;
        }
    ck_assert_int_eq(bad, 0);
    ck_assert(isnan(latlong_lookup_nearest(&m, texel_dir(10, 8, 32, 16)).r));
    ck_assert(isinf(latlong_lookup_nearest(&m, texel_dir(11, 8, 32, 16)).g));
    ck_assert(latlong_lookup_nearest(&m, texel_dir(12, 8, 32, 16)).b == -2.0);
    image_free(&m);
}
END_TEST

/* A 1 x 1 map is one colour in every direction, poles and seam included, for both lookups
 * (catches a bilinear footprint that needs two texels, or a division by W - 1 or H - 1). */
START_TEST(test_one_by_one_map_is_constant_everywhere)
{
    image m = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&m, 1, 1, &err), 0);
    image_set(&m, 0, 0, rgb_make(0.25, 2.0, 8.0));
    const vec3 dirs[] = {{0, 0, 1},  {0, 0, -1},     {1, 0, 0},        {1, -1e-300, 0},
                         {-1, 0, 0}, {1e-300, 0, 1}, {0.3, -0.4, 0.5}, {-1e-9, -1e-9, -1}};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        rgb b = latlong_lookup_bilinear(&m, dirs[i]), n = latlong_lookup_nearest(&m, dirs[i]);
        ck_assert_msg(b.r == 0.25 && b.g == 2.0 && b.b == 8.0, "bilinear dir %zu: %g %g %g", i, b.r,
                      b.g, b.b);
        ck_assert_msg(n.r == 0.25 && n.g == 2.0 && n.b == 8.0, "nearest dir %zu", i);
    }
    image_free(&m);
}
END_TEST

/* An 8192 x 4096 map (allocated zero-filled, so only the texels written here cost memory):
 * every pole-row and seam-column texel is found by the direction of its centre; the poles
 * themselves and directions a hair either side of the seam (phi = 0 and phi -> 2 pi, where
 * u rounds to 1) give the pole / seam values, never a texel out of range (AddressSanitizer) or
 * a blend with the wrong side.  Catches float precision loss in u, v at this resolution and
 * an off-by-one at the wrap. */
START_TEST(test_8192_map_poles_and_seam_are_exact)
{
    const int w = 8192, h = 4096;
    image m = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&m, w, h, &err), 0);
    for (int c = 0; c < w; c++) {
        image_set(&m, c, 0, rgb_make(1, 0, 0));     /* zenith row: red */
        image_set(&m, c, h - 1, rgb_make(0, 0, 1)); /* nadir row: blue */
    }
    for (int r = 1; r < h - 1; r++) {
        image_set(&m, 0, r, rgb_make(0, 1, 0));     /* first column: green */
        image_set(&m, w - 1, r, rgb_make(0, 1, 0)); /* last column: green too */
    }
    uv2 uv;
    int bad = 0;
    for (int c = 0; c < w; c += 7) { /* pole rows, by their texel centres */
        rgb a = latlong_lookup_nearest(&m, texel_dir(c, 0, w, h));
        rgb b = latlong_lookup_nearest(&m, texel_dir(c, h - 1, w, h));
        if (a.r != 1 || b.b != 1) bad++;
    }
    for (int r = 1; r < h - 1; r += 5) { /* seam columns */
        rgb a = latlong_lookup_nearest(&m, texel_dir(0, r, w, h));
        rgb b = latlong_lookup_nearest(&m, texel_dir(w - 1, r, w, h));
        rgb across = latlong_lookup_bilinear(
            &m, vec3_make(sin(PI * (r + 0.5) / h), -1e-300, cos(PI * (r + 0.5) / h)));
        if (a.g != 1 || b.g != 1 || fabs(across.g - 1) > 1e-6) bad++;
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_near(latlong_lookup_bilinear(&m, vec3_make(0, 0, 1)).r, 1, 1e-6);
    ck_assert_near(latlong_lookup_bilinear(&m, vec3_make(0, 0, -1)).b, 1, 1e-6);
    ck_assert_near(latlong_lookup_bilinear(&m, vec3_make(1e-300, -1e-300, 1)).r, 1, 1e-6);
    /* u in [0, 1) even where phi = 2 pi - tiny rounds to 2 pi */
    const vec3 seam[] = {{1, -1e-300, 0}, {1, -1e-17, 0}, {1, -1e-16, 1}, {1, 0, 0}, {1, -0.0, 0}};
    for (size_t i = 0; i < sizeof seam / sizeof seam[0]; i++) {
        ck_assert_int_eq(latlong_dir_to_uv(seam[i], &uv), 0);
        ck_assert_msg(uv.u >= 0 && uv.u < 1, "seam dir %zu: u = %.17g", i, uv.u);
        ck_assert_msg(uv.v >= 0 && uv.v <= 1, "seam dir %zu: v = %.17g", i, uv.v);
    }
    image_free(&m);
}
END_TEST

/* ---- triangles ----------------------------------------------------------------------------- */

/* How many of the n triangles tri[k] ray r hits (each tested alone, so two hits at one t count
 * as two). */
static int count_hits(const triangle *tri, int n, const ray *r)
{
    int hits = 0;
    for (int k = 0; k < n; k++) {
        double t, b1, b2;
        hits += triangle_intersect(tri[k].p[0], tri[k].p[1], tri[k].p[2], r, &t, &b1, &b2);
    }
    return hits;
}

/* A fan of 7 triangles around a centre vertex at awkward (non-binary) coordinates, every other
 * one wound the other way.  Rays along -z are swept across every shared edge, in steps of a few
 * ulps around the edge line, and through the centre vertex and near every rim vertex from
 * slanted directions: each ray hits exactly one triangle.  Catches a strict inside test, or an
 * edge function whose rounding differs between the two triangles of an edge (pinholes), and an
 * inside test with a tolerance (two hits: an edge counted twice, as light or as an occluder). */
START_TEST(test_rays_across_shared_edges_and_vertices_hit_exactly_one_triangle)
{
    enum { N = 7 };
    vec3 centre = vec3_make(0.1, 1.0 / 3.0, 0.7);
    vec3 rim[N];
    triangle fan[N];
    for (int k = 0; k < N; k++) {
        double a = 2 * PI * k / N + 0.1;
        rim[k] = vec3_make(centre.x + 1.3 * cos(a), centre.y + 0.9 * sin(a), 0.7 + 0.01 * k);
    }
    for (int k = 0; k < N; k++) {
        fan[k].p[0] = centre;
        fan[k].p[1 + k % 2] = rim[k];
        fan[k].p[2 - k % 2] = rim[(k + 1) % N];
    }
    long rays = 0, misses = 0, doubles = 0;
    for (int k = 0; k < N; k++) {
        vec3 a = centre, b = rim[k];
        vec3 side = vec3_make(-(b.y - a.y), b.x - a.x, 0); /* across the edge, in the xy plane */
        double len = vec3_length(side);
        side = vec3_scale(side, 1 / len);
        for (int i = 1; i < 40; i++) {
            double s = i / 40.0 + 1e-3 * i; /* along the edge, not at a vertex */
            vec3 on = vec3_add(a, vec3_scale(vec3_sub(b, a), s < 1 ? s : 0.999));
            for (int j = -8; j <= 8; j++) {
                double off = j * 1e-15 * (1 + fabs(on.x) + fabs(on.y));
                ray r = {vec3_make(on.x + off * side.x, on.y + off * side.y, 5),
                         vec3_make(0, 0, -1), 0, INFINITY};
                int hits = count_hits(fan, N, &r);
                rays++, misses += hits == 0, doubles += hits > 1;
            }
        }
    }
    for (int k = 0; k <= N; k++) { /* through the vertices, from a few slanted directions */
        vec3 v = k < N ? rim[k] : centre;
        if (k < N)
            v = vec3_add(vec3_scale(v, 0.999), vec3_scale(centre, 0.001)); /* rim: just inside */
        for (int j = 0; j < 8; j++) {
            vec3 d = vec3_make(0.3 * cos(j), 0.3 * sin(j), -1);
            ray r = {vec3_sub(v, vec3_scale(d, 3)), d, 0, INFINITY};
            int hits = count_hits(fan, N, &r);
            rays++, misses += hits == 0, doubles += hits > 1;
        }
    }
    ck_assert_msg(misses == 0 && doubles == 0, "of %ld rays, %ld fell through the fan, %ld hit two",
                  rays, misses, doubles);
}
END_TEST

/* A grid of 12 x 12 quads on a tilted, bumpy sheet at awkward coordinates, split along
 * alternating diagonals, at the origin and moved to 1e6: rays through every inner vertex (where
 * eight or four triangles meet) and through points of its edges, from three directions,
 * each hit exactly one triangle; and the BVH finds each of them (the same t as that triangle).
 * Catches what the fan does, at vertices of both valences, and a filter that drops a hit when
 * the sheet is far from the origin. */
START_TEST(test_rays_through_a_grid_hit_exactly_one_triangle)
{
    enum { G = 12, NT = 2 * G * G };
    static triangle tri[NT];
    const vec3 dirs[3] = {{0, 0, -1}, {0.31, -0.17, -1}, {-0.6, 0.45, -0.7}};
    const double at[2] = {0, 1e6};
    for (int o = 0; o < 2; o++) {
        vec3 v[G + 1][G + 1];
        for (int j = 0; j <= G; j++)
            for (int i = 0; i <= G; i++)
                v[j][i] = vec3_make(at[o] + i / 3.0 + 0.01 * sin(j), at[o] + j / 7.0 * 2.3,
                                    at[o] + 0.1 * i - 0.07 * j + 0.02 * cos(i * j));
        int n = 0;
        memset(tri, 0, sizeof tri);
        for (int j = 0; j < G; j++)
            for (int i = 0; i < G; i++) {
                vec3 a = v[j][i], b = v[j][i + 1], c = v[j + 1][i + 1], d = v[j + 1][i];
                if ((i + j) % 2) /* diagonal a-c */
                    tri[n].p[0] = a, tri[n].p[1] = b, tri[n++].p[2] = c,
                    tri[n].p[0] = a, tri[n].p[1] = c, tri[n++].p[2] = d;
                else /* diagonal b-d */
                    tri[n].p[0] = a, tri[n].p[1] = b, tri[n++].p[2] = d,
                    tri[n].p[0] = b, tri[n].p[1] = c, tri[n++].p[2] = d;
            }
        bvh b;
        error err = {0};
        ck_assert_int_eq(bvh_build(&b, (bvh_prims){.triangles = tri, .n_triangles = n}, NULL, &err),
                         0);
        long rays = 0, misses = 0, doubles = 0, bvh_misses = 0;
        for (int j = 1; j < G; j++)
            for (int i = 1; i < G; i++)
                for (int e = 0; e < 4; e++) { /* the vertex, points on two of its edges, and
                                                 * towards its diagonal neighbour (an edge where
                                                 * the quad's diagonal runs there) */
                    vec3 q = v[j][i], nb = e == 1 ? v[j][i + 1] : e == 2 ? v[j + 1][i]
                                                                         : v[j + 1][i + 1];
                    if (e) q = vec3_add(vec3_scale(q, 0.6), vec3_scale(nb, 0.4));
                    for (int k = 0; k < 3; k++) {
                        ray r = {vec3_madd(q, dirs[k], -2), dirs[k], 0, INFINITY};
                        int hits = count_hits(tri, n, &r);
                        hit h;
                        rays++, misses += hits == 0, doubles += hits > 1;
                        bvh_misses += bvh_intersect(&b, &r, &h) != BVH_SURFACE;
                    }
                }
        ck_assert_msg(misses == 0 && doubles == 0 && bvh_misses == 0,
                      "grid at %g: of %ld rays, %ld fell through, %ld hit two, the BVH missed %ld",
                      at[o], rays, misses, doubles, bvh_misses);
        bvh_free(&b);
    }
}
END_TEST

/* A UV sphere of 48 x 24 quads (2304 triangles, the poles' degenerate ones included) of radius
 * `scale` about (far, far, far), seen from `dist` radii away along a diagonal: every ray of a
 * 32 x 32 grid gets from the BVH - one at a time, as shadow rays and in packets - what the
 * double test of every triangle gives (hit or miss, and the closest t).  Catches a float
 * filter that is not conservative far from the origin: p0 rounded to float moves by |p0|
 * 2^-24, at 1e6 about the size of these triangles, and a fixed barycentric margin rejected true
 * hits (at 1e5, of 1024 rays, 4 holes and 40 that found a farther triangle; at 1e7 nearly
 * all); or far from its camera: s = o - p0 rounded to float (seen from 1e4 radii, 2 rays found
 * a farther triangle). */
static void check_mesh_far_from_origin(double far, double scale, double dist)
{
    enum { NU = 48, NV = 24, W = 32 };
    static triangle tri[2 * NU * NV];
    memset(tri, 0, sizeof tri);
    int n = 0;
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            vec3 q[4];
            for (int k = 0; k < 4; k++) {
                double th = PI * (j + (k >= 2)) / NV, ph = 2 * PI * (i + (k == 1 || k == 2)) / NU;
                q[k] = vec3_make(far + scale * sin(th) * cos(ph), far + scale * sin(th) * sin(ph),
                                 far + scale * cos(th));
            }
            tri[n].p[0] = q[0], tri[n].p[1] = q[1], tri[n++].p[2] = q[2];
            tri[n].p[0] = q[0], tri[n].p[1] = q[2], tri[n++].p[2] = q[3];
        }
    bvh b;
    error err = {0};
    ck_assert_int_eq(bvh_build(&b, (bvh_prims){.triangles = tri, .n_triangles = n}, NULL, &err), 0);
    /* the camera dist radii away along an awkward diagonal (so that every coordinate of
     * o - p0 is large), the view's width shrinking with the distance */
    vec3 w = vec3_normalize(vec3_make(1, 1.1, 0.9)), u, v;
    vec3_basis(w, &u, &v);
    vec3 o = vec3_madd(vec3_make(far, far, far), w, -dist * scale);
    double spread = 4 / dist;
    long holes = 0, extra = 0, wrong_t = 0, shadow = 0, packet = 0, hits = 0;
    for (int y = 0; y < W; y++) {
        ray r[W];
        int ref[W];
        double ref_t[W];
        for (int x = 0; x < W; x++) {
            vec3 d = vec3_madd(vec3_madd(w, u, ((x + 0.5) / W * 0.6 - 0.3) * spread), v,
                               (0.3 - (y + 0.5) / W * 0.6) * spread);
            r[x] = (ray){o, vec3_normalize(d), 0, INFINITY};
            ray rr = r[x];
            ref[x] = 0;
            for (int k = 0; k < n; k++) {
                double t, b1, b2;
                if (triangle_intersect(tri[k].p[0], tri[k].p[1], tri[k].p[2], &rr, &t, &b1, &b2))
                    ref[x] = 1, rr.tmax = ref_t[x] = t;
            }
            hit h;
            int got = bvh_intersect(&b, &r[x], &h) == BVH_SURFACE;
            hits += ref[x];
            holes += ref[x] && !got;
            extra += got && !ref[x];
            wrong_t += got && ref[x] && h.t != ref_t[x];
            shadow += bvh_occluded(&b, &r[x]) != ref[x];
        }
        int got[W];
        hit h[W];
        bvh_intersect_packet(&b, r, W, got, h);
        for (int x = 0; x < W; x++) packet += (got[x] == BVH_SURFACE) != ref[x];
    }
    ck_assert_msg(hits > W * W / 4, "at %g, scale %g, %g radii: the mesh is not in view", far,
                  scale, dist);
    ck_assert_msg(holes == 0 && extra == 0 && wrong_t == 0 && shadow == 0 && packet == 0,
                  "mesh at %g, scale %g, seen from %g radii: of %ld hits, %ld holes, %ld extra, "
                  "%ld with another t; %ld shadow rays and %ld packet rays disagree", far, scale,
                  dist, hits, holes, extra,
                  wrong_t, shadow, packet);
    bvh_free(&b);
}

START_TEST(test_a_mesh_far_from_the_origin_has_no_holes)
{
    const double at[][2] = {{0, 1}, {1e3, 1}, {1e5, 1}, {1e6, 1}, {1e7, 1}, {1e6, 1e-4},
                            {0, 1e-4}, {0, 1e4}, {1e5, 1e4}};
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++)
        check_mesh_far_from_origin(at[i][0], at[i][1], 4);
    for (double dist = 1e2; dist <= 1e6; dist *= 10) check_mesh_far_from_origin(0, 1, dist);
}
END_TEST

/* The same through the whole pipeline: a quad of two triangles whose diagonal runs through
 * pixel centres fills the view; every pixel is the quad's colour (a crack shows the black
 * background). */
START_TEST(test_rendered_quad_diagonal_has_no_crack)
{
    scene sc;
    load(&sc, "size 33 33\n"
              "camera 0 0 3  0 0 0  0 1 0  30\n"
              "ambient 1 1 1\n"
              "vertex -2 -2 0\nvertex 2 -2 0\nvertex 2 2 0\nvertex -2 2 0\n"
              "tri 0 1 2\ntri 0 2 3\n");
    image img = {0};
    render_stats st;
    render(&sc, &img, &st);
    long black = 0;
    for (int y = 0; y < img.h; y++)
        for (int x = 0; x < img.w; x++)
            if (image_get(&img, x, y).r < 0.5) black++;
    ck_assert_msg(black == 0, "%ld pixels see through the diagonal", black);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

/* Grazing footprints: needles 1e-9 wide and 0.1 long at angles 0 .. 90 degrees, on a 64 x 64
 * ramp (texel i holds (i + 1/2) / 64, so its bilinear reconstruction is s itself): EWA and
 * trilinear give s (a symmetric normalized filter keeps a linear function) to 2e-3, an eighth
 * of a texel (EWA's Gaussian, cut to its support on the texel grid, is centred within a
 * fraction of a texel: 5e-4 measured); needles 1e6 long (a plane seen edge-on) give a value
 * within the ramp, never NaN.  Catches EWA's
 * ellipse without its one texel^2 (a 1e-9 needle then meets the texel grid lopsided: 3.6e-3
 * off), a level from log2 of 0, and an ellipse coefficient that overflows to NaN. */
START_TEST(test_grazing_footprints_keep_a_ramp_and_stay_finite)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 64, 64, &err), 0);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) image_set(&im, x, y, rgb_gray((x + 0.5) / 64));
    mipmap m;
    ck_assert_int_eq(mipmap_build(&m, &im, WRAP_CLAMP, &err), 0);
    for (int a = 0; a <= 6; a++) {
        double ang = a * PI / 12;
        for (int i = 0; i < 3; i++) {
            uv2 st = {0.3 + 0.2 * i, 0.35 + 0.1 * i};
            uv2 dx = {1e-9 * cos(ang), -1e-9 * sin(ang)}, dy = {0.1 * sin(ang), 0.1 * cos(ang)};
            double e = mipmap_lookup_ewa(&m, st, dx, dy).r;
            double t = mipmap_lookup_trilinear(&m, st, 0.1).r;
            ck_assert_msg(fabs(e - st.u) < 2e-3 && fabs(t - st.u) < 2e-3,
                          "angle %d deg at s %g: EWA %.9g, trilinear %.9g", a * 15, st.u, e, t);
            uv2 far = {1e6 * sin(ang), 1e6 * cos(ang)};
            double g = mipmap_lookup_ewa(&m, st, dx, far).r;
            double h = mipmap_lookup_trilinear(&m, st, 1e6).r;
            ck_assert_msg(isfinite(g) && g >= 0.5 / 64 && g <= 63.5 / 64 && isfinite(h) &&
                              h >= 0.5 / 64 && h <= 63.5 / 64,
                          "angle %d deg, 1e6 long: EWA %g, trilinear %g", a * 15, g, h);
        }
    }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

/* Grazing rays (direction nearly in the plane) either miss or hit at a finite t on the plane;
 * rays exactly in the plane never hit; degenerate triangles (collinear corners, a repeated
 * corner, a needle) are never hit (catches NaN t or barycentrics from a zero determinant). */
START_TEST(test_grazing_rays_and_degenerate_triangles_give_no_garbage)
{
    vec3 p0 = vec3_make(0, 0, 0), p1 = vec3_make(1, 0, 0), p2 = vec3_make(0, 1, 0);
    int bad = 0;
    for (int k = 0; k < 60; k++) {
        double dz = -pow(10.0, -k * 0.3); /* from -1 down to -1e-18: ever closer to grazing */
        ray r = {vec3_make(-0.5, 0.25, -dz * 0.5), vec3_make(1, 0.01, dz), 0, INFINITY};
        double t, b1, b2;
        if (triangle_intersect(p0, p1, p2, &r, &t, &b1, &b2)) {
            vec3 p = vec3_madd(r.o, r.d, t);
            if (!isfinite(t) || !isfinite(b1) || !isfinite(b2) || fabs(p.z) > 1e-9 || b1 < -1e-9 ||
                b2 < -1e-9)
                bad++;
        }
    }
    ck_assert_int_eq(bad, 0);
    double t, b1, b2;
    ray inplane = {vec3_make(-1, 0.2, 0), vec3_make(1, 0, 0), 0, INFINITY};
    ck_assert_int_eq(triangle_intersect(p0, p1, p2, &inplane, &t, &b1, &b2), 0);
    ray down = {vec3_make(0.2, 0.2, 1), vec3_make(0, 0, -1), 0, INFINITY};
    ck_assert_int_eq(
        triangle_intersect(p0, vec3_make(1, 1, 0), vec3_make(2, 2, 0), &down, &t, &b1, &b2), 0);
    ck_assert_int_eq(triangle_intersect(p0, p0, p2, &down, &t, &b1, &b2), 0);
    ck_assert_int_eq(
        triangle_intersect(p0, vec3_make(1, 1e-300, 0), vec3_make(2, 0, 0), &down, &t, &b1, &b2),
        0);
    /* and in a render: degenerate triangles in front of a sphere leave no NaN */
    scene sc;
    load(&sc, "size 16 16\ncamera 0 0 4  0 0 0  0 1 0  45\nambient 0.5 0.5 0.5\n"
              "vertex 0 0 1\nvertex 1 1 1\nvertex 2 2 1\nvertex 0.1 0.2 1\n"
              "tri 0 1 2\ntri 0 0 1\ntri 3 3 3\nsphere 0 0 0 1\n");
    image img = {0};
    render_stats st;
    render(&sc, &img, &st);
    ck_assert_int_eq(count_nonfinite(&img), 0);
    ck_assert_int_eq(st.nonfinite_pixels, 0);
    ck_assert_near(image_get(&img, 8, 8).r, 0.5, 1e-6); /* the sphere, seen through the slivers */
    image_free(&img);
    scene_free(&sc);
}
END_TEST

/* ---- textures and noise -------------------------------------------------------------------- */

/* Coordinates far outside [0, 1], negative, NaN and infinite, in every wrap mode, on a 1 x 1 and
 * a 1 x 5 texture: the 1 x 1 returns its texel exactly; the 1 x 5 (a column: only t matters)
 * returns a blend of its texels, within their range and finite (catches an int overflow of
 * floor(s W) at 1e9, a negative modulo, a NaN index, a division by W - 1 = 0). */
START_TEST(test_tiny_textures_read_far_outside_stay_inside_their_texels)
{
    image one = {0}, col = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&one, 1, 1, &err), 0);
    ck_assert_int_eq(image_alloc(&col, 1, 5, &err), 0);
    image_set(&one, 0, 0, rgb_make(0.25, 0.5, 0.75));
    for (int j = 0; j < 5; j++) image_set(&col, 0, j, rgb_gray(1 + j)); /* 1 .. 5 */
    const double far[] = {0.5,   -0.5,   1e6 + 0.3, -1e6 - 0.3, 1e9 + 0.7, -1e9 - 0.7, 3e15, -3e15,
                          1e300, -1e300, NAN,       INFINITY,   -INFINITY, 1.0,        -0.0};
    const wrap_mode wraps[] = {WRAP_REPEAT, WRAP_CLAMP, WRAP_MIRROR};
    int n = sizeof far / sizeof far[0], bad = 0;
    for (int w = 0; w < 3; w++)
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) {
                uv2 st = {far[a], far[b]};
                rgb p = texlookup_nearest(&one, st, wraps[w]),
                    q = texlookup_bilinear(&one, st, wraps[w]);
                if (p.r != 0.25 || p.b != 0.75 || fabs(q.r - 0.25) > 1e-12 ||
                    fabs(q.b - 0.75) > 1e-12)
                    bad++;
                rgb c = texlookup_nearest(&col, st, wraps[w]),
                    d = texlookup_bilinear(&col, st, wraps[w]);
                if (!(c.r >= 1 && c.r <= 5) || !(d.r >= 1 - 1e-12 && d.r <= 5 + 1e-12)) bad++;
            }
    ck_assert_int_eq(bad, 0);
    image_free(&one);
    image_free(&col);
}
END_TEST

/* Footprints of zero and of the whole texture, for trilinear and EWA: zero is the bilinear
 * lookup of the base; the whole texture (and beyond, and non-finite) is its mean, here of an
 * 8 x 8 checkerboard of 0 and 1, i.e. 0.5 (catches a log2(0) level, a level index past the top
 * of the pyramid, a NaN footprint that reaches an index). */
START_TEST(test_zero_and_whole_texture_footprints_give_bilinear_and_mean)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 8, 8, &err), 0);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) image_set(&im, x, y, rgb_gray((x + y) & 1));
    mipmap m;
    ck_assert_int_eq(mipmap_build(&m, &im, WRAP_REPEAT, &err), 0);
    uv2 st = {0.3, 0.7}, zero = {0, 0};
    rgb bl = texlookup_bilinear(&im, st, WRAP_REPEAT);
    ck_assert_near(mipmap_lookup_trilinear(&m, st, 0).r, bl.r, 1e-6);
    ck_assert_near(mipmap_lookup_ewa(&m, st, zero, zero).r, bl.r, 1e-12);
    const double whole[] = {1, 2, 1e6, INFINITY};
    for (size_t i = 0; i < sizeof whole / sizeof whole[0]; i++) {
        ck_assert_near(mipmap_lookup_trilinear(&m, st, whole[i]).r, 0.5, 1e-6);
        uv2 dx = {whole[i], 0}, dy = {0, whole[i]};
        ck_assert_near(mipmap_lookup_ewa(&m, st, dx, dy).r, 0.5, 1e-6);
    }
    uv2 nan2 = {NAN, NAN};
    ck_assert_near(mipmap_lookup_ewa(&m, st, nan2, nan2).r, 0.5, 1e-6);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

/* Improved noise at |x| = 1e6 and at negative coordinates: 0 at every lattice point, within
 * PERLIN_NOISE_BOUND and finite between them, and fbm with the most octaves stays finite
 * (catches an int conversion of floor(x) that overflows or rounds the wrong way below zero,
 * and a fraction computed as x - (int)x, which is wrong for negatives). */
START_TEST(test_noise_far_away_and_negative_is_bounded_and_zero_on_the_lattice)
{
    const double base[] = {1e6, -1e6, -1.0, -37.0, 123456.0, -987654.0};
    int bad = 0;
    for (size_t i = 0; i < sizeof base / sizeof base[0]; i++) {
        double x = base[i];
        if (perlin_noise(x, -x, x) != 0.0) bad++;
        for (int k = 1; k < 50; k++) {
            double f = k / 50.0;
            double n = perlin_noise(x + f, x - f * 0.7, -x + f * 0.3);
            if (!isfinite(n) || fabs(n) > PERLIN_NOISE_BOUND) bad++;
        }
        double fbm = perlin_fbm(vec3_make(x + 0.1, x, -x), PERLIN_MAX_OCTAVES, 2.0, 0.5);
        if (!isfinite(fbm) || fabs(fbm) > 2 * PERLIN_NOISE_BOUND) bad++;
    }
    ck_assert_int_eq(bad, 0);
    /* continuity across the negative lattice point x = -1: no jump from a wrong floor */
    ck_assert_near(perlin_noise(-1 - 1e-9, 0.3, 0.6), perlin_noise(-1 + 1e-9, 0.3, 0.6), 1e-6);
}
END_TEST

/* ---- self-intersection --------------------------------------------------------------------- */

/* The 2304-triangle UV sphere of check_mesh_far_from_origin, radius 1 about (o, o, o), as
 * scene commands appended at t + n (capacity cap); returns the new length. */
static int ball_mesh(char *t, size_t cap, int n, double o)
{
    enum { NU = 48, NV = 24 };
    n += snprintf(t + n, cap - n, "maxverts %d\n", (NU + 1) * (NV + 1));
    for (int j = 0; j <= NV; j++)
        for (int i = 0; i <= NU; i++) {
            double th = PI * j / NV, ph = 2 * PI * i / NU;
            n += snprintf(t + n, cap - n, "vertex %.17g %.17g %.17g\n", o + sin(th) * cos(ph),
                          o + sin(th) * sin(ph), o + cos(th));
        }
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            int a = j * (NU + 1) + i, b = a + 1, c = b + NU + 1, d = a + NU + 1;
            n += snprintf(t + n, cap - n, "tri %d %d %d\ntri %d %d %d\n", a, c, b, a, d, c);
        }
    return n;
}
#define BALL_MESH_CHARS 200000 /* room for ball_mesh's commands */

/* A scene of a ball seen from 4 radii away, everything moved by `far` on each axis: the ball
 * an analytic sphere or (mesh = 1) ball_mesh, in `material`.  The caller frees it. */
static char *far_scene(const char *material, double far, int mesh)
{
    size_t cap = 512 + strlen(material) + BALL_MESH_CHARS;
    char *t = malloc(cap);
    ck_assert_ptr_nonnull(t);
    double o = far;
    int n = snprintf(t, cap,
                     "size 48 48\ncamera %.17g %.17g %.17g  %.17g %.17g %.17g  0 0 1  40\n"
                     "maxdepth 6\nambient 0 0 0\n%s\n",
                     o, o - 4, o + 0.5, o, o, o, material);
    if (mesh)
        ball_mesh(t, cap, n, o);
    else
        snprintf(t + n, cap - n, "sphere %.17g %.17g %.17g 1\n", o, o, o);
    return t;
}

/* How many pixels of two renders differ by more than tol in a channel (or are not finite). */
static long pixels_apart(const image *a, const image *b, double tol)
{
    long differ = 0;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            rgb p = image_get(a, x, y), q = image_get(b, x, y);
            differ += !rgb_is_finite(q) || fabs(p.r - q.r) > tol || fabs(p.g - q.g) > tol ||
                      fabs(p.b - q.b) > tol;
        }
    return differ;
}

/* The ball in `material` at `far` renders like the same ball at the origin: every pixel within
 * tol (no acne: a leaving ray that hits its own surface; no light leaking through a mesh). */
static void check_far_from_origin(const char *name, const char *material, double far, int mesh,
                                  double tol)
{
    char *a = far_scene(material, 0, mesh), *b = far_scene(material, far, mesh);
    scene sa, sb;
    load(&sa, a);
    load(&sb, b);
    free(a);
    free(b);
    set_sky(&sa);
    set_sky(&sb);
    image ia = {0}, ib = {0};
    render_stats st;
    render(&sa, &ia, &st);
    render(&sb, &ib, &st);
    long differ = pixels_apart(&ia, &ib, tol);
    ck_assert_msg(differ == 0, "%s %s at %g: %ld of %d pixels differ by more than %g",
                  mesh ? "mesh" : "sphere", name, far, differ, ia.w * ia.h, tol);
    image_free(&ia);
    image_free(&ib);
    scene_free(&sa);
    scene_free(&sb);
}

/* A mirror ball, analytic and a mesh, at 1e5 .. 1e7: every pixel within 0.005 of the ball at
 * the origin.  Catches a leaving ray offset too small for the hit point's rounding (acne) and
 * one far too large: RAY_OFFSET_REL at 1e-9 moved rays by 1e-2 at 1e7. */
START_TEST(test_mirror_far_from_origin_has_no_acne)
{
    for (int mesh = 0; mesh < 2; mesh++)
        for (double far = 1e5; far <= 1e7; far *= 10)
            check_far_from_origin("mirror", "brdf mirror\nspecular 1 1 1", far, mesh, 0.005);
}
END_TEST

/* The same for glass (rays that enter, reflect inside and leave): with RAY_OFFSET_REL at 1e-9,
 * 0.04 apart at 1e6 and 0.07 at 1e7 (the sphere), 0.74 at 1e7 (the mesh). */
START_TEST(test_glass_far_from_origin_has_no_acne)
{
    for (int mesh = 0; mesh < 2; mesh++)
        for (double far = 1e5; far <= 1e7; far *= 10)
            check_far_from_origin("glass", "brdf glass\nspecular 1 1 1\nior 1.5", far, mesh,
                                  0.005);
}
END_TEST

/* A point light inside the closed mesh ball at 1e6 (and at the origin), a ground square and the
 * ball's outside seen from above: nothing the camera sees has a line to the light, so every
 * pixel is exactly 0.  Catches a shadow ray that leaks through the mesh: a hole between
 * triangles (the float filter far from the origin), or an edge or vertex that neither of its
 * triangles takes. */
START_TEST(test_a_light_inside_a_closed_mesh_far_away_does_not_leak)
{
    const double at[2] = {0, 1e6};
    for (int k = 0; k < 2; k++) {
        double o = at[k];
        size_t cap = 1024 + BALL_MESH_CHARS;
        char *t = malloc(cap);
        ck_assert_ptr_nonnull(t);
        int n = snprintf(t, cap,
                         "size 48 48\nintegrator raytracer\nmaxdepth 1\n"
                         "camera %.17g %.17g %.17g  %.17g %.17g %.17g  0 1 0  60\n"
                         "ambient 0 0 0\ndiffuse 0.8 0.8 0.8\npoint %.17g %.17g %.17g 1e6 1e6 1e6\n"
                         "vertex %.17g %.17g %.17g\nvertex %.17g %.17g %.17g\n"
                         "vertex %.17g %.17g %.17g\nvertex %.17g %.17g %.17g\n"
                         "tri 0 1 2\ntri 0 2 3\n",
                         o + 0.3, o + 0.2, o + 6, o, o, o - 1.5, o, o, o, o - 9, o - 9, o - 1.5,
                         o + 9, o - 9, o - 1.5, o + 9, o + 9, o - 1.5, o - 9, o + 9, o - 1.5);
        ball_mesh(t, cap, n, o);
        scene sc;
        load(&sc, t);
        free(t);
        image im = {0};
        render_stats st;
        render(&sc, &im, &st);
        long lit = 0;
        for (int y = 0; y < im.h; y++)
            for (int x = 0; x < im.w; x++) lit += !rgb_is_black(image_get(&im, x, y));
        ck_assert_msg(lit == 0, "at %g: light leaks into %ld of %d pixels", o, lit, im.w * im.h);
        image_free(&im);
        scene_free(&sc);
    }
}
END_TEST

/* A glass ball seen from 1e8 away (the camera's fovy narrowed to frame it) renders like the same
 * ball seen from 1e6 away: every pixel within 1e-4 (measured 4e-6: the two perspectives).
 * Catches a sphere hit point taken as o + t d alone, whose error grows with t (1e-8 at 1e8,
 * beyond the offset): before sphere_hit moved it onto the sphere, pixels 0.41 apart. */
START_TEST(test_glass_ball_seen_from_1e8_away_has_no_acne)
{
    image im[2] = {{0}, {0}};
    for (int k = 0; k < 2; k++) {
        double dist = k ? 1e8 : 1e6;
        char text[512];
        snprintf(text, sizeof text,
                 "size 48 48\ncamera 0 %.17g 0.3  0 0 0.3  0 0 1  %.17g\nmaxdepth 6\n"
                 "ambient 0 0 0\nbrdf glass\nspecular 1 1 1\nior 1.5\nsphere 0 0 0 1\n",
                 -dist, 2 * atan(1.3 / dist) * 180 / PI);
        scene sc;
        load(&sc, text);
        set_sky(&sc);
        render_stats st;
        render(&sc, &im[k], &st);
        scene_free(&sc);
    }
    long differ = pixels_apart(&im[0], &im[1], 1e-4);
    ck_assert_msg(differ == 0, "%ld of %d pixels differ", differ, im[0].w * im[0].h);
    image_free(&im[0]);
    image_free(&im[1]);
}
END_TEST

/* ---- far lattices, corners and rims ------------------------------------------------------ */

/* Noise is periodic (256 on each axis): at x = 1e15 + f it is the noise at (1e15 mod 256) + f,
 * f on the 1/8 grid (the only fractions a double holds there), also near -1e15 and 2^49: the same
 * value to 1e-12, 0 on the lattice.  Catches a lattice index taken
 * through int (overflows past 2^31) or a fraction taken as x - (long)x in float. */
START_TEST(test_noise_at_1e15_is_the_noise_of_its_period)
{
    const double bases[] = {1e15 + 37, -1e15 - 101, 0x1p49 + 77}; /* (not multiples of 256) */
    for (int b = 0; b < 3; b++) {
        double x = bases[b], m = x - 256 * floor(x / 256); /* exact: x is a whole number */
        for (int k = 0; k < 8; k++) {
            double f = k / 8.0, got = perlin_noise(x + f, 0.375 - x, x + 0.625);
            double want = perlin_noise(m + f, 0.375 - x + 256 * ceil(x / 256), m + 0.625);
            ck_assert_msg(fabs(got - want) <= 1e-12 && (k || perlin_noise(x, -x, x) == 0),
                          "x = %.17g + %g: %.17g, its period's %.17g", x, f, got, want);
        }
    }
}
END_TEST

/* Directions exactly at the 8 cube corners and the 12 edge midpoints, and an ulp of a component
 * either side: a face whose axis holds the largest |component| (ties: x before y before z,
 * cubemap.h), (s, t) in [0, 1], and back through the face the same direction to 1e-15.
 * Catches a strict comparison that picks no face on a tie, and s or t a rounding outside the
 * face that reads past its edge. */
START_TEST(test_cube_corners_and_edges_pick_a_face_and_come_back)
{
    long n = 0;
    for (int i = 0; i < 27; i++) {
        vec3 d0 = vec3_make(i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1);
        int zeros = (d0.x == 0) + (d0.y == 0) + (d0.z == 0);
        if (zeros > 1) continue; /* corners (0 zeros) and edges (1) */
        for (int a = 0; a < 3; a++)
            for (int sgn = -1; sgn <= 1; sgn++) {
                vec3 d = d0;
                double *c = a == 0 ? &d.x : a == 1 ? &d.y : &d.z;
                if (sgn && *c != 0) *c = nextafter(*c, sgn * INFINITY);
                int face;
                uv2 st;
                ck_assert_int_eq(cubemap_dir_to_face(d, &face, &st), 0);
                double comp[3] = {d.x, d.y, d.z}, big = fmax(fabs(d.x), fmax(fabs(d.y), fabs(d.z)));
                int axis = face / 2, first = fabs(d.x) == big ? 0 : fabs(d.y) == big ? 1 : 2;
                ck_assert_msg(axis == first && (comp[axis] > 0) == (face % 2 == 0),
                              "(%g %g %g): face %d", d.x, d.y, d.z, face);
                ck_assert(st.u >= 0 && st.u <= 1 && st.v >= 0 && st.v <= 1);
                vec3 back = cubemap_face_to_dir(face, st);
                ck_assert_msg(vec3_length(vec3_sub(back, vec3_normalize(d))) < 1e-15,
                              "(%g %g %g): back %.17g %.17g %.17g", d.x, d.y, d.z, back.x, back.y,
                              back.z);
                n++;
            }
    }
    ck_assert_int_eq(n, 20 * 9);
}
END_TEST

/* A direction alpha from the probe's centre direction (+x) sits at radius sin(alpha / 2) on the
 * mirror ball (its normal halfway): for alpha up to pi - 1e-300 (the rim, all of it -x) the map
 * and its inverse hold that to 1e-15, -x itself lands on the rim, and no uv leaves the disc.
 * Catches rho from cos alpha (sqrt((1 - cos alpha) / 2) loses everything near the centre), a
 * normal that divides by |r + V| = 0 at -x, and a rim point pushed past rho = 1. */
START_TEST(test_mirror_ball_radius_is_sin_half_the_angle_up_to_the_rim)
{
    for (int e = 0; e <= 300; e++) {
        double gap = pow(10, -e), alpha = e == 0 ? 1.0 : M_PI - gap; /* (e = 0: one radian) */
        for (int k = 0; k < 4; k++) {
            double psi = k * 1.1;
            vec3 d = vec3_make(cos(alpha), sin(alpha) * cos(psi), sin(alpha) * sin(psi));
            uv2 uv;
            ck_assert_int_eq(mirrorball_dir_to_uv(d, &uv), 0);
            double a = 2 * uv.u - 1, b = 1 - 2 * uv.v, rho = sqrt(a * a + b * b);
            double want = sin(alpha / 2);
            ck_assert_msg(fabs(rho - want) <= 1e-15 && rho <= 1,
                          "alpha = pi - 1e-%d: rho %.17g, want %.17g", e, rho, want);
            vec3 back;
            ck_assert_int_eq(mirrorball_uv_to_dir(uv, &back), 0);
            ck_assert(vec3_is_finite(back) && fabs(vec3_length(back) - 1) < 1e-15);
        }
    }
    uv2 uv;
    ck_assert_int_eq(mirrorball_dir_to_uv(vec3_make(-1, 0, 0), &uv), 0);
    ck_assert_msg(fabs(hypot(2 * uv.u - 1, 1 - 2 * uv.v) - 1) < 1e-15, "-x at %g %g", uv.u, uv.v);
}
END_TEST

/* A 5 x 3 texture of distinct texels read at (s, t) + 1e9 (1e9 + f is exact for f on the 1/64
 * grid, and 1e9 is whole periods) with repeat, and at 2e9 + 2 - (s, t) with mirror (the copy
 * in an odd period is mirrored): nearest and bilinear give exactly the lookup at (s, t).
 * Catches a texel index through a 32-bit int of s w (2e9 x 5 overflows it) and a wrap by fmod
 * in float. */
START_TEST(test_texture_lookups_at_1e9_are_the_lookups_of_their_period)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 5, 3, &err), 0);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 5; i++) image_set(&im, i, j, rgb_make(i, j, i * 3 + j));
    for (int k = 0; k < 64; k++) {
        uv2 st = {k / 64.0, (63 - k) / 64.0};
        uv2 far = {st.u + 1e9, st.v + 1e9}, flip = {2e9 + 2 - st.u, 2e9 + 2 - st.v};
        const wrap_mode rep = WRAP_REPEAT, mir = WRAP_MIRROR;
        rgb n0 = texlookup_nearest(&im, st, rep), n1 = texlookup_nearest(&im, far, rep);
        rgb b0 = texlookup_bilinear(&im, st, rep), b1 = texlookup_bilinear(&im, far, rep);
        rgb m0 = texlookup_bilinear(&im, st, mir), m1 = texlookup_bilinear(&im, flip, mir);
        ck_assert_msg(n0.b == n1.b && b0.r == b1.r && b0.g == b1.g && m0.r == m1.r && m0.g == m1.g,
                      "(%g, %g): nearest %g %g, bilinear %g %g, mirrored %g %g", st.u, st.v, n0.b,
                      n1.b, b0.r, b1.r, m0.r, m1.r);
    }
    image_free(&im);
}
END_TEST

/* A sun one texel wide (1000 over black) of a 256 x 128 map - in the pole row, in the seam's
 * column, in the two rows either side of the horizon - lights a diffuse ground (albedo 0.5,
 * normal +z) through `integrator direct` and the cdf light, binary search and alias: the ground
 * reflects 0.5 / pi times the texel's exact integral of max(0, z): 1000 dphi (z0+^2 - z1+^2) / 2
 * over its rows' z0 > z1.  Within 1% (the samples' spread over the texel).  Catches a texel
 * sampled a row off (2.3% at row 30), a pdf from the wrong row or column at the pole or the
 * seam, and a horizon row counted whole (the half below the ground lights nothing). */
START_TEST(test_a_one_texel_sun_at_the_pole_seam_and_horizon_lights_the_ground)
{
    const int w = 256, h = 128, at[][2] = {{40, 0}, {w - 1, 30}, {7, h / 2 - 1}, {100, h / 2}};
    const char *samplers[] = {"binary", "alias"};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++) {
            char text[512];
            snprintf(text, sizeof text,
                     "size 16 16\nintegrator direct\nenvsampling cdf\nenvsampler %s\n"
                     "camera 0 0 5  0 0 0  0 1 0  20\nambient 0 0 0\ndiffuse 0.5 0.5 0.5\n"
                     "vertex -9 -9 0\nvertex 9 -9 0\nvertex 9 9 0\nvertex -9 9 0\n"
                     "tri 0 1 2\ntri 0 2 3\n",
                     samplers[k]);
            scene sc;
            load(&sc, text);
            error err = {0};
            image sun = {0};
            ck_assert_int_eq(image_alloc(&sun, w, h, &err), 0);
            image_set(&sun, at[i][0], at[i][1], rgb_gray(1000));
            set_map(&sc, &sun);
            long bad;
            double mean = render_mean(&sc, 16, &bad);
            double z0 = fmax(0, cos(PI * at[i][1] / h)), z1 = fmax(0, cos(PI * (at[i][1] + 1) / h));
            double want = 0.5 / PI * 1000 * (2 * PI / w) * (z0 * z0 - z1 * z1) / 2;
            /* (the row just below the horizon: cos(pi / 2) rounds to 6e-17, want to 7e-33) */
            ck_assert_msg(want < 1e-20 ? mean < 1e-20 : fabs(mean / want - 1) < 0.01,
                          "sun at texel (%d, %d), %s: the ground %.9g, want %.9g", at[i][0],
                          at[i][1], samplers[k], mean, want);
            scene_free(&sc);
        }
}
END_TEST

/* ---- glass ------------------------------------------------------------------------------- */

/* Fresnel in long double, from Snell's law: the independent answer (eta = n_t / n_i). */
static long double fresnel_reference(long double ci, long double eta)
{
    long double st2 = (1 - ci * ci) / (eta * eta);
    if (st2 >= 1) return 1;
    long double ct = sqrtl(1 - st2);
    long double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
    return (rs * rs + rp * rp) / 2;
}

/* Glass at ior 0.01, 1 / 1.5 (leaving glass), 1, 1.5 and 100, at 2001 angles from normal to
 * grazing and at the critical angle and one ulp either side: F within 1e-12 of the long double
 * Snell-Fresnel, refraction unit and obeying Snell's law where it exists, total internal
 * reflection (F = 1, no refracted ray) past the critical angle, F = 0 and the ray unbent at
 * ior 1, F = 1 at grazing.  Catches a cos_t taken as sqrt of a slightly negative number at the
 * critical angle (NaN), eta inverted, and F < 1 under total internal reflection. */
START_TEST(test_glass_from_ior_0_01_to_100_and_at_the_critical_angle)
{
    const double etas[] = {0.01, 1 / 1.5, 1, 1.5, 100};
    const vec3 n = vec3_make(0, 0, 1);
    for (int e = 0; e < 5; e++) {
        double eta = etas[e];
        double cosines[2004];
        int m = 0;
        for (int i = 0; i <= 2000; i++) cosines[m++] = i / 2000.0;
        if (eta < 1) { /* the critical angle: sin_i = eta, and one ulp either side */
            double cc = sqrt(1 - eta * eta);
            cosines[m++] = cc, cosines[m++] = nextafter(cc, 0), cosines[m++] = nextafter(cc, 1);
        }
        for (int i = 0; i < m; i++) {
            double ci = cosines[i], si = sqrt(fmax(0, 1 - ci * ci));
            double F = fresnel_dielectric(ci, eta);
            long double want = fresnel_reference(ci, eta);
            /* near the critical angle F falls as 2 cos_t (1 / eta + eta), and cos_t^2, a few
             * ulps of 1 apart from its rounding, moves cos_t by ~1e-16 / cos_t: F's
             * condition (2e-8 at eta = 0.01 one ulp inside the critical angle) */
            long double ct2 = 1 - (1 - (long double)ci * ci) / ((long double)eta * eta);
            double tol = 1e-12 + (ct2 > 0 ? 1e-15 * (1 / eta + eta) / sqrtl(ct2 + 1e-32L) : 0);
            ck_assert_msg(isfinite(F) && fabsl(F - want) <= tol,
                          "eta %g, cos_i %.17g: F %.17g, want %.17Lg", eta, ci, F, want);
            vec3 d = vec3_make(si, 0, -ci), t;
            int refracts = fresnel_refract(d, n, eta, &t);
            if (si > eta * (1 + 1e-12)) { /* past the critical angle */
                ck_assert_msg(!refracts && F == 1, "eta %g, cos_i %.17g: no TIR", eta, ci);
                continue;
            }
            if (!refracts) { /* only at the critical angle itself, within rounding */
                ck_assert_msg(si > eta * (1 - 1e-12) && F == 1, "eta %g, cos_i %.17g", eta, ci);
                continue;
            }
            ck_assert_msg(vec3_is_finite(t) && fabs(vec3_length(t) - 1) < 1e-14 && t.z <= 0,
                          "eta %g, cos_i %.17g: refracted (%g %g %g)", eta, ci, t.x, t.y, t.z);
            ck_assert_msg(fabs(t.x * eta - si) < 1e-12, "eta %g, cos_i %.17g: Snell", eta, ci);
            /* ior 1: nothing reflected, nothing bent, but for cos_t's rounding (~1e-16 /
             * cos_i near grazing; at grazing itself F = 1 at any ior) */
            double bend = 1e-15 / fmax(ci, 1e-300);
            if (eta == 1 && ci > 0)
                ck_assert_msg(F <= bend * bend / (ci * ci) && vec3_length(vec3_sub(t, d)) <= bend,
                              "ior 1, cos_i %.17g: F %g, bent by %g", ci, F,
                              vec3_length(vec3_sub(t, d)));
        }
        ck_assert(fresnel_dielectric(0, eta) == 1 || eta == 1); /* grazing */
    }
}
END_TEST

/* ---- furnaces ------------------------------------------------------------------------------ */

/* A diffuse sphere (albedo 0.5) under a constant sky of radiance V reflects 0.5 V everywhere:
 * `integrator direct`, 32 x 32 pixels all on the sphere, 16 samples each, under every
 * envsampling, for V from 1e-37 (near float's smallest normal) to 1e37 (near its largest).
 * Every pixel finite, the mean within 5% of 0.5 V (4 sigma for the unbiased samplers; measured
 * 0.997 uniform, 0.991 cdf and cdf-sintheta, 0.989 SIS at every V; median cut 0.976 .. 1.008,
 * its strata moving with V).  Catches a product of radiances rounded to
 * float: the map's power |L| (the pdf's divisor) taken through (float)(L^2 dOmega) / L left
 * every light sample weighing 0 from V = 1e20 on; a pdf of 0 or Inf; a NaN. */
START_TEST(test_furnaces_from_1e_37_to_1e37_under_every_envsampling)
{
    const char *modes[] = {"uniform", "cdf", "cdf-sintheta", "mediancut 64", "sis 64"};
    const double scales[] = {1e-37, 1e-20, 1, 1e20, 1e37};
    for (int m = 0; m < 5; m++)
        for (int k = 0; k < 5; k++) {
            char text[512];
            snprintf(text, sizeof text,
                     "size 32 32\nintegrator direct\nenvsampling %s\n"
                     "camera 0 -3 0  0 0 0  0 0 1  25\nambient 0 0 0\ndiffuse 0.5 0.5 0.5\n"
                     "sphere 0 0 0 1\n",
                     modes[m]);
            scene sc;
            load(&sc, text);
            genenv_params p = genenv_defaults();
            p.width = 32;
            p.value = scales[k];
            error err = {0};
            image sky = {0};
            ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &p, &sky, &err), 0);
            set_map(&sc, &sky);
            long bad;
            double mean = render_mean(&sc, 16, &bad) / (0.5 * scales[k]);
            ck_assert_msg(bad == 0 && fabs(mean - 1) < 0.05,
                          "envsampling %s, V = %g: mean %g of 0.5 V, %ld pixels not finite",
                          modes[m], scales[k], mean, bad);
            scene_free(&sc);
        }
}
END_TEST

/* ---- camera inside a sphere ---------------------------------------------------------------- */

/* Every primary ray starts inside the sphere and hits its inside: every pixel is the ambient
 * colour, none is the background and none is NaN (catches a sphere test that only takes the
 * near root, or a normal flip that divides by zero). */
START_TEST(test_camera_inside_a_sphere_sees_its_inside_everywhere)
{
    scene sc;
    load(
        &sc,
        "size 24 16\ncamera 0.1 0.2 0.3  1 0 0  0 0 1  120\nambient 0.3 0.6 0.9\nsphere 0 0 0 2\n");
    image img = {0};
    render_stats st;
    render(&sc, &img, &st);
    long wrong = 0;
    for (int y = 0; y < img.h; y++)
        for (int x = 0; x < img.w; x++) {
            rgb c = image_get(&img, x, y);
            if (fabs(c.r - 0.3) > 1e-6 || fabs(c.g - 0.6) > 1e-6 || fabs(c.b - 0.9) > 1e-6)
                wrong++; /* float pixels */
        }
    ck_assert_int_eq(wrong, 0);
    ck_assert_int_eq(st.nonfinite_pixels, 0);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

/* ---- NaN and Inf are reported ------------------------------------------------------------ */

/* tonemap_image counts each pixel with a NaN or Inf channel once, encodes NaN as 0 and +Inf as
 * full white (documented in tonemap.c), and leaves the finite pixels around them untouched. */
START_TEST(test_tonemap_reports_nan_and_inf_pixels_and_encodes_them_fixed)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 1, &err), 0);
    image_set(&im, 0, 0, rgb_make(0.5, 0.5, 0.5));
    image_set(&im, 1, 0, rgb_make(NAN, 0.5, 0.5));
    image_set(&im, 2, 0, rgb_make(INFINITY, -INFINITY, 0.5));
    image_set(&im, 3, 0, rgb_make(0.5, 0.5, 0.5));
    tonemap_params tm = tonemap_defaults();
    uint8_t out[12];
    memset(out, 0xAB, sizeof out);
    ck_assert_int_eq(tonemap_image(&tm, &im, out), 2);
    ck_assert_int_eq(out[3], 0);   /* NaN -> 0 */
    ck_assert_int_eq(out[6], 255); /* +Inf -> 1 */
    ck_assert_int_eq(out[7], 0);   /* -Inf -> 0 */
    ck_assert_int_eq(out[0], out[9]);
    ck_assert_int_eq(out[4], out[0]); /* the finite channel of a NaN pixel is encoded normally */
    image_free(&im);
}
END_TEST

/* A mirror sphere reflecting an envmap with NaN texels makes NaN pixels; the renderer's count
 * equals the number actually in the image (catches a count that is never incremented, which
 * would let NaN reach files unreported). */
START_TEST(test_render_counts_the_nan_pixels_it_makes)
{
    scene sc;
    load(&sc, "size 32 32\ncamera 0 -4 0  0 0 0  0 0 1  40\nbrdf mirror\nspecular 1 1 1\n"
              "ambient 0 0 0\nsphere 0 0 0 1\n");
    set_sky(&sc);
    image *m = &sc.envmap.img;
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x += 4) image_px(m, x, y)[1] = NAN;
    image img = {0};
    render_stats st;
    render(&sc, &img, &st);
    long n = count_nonfinite(&img);
    ck_assert_int_gt(n, 0);
    ck_assert_int_eq(st.nonfinite_pixels, n);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

/* Radiance that a double holds but a float cannot (emission 1e39 > FLT_MAX) is Inf in the
 * stored image, and the count says so; likewise the variance image's own count.  Catches a
 * count taken on the double before the store (it reported 0 while files held Inf). */
START_TEST(test_render_counts_pixels_that_overflow_the_float_image)
{
    scene sc;
    load(&sc, "size 16 16\ncamera 0 0 4 0 0 0 0 1 0 45\nambient 0 0 0\n"
              "emission 1e39 1e39 1e39\nsphere 0 0 0 1\n");
    image img = {0};
    render_stats st;
    render(&sc, &img, &st);
    long n = count_nonfinite(&img);
    ck_assert_int_gt(n, 0);
    ck_assert_int_eq(st.nonfinite_pixels, n);
    ck_assert_int_eq(st.nonfinite_variance, 0); /* no variance image asked for */
    image_free(&img);
    scene_free(&sc);
    /* a finite image whose variance overflows: 4 samples of a pixel on the sphere's edge, each
     * 0 or 1e20: s^2 / 4 ~ 1e39 > FLT_MAX */
    load(&sc, "size 16 16\ncamera 0 0 4 0 0 0 0 1 0 45\nambient 0 0 0\n"
              "emission 1e20 1e20 1e20\nsphere 0 0 0 1\n");
    render_opts o = render_defaults();
    o.spp = 4;
    image var = {0};
    o.variance = &var;
    error err = {0};
    if (render_scene(&sc, &o, &img, &st, &err)) ck_abort_msg("render: %s", err.msg);
    ck_assert_int_eq(st.nonfinite_pixels, count_nonfinite(&img));
    long nv = count_nonfinite(&var);
    ck_assert_int_gt(nv, 0);
    ck_assert_int_eq(st.nonfinite_variance, nv);
    image_free(&img);
    image_free(&var);
    scene_free(&sc);
}
END_TEST

Suite *hardcases_suite(void)
{
    Suite *s = suite_create("hardcases");
    TCase *env = tcase_create("envmaps");
    tcase_add_test(env, test_bad_texels_stay_local_and_are_returned_as_they_are);
    tcase_add_test(env, test_one_by_one_map_is_constant_everywhere);
    tcase_add_test(env, test_8192_map_poles_and_seam_are_exact);
    suite_add_tcase(s, env);
    TCase *geo = tcase_create("geometry");
    tcase_add_test(geo, test_rays_across_shared_edges_and_vertices_hit_exactly_one_triangle);
    tcase_add_test(geo, test_rays_through_a_grid_hit_exactly_one_triangle);
    tcase_add_test(geo, test_rendered_quad_diagonal_has_no_crack);
    tcase_add_test(geo, test_a_mesh_far_from_the_origin_has_no_holes);
    tcase_add_test(geo, test_grazing_rays_and_degenerate_triangles_give_no_garbage);
    tcase_add_test(geo, test_mirror_far_from_origin_has_no_acne);
    tcase_add_test(geo, test_glass_far_from_origin_has_no_acne);
    tcase_add_test(geo, test_glass_ball_seen_from_1e8_away_has_no_acne);
    tcase_add_test(geo, test_a_light_inside_a_closed_mesh_far_away_does_not_leak);
    tcase_add_test(geo, test_camera_inside_a_sphere_sees_its_inside_everywhere);
    tcase_add_test(geo, test_furnaces_from_1e_37_to_1e37_under_every_envsampling);
    tcase_add_test(geo, test_glass_from_ior_0_01_to_100_and_at_the_critical_angle);
    tcase_add_test(geo, test_noise_at_1e15_is_the_noise_of_its_period);
    tcase_add_test(geo, test_cube_corners_and_edges_pick_a_face_and_come_back);
    tcase_add_test(geo, test_mirror_ball_radius_is_sin_half_the_angle_up_to_the_rim);
    tcase_add_test(geo, test_texture_lookups_at_1e9_are_the_lookups_of_their_period);
    tcase_add_test(geo, test_a_one_texel_sun_at_the_pole_seam_and_horizon_lights_the_ground);
    suite_add_tcase(s, geo);
    TCase *tex = tcase_create("textures and noise");
    tcase_add_test(tex, test_tiny_textures_read_far_outside_stay_inside_their_texels);
    tcase_add_test(tex, test_zero_and_whole_texture_footprints_give_bilinear_and_mean);
    tcase_add_test(tex, test_grazing_footprints_keep_a_ramp_and_stay_finite);
    tcase_add_test(tex, test_noise_far_away_and_negative_is_bounded_and_zero_on_the_lattice);
    suite_add_tcase(s, tex);
    TCase *rep = tcase_create("reporting");
    tcase_add_test(rep, test_tonemap_reports_nan_and_inf_pixels_and_encodes_them_fixed);
    tcase_add_test(rep, test_render_counts_the_nan_pixels_it_makes);
    tcase_add_test(rep, test_render_counts_pixels_that_overflow_the_float_image);
    suite_add_tcase(s, rep);
    return s;
}

UNIT_MAIN(hardcases_suite)

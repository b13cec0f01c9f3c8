/* test_bvh_packet.c - bvh_intersect_packet finds, ray by ray and bit for bit, what bvh_intersect
 * finds: for packets of camera rays (one origin, directions in a narrow cone) over random scenes
 * of spheres, ellipsoids, triangles and quads; for rays grazing the boxes' edges from afar; and
 * for packets it must trace one ray at a time (mixed origins, signs, tmax, a zero component). */
#include "envtex/geometry/bvh_packet.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/core/rng.h"
#include "envtex/scene/scene.h"
#include "unit.h"

static double sym(rng *g) { return 2 * rng_uniform(g) - 1; }

static vec3 random_unit(rng *g)
{
    double z = sym(g), phi = 2 * M_PI * rng_uniform(g);
    double s = sqrt(fmax(0.0, 1 - z * z));
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

/* What a packet is checked against: n primitives in [-10, 10]^3 (40% spheres, every fourth an
 * ellipsoid; triangles, every fifth flat in z) and n_quads quads, built into *b. */
typedef struct world {
    scene sc;
    bvh_quad *quads;
    bvh b;
} world;

static void world_make(world *w, long n, long n_quads, uint64_t seed)
{
    rng g;
    rng_seed(&g, seed, 0);
    scene *sc = &w->sc;
    memset(sc, 0, sizeof *sc);
    sc->n_spheres = n * 2 / 5;
    sc->n_triangles = n - sc->n_spheres;
    sc->spheres = calloc((size_t)sc->n_spheres + 1, sizeof *sc->spheres);
    sc->triangles = calloc((size_t)sc->n_triangles + 1, sizeof *sc->triangles);
    w->quads = calloc((size_t)n_quads + 1, sizeof *w->quads);
    ck_assert(sc->spheres && sc->triangles && w->quads);
    for (long i = 0; i < sc->n_spheres; i++) {
        sphere *s = &sc->spheres[i];
        vec3 c = vec3_make(10 * sym(&g), 10 * sym(&g), 10 * sym(&g));
        s->center = c;
        s->radius = 0.1 + 0.9 * rng_uniform(&g);
        s->xf = mat4_identity();
        if (i % 4 == 3) { /* an ellipsoid: the unit-centred sphere moved, turned and stretched */
            s->center = vec3_make(0, 0, 0);
            s->xf = mat4_mul(mat4_translate(c),
                             mat4_mul(mat4_rotate(random_unit(&g), 360 * rng_uniform(&g)),
                                      mat4_scale(vec3_make(2, 0.5, 1))));
        }
        ck_assert_int_eq(mat4_inverse(s->xf, &s->inv), 0);
        s->material = (int)(i % 3);
    }
    for (long i = 0; i < sc->n_triangles; i++) {
        triangle *t = &sc->triangles[i];
        vec3 c = vec3_make(10 * sym(&g), 10 * sym(&g), 10 * sym(&g));
        double size = 0.2 + 2 * rng_uniform(&g);
        for (int k = 0; k < 3; k++) {
            t->p[k] = vec3_madd(c, random_unit(&g), size);
            if (i % 5 == 4) t->p[k].z = c.z;
        }
        t->material = (int)(i % 3);
    }
    for (long k = 0; k < n_quads; k++)
        w->quads[k] = (bvh_quad){vec3_make(10 * sym(&g), 10 * sym(&g), 10 * sym(&g)),
                                 vec3_scale(random_unit(&g), 2), vec3_scale(random_unit(&g), 1.5)};
    bvh_prims p = scene_prims(sc);
    p.quads = w->quads;
    p.n_quads = n_quads;
    error err = {0};
    ck_assert_int_eq(bvh_build(&w->b, p, NULL, &err), 0);
}

static void world_free(world *w)
{
    bvh_free(&w->b);
    free(w->quads);
    scene_free(&w->sc);
}

/* Ray i of r[0..n) found by the packet as bvh_intersect finds it alone, bit for bit; returns
 * how many of them hit. */
static int check_packet(const bvh *b, const ray *r, int n, const char *what)
{
    int got[BVH_PACKET], hits = 0;
    hit h[BVH_PACKET];
    bvh_intersect_packet(b, r, n, got, h);
    for (int i = 0; i < n; i++) {
        hit one;
        int want = bvh_intersect(b, &r[i], &one);
        if (got[i] != want) ck_abort_msg("%s, ray %d: packet %d, alone %d", what, i, got[i], want);
        if (!want) continue;
        hits++;
        int same = h[i].t == one.t && h[i].prim == one.prim;
        if (want == BVH_SURFACE)
            same = same && h[i].is_sphere == one.is_sphere && h[i].material == one.material &&
                   !memcmp(&h[i].p, &one.p, sizeof one.p) &&
                   !memcmp(&h[i].ng, &one.ng, sizeof one.ng) &&
                   !memcmp(&h[i].ns, &one.ns, sizeof one.ns) &&
                   !memcmp(&h[i].bary, &one.bary, sizeof one.bary);
        if (!same)
            ck_abort_msg("%s, ray %d: packet t %.17g prim %ld, alone t %.17g prim %ld", what, i,
                         h[i].t, h[i].prim, one.t, one.prim);
    }
    return hits;
}

/* BVH_PACKET camera rays from eye: a square block of pixels (jittered) around direction fwd,
 * pixels `pixel` radians apart. */
static void camera_packet(rng *g, vec3 eye, vec3 fwd, double pixel, ray *r)
{
    vec3 u = vec3_normalize(
        vec3_cross(fwd, fabs(fwd.z) < 0.9 ? vec3_make(0, 0, 1) : vec3_make(1, 0, 0)));
    vec3 v = vec3_cross(u, fwd);
    for (int i = 0; i < BVH_PACKET; i++) {
        int side = (int)sqrt(BVH_PACKET);
        double x = (i % side - (side - 1) / 2.0 + sym(g) / 2) * pixel;
        double y = (i / side - (side - 1) / 2.0 + sym(g) / 2) * pixel;
        vec3 d = vec3_add(fwd, vec3_add(vec3_scale(u, x), vec3_scale(v, y)));
        r[i] = (ray){eye, vec3_normalize(d), 0.0, INFINITY};
    }
}

START_TEST(test_bvh_packet_finds_what_bvh_intersect_finds_for_camera_rays)
{
    world w;
    world_make(&w, 3000, 40, 168);
    rng g;
    rng_seed(&g, 1, 0);
    int hits = 0, rays = 0;
    for (int k = 0; k < 3000; k++) {
        /* eyes inside and outside the scene, looking at a random point of it; pixels from
         * 1/1000 to 1/10 radian (a wide view or a zoom, and rays that cross many leaves) */
        vec3 eye = vec3_scale(random_unit(&g), k % 3 ? 25 : 8 * rng_uniform(&g));
        vec3 at = vec3_make(8 * sym(&g), 8 * sym(&g), 8 * sym(&g));
        ray r[BVH_PACKET];
        camera_packet(&g, eye, vec3_normalize(vec3_sub(at, eye)), 1e-3 * pow(100, rng_uniform(&g)),
                      r);
        if (k % 7 == 0) /* a finite segment, as a shadow ray's */
            for (int i = 0; i < BVH_PACKET; i++) r[i].tmin = 2, r[i].tmax = 20;
        hits += check_packet(&w.b, r, BVH_PACKET, "camera packet");
        rays += BVH_PACKET;
    }
    ck_assert_int_gt(hits, rays / 4); /* the rays met the scene, not only the sky */
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_keeps_hits_along_box_edges_seen_from_far_away)
{
    /* test_bvh's right triangles with legs along the axes, seen from ~500 units: a packet of
     * rays from one eye aimed at points just inside the legs of one triangle (every other packet
     * one ray again and again: the interval test of the packet is then the ray's own) */
    const int n = 200;
    world w;
    memset(&w, 0, sizeof w);
    w.sc.n_triangles = n;
    w.sc.triangles = calloc(n, sizeof *w.sc.triangles);
    w.sc.spheres = calloc(1, sizeof *w.sc.spheres);
    ck_assert(w.sc.triangles && w.sc.spheres);
    rng g;
    rng_seed(&g, 50, 0);
    for (int i = 0; i < n; i++) {
        vec3 c = vec3_make(4 * sym(&g), 4 * sym(&g), 4 * sym(&g));
        double s = 0.5 + rng_uniform(&g);
        w.sc.triangles[i] =
            (triangle){.p = {c, vec3_add(c, vec3_make(s, 0, 0)), vec3_add(c, vec3_make(0, s, 0))}};
    }
    error err = {0};
    ck_assert_int_eq(bvh_build(&w.b, scene_prims(&w.sc), NULL, &err), 0);
    int hits = 0;
    for (int k = 0; k < 20000; k++) {
        const triangle *t = &w.sc.triangles[(int)(rng_uniform(&g) * n)];
        vec3 dir = random_unit(&g);
        if (dir.z < 0.3) dir = vec3_normalize(vec3_make(dir.x, dir.y, 1));
        vec3 eye = vec3_madd(t->p[0], dir, 500 + rng_uniform(&g));
        ray r[BVH_PACKET];
        for (int i = 0; i < BVH_PACKET; i++) {
            if (k % 2 && i > 0) {
                r[i] = r[0];
                continue;
            }
            double u = rng_uniform(&g), v = 1e-6 * rng_uniform(&g); /* just inside a leg */
            if (i % 2) u = v, v = rng_uniform(&g);
            vec3 target = vec3_add(vec3_add(vec3_scale(t->p[0], 1 - u - v), vec3_scale(t->p[1], u)),
                                   vec3_scale(t->p[2], v));
            r[i] = (ray){eye, vec3_sub(target, eye), 0.0, INFINITY};
        }
        hits += check_packet(&w.b, r, BVH_PACKET, "edge packet");
    }
    ck_assert_int_gt(hits, 20000 * BVH_PACKET / 2);
    world_free(&w);
}
END_TEST

/* Triangles built into w->b (no spheres, no quads); w->sc owns them. */
static void world_of_triangles(world *w, triangle *t, long n)
{
    memset(w, 0, sizeof *w);
    w->sc.n_triangles = n;
    w->sc.triangles = t;
    w->sc.spheres = calloc(1, sizeof *w->sc.spheres);
    ck_assert(w->sc.spheres);
    error err = {0};
    ck_assert_int_eq(bvh_build(&w->b, scene_prims(&w->sc), NULL, &err), 0);
}

START_TEST(test_bvh_packet_finds_the_nearer_of_nearly_coincident_triangles)
{
    /* pairs of the same triangle 1e-7 apart along z, seen from above: the float t of the
     * nearer one rounds to the farther one's, which an earlier hit made tmax; the filter's
     * margin on t (BVH_FILTER_EPS) keeps it for the double test, which tells them apart */
    const int pairs = 100;
    triangle *t = calloc(2 * pairs, sizeof *t);
    ck_assert(t);
    rng g;
    rng_seed(&g, 60, 0);
    for (int i = 0; i < pairs; i++) {
        vec3 c = vec3_make(6 * sym(&g), 6 * sym(&g), 2 * sym(&g));
        for (int k = 0; k < 3; k++) t[2 * i].p[k] = vec3_madd(c, random_unit(&g), 1.5);
        for (int k = 0; k < 3; k++) t[2 * i].p[k].z = c.z + 0.2 * sym(&g);
        t[2 * i + 1] = t[2 * i];
        for (int k = 0; k < 3; k++) t[2 * i + 1].p[k].z += 1e-7;
    }
    world w;
    world_of_triangles(&w, t, 2 * pairs);
    int hits = 0;
    for (int k = 0; k < 2000; k++) {
        vec3 eye = vec3_make(3 * sym(&g), 3 * sym(&g), 20 + 10 * rng_uniform(&g));
        vec3 at = vec3_make(6 * sym(&g), 6 * sym(&g), 0);
        ray r[BVH_PACKET];
        camera_packet(&g, eye, vec3_normalize(vec3_sub(at, eye)), 0.01, r);
        hits += check_packet(&w.b, r, BVH_PACKET, "coincident packet");
    }
    ck_assert_int_gt(hits, 2000 * BVH_PACKET / 4);
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_of_grazing_rays_leaves_them_to_the_double_test)
{
    /* large triangles in a tilted plane, rays from just off it at slopes 1e-9 to 1e-5: their
     * float barycentrics are noise, so the filter must let the double test decide */
    const int n = 64;
    triangle *t = calloc(n, sizeof *t);
    ck_assert(t);
    rng g;
    rng_seed(&g, 61, 0);
    mat4 tilt = mat4_rotate(vec3_normalize(vec3_make(1, 2, 3)), 37);
    vec3 normal = mat4_dir(&tilt, vec3_make(0, 0, 1));
    for (int i = 0; i < n; i++) {
        double x = -20 + 5 * (i % 8), y = -20 + 5 * (i / 8);
        vec3 p[3] = {{x, y, 0}, {x + 5, y, 0}, {x + sym(&g), y + 5, 0}};
        for (int k = 0; k < 3; k++) t[i].p[k] = mat4_point(&tilt, p[k]);
    }
    world w;
    world_of_triangles(&w, t, n);
    int hits = 0;
    for (int k = 0; k < 2000; k++) {
        double slope = 1e-9 * pow(1e4, rng_uniform(&g)), dist = 5 + 10 * rng_uniform(&g);
        double phi = 2 * M_PI * rng_uniform(&g);
        vec3 along = mat4_dir(&tilt, vec3_make(cos(phi), sin(phi), 0));
        vec3 at = mat4_point(&tilt, vec3_make(8 * sym(&g), 8 * sym(&g), 0));
        vec3 eye = vec3_madd(vec3_madd(at, along, -dist), normal, slope * dist);
        ray r[BVH_PACKET];
        camera_packet(&g, eye, vec3_normalize(vec3_sub(at, eye)), 1e-3 * slope, r);
        hits += check_packet(&w.b, r, BVH_PACKET, "grazing packet");
    }
    ck_assert_int_gt(hits, 2000 * BVH_PACKET / 4);
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_of_a_small_scene_far_from_the_origin_of_coordinates)
{
    /* millimetre triangles around (1000, -2000, 500) seen from a few centimetres: the eye's
     * coordinates are not floats, and their rounding is a sizeable part of a triangle, which
     * the filter's o_lo (the rest of o after rounding) takes back */
    const int n = 300;
    triangle *t = calloc(n, sizeof *t);
    ck_assert(t);
    rng g;
    rng_seed(&g, 62, 0);
    vec3 far = vec3_make(1000.0001234, -2000.0004321, 500.0002468);
    for (int i = 0; i < n; i++) {
        vec3 c = vec3_madd(far, vec3_make(sym(&g), sym(&g), sym(&g)), 0.01);
        for (int k = 0; k < 3; k++) t[i].p[k] = vec3_madd(c, random_unit(&g), 1e-3);
    }
    world w;
    world_of_triangles(&w, t, n);
    int hits = 0;
    for (int k = 0; k < 2000; k++) {
        const triangle *tk = &t[(int)(rng_uniform(&g) * n)];
        vec3 c = vec3_scale(vec3_add(vec3_add(tk->p[0], tk->p[1]), tk->p[2]), 1.0 / 3);
        vec3 eye = vec3_madd(c, random_unit(&g), 0.02 + 0.03 * rng_uniform(&g));
        ray r[BVH_PACKET];
        camera_packet(&g, eye, vec3_normalize(vec3_sub(c, eye)), 0.004, r);
        hits += check_packet(&w.b, r, BVH_PACKET, "far packet");
    }
    ck_assert_int_gt(hits, 2000 * BVH_PACKET / 4);
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_breaks_ties_in_the_order_bvh_intersect_does)
{
    /* 20 copies of one sphere (their centres coincide: the build halves them by count into
     * leaves of their own) and 20 copies of one triangle: every ray that meets them meets all
     * at one t, and the first in traversal order, near child first, is the hit */
    world w;
    memset(&w, 0, sizeof w);
    w.sc.n_spheres = w.sc.n_triangles = 20;
    w.sc.spheres = calloc(20, sizeof *w.sc.spheres);
    w.sc.triangles = calloc(20, sizeof *w.sc.triangles);
    ck_assert(w.sc.spheres && w.sc.triangles);
    for (int i = 0; i < 20; i++) {
        w.sc.spheres[i] = (sphere){.center = {1, 0, 0}, .radius = 1, .material = i % 3};
        w.sc.spheres[i].xf = w.sc.spheres[i].inv = mat4_identity();
        w.sc.triangles[i] = (triangle){.p = {{-3, -1, -1}, {-3, 1, -1}, {-3, 0, 1}}};
    }
    error err = {0};
    ck_assert_int_eq(bvh_build(&w.b, scene_prims(&w.sc), NULL, &err), 0);
    rng g;
    rng_seed(&g, 63, 0);
    int hits = 0;
    for (int k = 0; k < 500; k++) {
        vec3 eye = vec3_scale(random_unit(&g), 12), at = vec3_make(k % 2 ? 1 : -3, 0, 0);
        ray r[BVH_PACKET];
        camera_packet(&g, eye, vec3_normalize(vec3_sub(at, eye)), 0.01, r);
        hits += check_packet(&w.b, r, BVH_PACKET, "tie packet");
    }
    ck_assert_int_gt(hits, 500 * BVH_PACKET / 4);
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_of_a_direction_beyond_float_range_goes_one_by_one)
{
    /* huge spheres near the top of float's range: a direction component of 1e39 is Inf in
     * float, its 1 / d is 0, and 0 x Inf (a plane beyond FLT_MAX from the origin) is NaN in the
     * packet's interval test: such a packet must go one ray at a time */
    world w;
    memset(&w, 0, sizeof w);
    w.sc.n_spheres = 10;
    w.sc.spheres = calloc(10, sizeof *w.sc.spheres);
    w.sc.triangles = calloc(1, sizeof *w.sc.triangles);
    ck_assert(w.sc.spheres && w.sc.triangles);
    for (int i = 0; i < 10; i++) {
        w.sc.spheres[i] = (sphere){.center = {3e38, 0, (i - 5) * 3e37}, .radius = 1e37};
        w.sc.spheres[i].xf = w.sc.spheres[i].inv = mat4_identity();
    }
    error err = {0};
    ck_assert_int_eq(bvh_build(&w.b, scene_prims(&w.sc), NULL, &err), 0);
    ray r[BVH_PACKET];
    for (int i = 0; i < BVH_PACKET; i++)
        r[i] = (ray){{-2e38, 1, 1}, {i ? 1 : 1e39, 1e-3 * (1 + i), 1e-3}, 0.0, 1e30};
    ck_assert_int_ge(check_packet(&w.b, r, BVH_PACKET, "huge packet"), 1); /* ray 0, at t 0.5 */
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_of_fewer_rays_than_a_packet)
{
    world w;
    world_make(&w, 500, 10, 8);
    rng g;
    rng_seed(&g, 4, 0);
    for (int n = 0; n <= BVH_PACKET; n++) {
        ray r[BVH_PACKET];
        vec3 eye = vec3_scale(random_unit(&g), 20);
        camera_packet(&g, eye, vec3_normalize(vec3_neg(eye)), 0.01, r);
        check_packet(&w.b, r, n, "short packet"); /* (n = 0: nothing, and nothing read) */
    }
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_traces_rays_that_cannot_go_together_one_by_one)
{
    world w;
    world_make(&w, 500, 10, 7);
    rng g;
    rng_seed(&g, 2, 0);
    for (int k = 0; k < 2000; k++) {
        ray r[BVH_PACKET];
        vec3 eye = vec3_scale(random_unit(&g), 20);
        camera_packet(&g, eye, vec3_normalize(vec3_neg(eye)), 0.02, r);
        int i = (int)(rng_uniform(&g) * BVH_PACKET);
        switch (k % 5) {
        case 0: r[i].o = vec3_add(r[i].o, vec3_make(0, 0.5, 0)); break; /* another origin */
        case 1: r[i].tmax = 15; break;                                  /* another tmax */
        case 2: r[i].tmin = 15; break;                                  /* another tmin */
        case 3: r[i].d = vec3_neg(r[i].d); break;                       /* other signs */
        default: r[i].d.y = k % 10 == 4 ? 0.0 : -0.0; break;            /* a zero component */
        }
        check_packet(&w.b, r, BVH_PACKET, "mixed packet");
    }
    world_free(&w);
}
END_TEST

START_TEST(test_bvh_packet_of_a_scene_without_a_tree_or_empty)
{
    world w;
    world_make(&w, 5, 1, 3); /* at most BVH_MIN_PRIMS: one leaf */
    ck_assert_int_eq(w.b.is_tree, 0);
    rng g;
    rng_seed(&g, 3, 0);
    for (int k = 0; k < 300; k++) {
        ray r[BVH_PACKET];
        vec3 eye = vec3_scale(random_unit(&g), 20);
        camera_packet(&g, eye, vec3_normalize(vec3_neg(eye)), 0.05, r);
        check_packet(&w.b, r, BVH_PACKET, "one-leaf packet");
    }
    world_free(&w);
    world_make(&w, 0, 0, 4);
    ray r[BVH_PACKET];
    camera_packet(&g, vec3_make(0, 0, 5), vec3_make(0, 0, -1), 0.1, r);
    int got[BVH_PACKET];
    hit h[BVH_PACKET];
    bvh_intersect_packet(&w.b, r, BVH_PACKET, got, h);
    for (int i = 0; i < BVH_PACKET; i++) ck_assert_int_eq(got[i], BVH_MISS);
    world_free(&w);
}
END_TEST

Suite *bvh_packet_suite(void)
{
    Suite *s = suite_create("bvh_packet");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_bvh_packet_finds_what_bvh_intersect_finds_for_camera_rays);
    tcase_add_test(tc, test_bvh_packet_keeps_hits_along_box_edges_seen_from_far_away);
    tcase_add_test(tc, test_bvh_packet_finds_the_nearer_of_nearly_coincident_triangles);
    tcase_add_test(tc, test_bvh_packet_of_grazing_rays_leaves_them_to_the_double_test);
    tcase_add_test(tc, test_bvh_packet_of_a_small_scene_far_from_the_origin_of_coordinates);
    tcase_add_test(tc, test_bvh_packet_breaks_ties_in_the_order_bvh_intersect_does);
    tcase_add_test(tc, test_bvh_packet_of_a_direction_beyond_float_range_goes_one_by_one);
    tcase_add_test(tc, test_bvh_packet_of_fewer_rays_than_a_packet);
    tcase_add_test(tc, test_bvh_packet_traces_rays_that_cannot_go_together_one_by_one);
    tcase_add_test(tc, test_bvh_packet_of_a_scene_without_a_tree_or_empty);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(bvh_packet_suite)

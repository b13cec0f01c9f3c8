/* test_bvh.c - the BVH returns exactly what a brute-force loop over every primitive returns
 * (closest t, which primitive, occlusion), for random scenes of spheres, ellipsoids and
 * triangles, with and without a tree, and for distributions that push the builder to its
 * depth limit. */
#include "envtex/scene/scene.h"
#include "envtex/geometry/bvh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/rng.h"
#include "envtex/geometry/sphere.h"
#include "envtex/geometry/triangle.h"
#include "unit.h"

/* Checks for long loops: every passing ck_assert costs a system call (Check records the last
 * passing line), which would dominate the run time; these report failures only. */
#define EXPECT(c)                                                                                  \
    do {                                                                                           \
        if (!(c)) ck_abort_msg("failed: %s", #c);                                                  \
    } while (0)
#define EXPECT_MSG(c, ...)                                                                         \
    do {                                                                                           \
        if (!(c)) ck_abort_msg(__VA_ARGS__);                                                       \
    } while (0)
#define EXPECT_INT_EQ(a, b)                                                                        \
    do {                                                                                           \
        long long a_ = (a), b_ = (b);                                                              \
        if (a_ != b_) ck_abort_msg("%s == %lld, %s == %lld", #a, a_, #b, b_);                      \
    } while (0)
#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

static double sym(rng *g) { return 2 * rng_uniform(g) - 1; }

static vec3 random_unit(rng *g)
{
    double z = sym(g), phi = 2 * M_PI * rng_uniform(g);
    double s = sqrt(fmax(0.0, 1 - z * z));
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

/* An empty scene with room for ns spheres and nt triangles and two materials; free with
 * scene_free. */
static void scene_alloc(scene *sc, long ns, long nt)
{
    memset(sc, 0, sizeof *sc);
    sc->n_materials = 2;
    sc->materials = calloc(2, sizeof *sc->materials);
    sc->spheres = calloc((size_t)(ns > 0 ? ns : 1), sizeof *sc->spheres);
    sc->triangles = calloc((size_t)(nt > 0 ? nt : 1), sizeof *sc->triangles);
    EXPECT(sc->materials && sc->spheres && sc->triangles);
    sc->materials[0] = sc->materials[1] = scene_default_material();
    sc->n_spheres = ns;
    sc->n_triangles = nt;
}

static void set_sphere(sphere *s, vec3 c, double r, mat4 xf, int material)
{
    s->center = c;
    s->radius = r;
    s->xf = xf;
    EXPECT_INT_EQ(mat4_inverse(xf, &s->inv), 0);
    s->material = material;
}

/* n primitives in [-10, 10]^3: 40% spheres (a quarter of them rotated ellipsoids), the rest
 * triangles of random size and orientation, a fifth of them flat in z (a box of zero height). */
static void random_scene(scene *sc, long n, uint64_t seed)
{
    rng g;
    rng_seed(&g, seed, 0);
    long ns = n * 2 / 5, nt = n - ns;
    scene_alloc(sc, ns, nt);
    for (long i = 0; i < ns; i++) {
        vec3 c = vec3_make(10 * sym(&g), 10 * sym(&g), 10 * sym(&g));
        double r = 0.1 + 0.9 * rng_uniform(&g);
        mat4 xf = mat4_identity();
        if (i % 4 == 3)
            xf = mat4_mul(mat4_translate(c),
                          mat4_mul(mat4_rotate(random_unit(&g), 360 * rng_uniform(&g)),
                                   mat4_scale(vec3_make(2, 0.5, 1))));
        set_sphere(&sc->spheres[i], i % 4 == 3 ? vec3_make(0, 0, 0) : c, r, xf, (int)(i & 1));
    }
    for (long i = 0; i < nt; i++) {
        triangle *t = &sc->triangles[i];
        vec3 c = vec3_make(10 * sym(&g), 10 * sym(&g), 10 * sym(&g));
        double size = 0.2 + 2 * rng_uniform(&g);
        for (int k = 0; k < 3; k++) {
            t->p[k] = vec3_madd(c, random_unit(&g), size);
            if (i % 5 == 4) t->p[k].z = c.z;
        }
        t->material = (int)(i & 1);
    }
}

/* The closest hit by testing every primitive: 1 and (t, id) with id < n_spheres a sphere. */
static int brute_closest(const scene *sc, const ray *r, double *t_best, long *id_best)
{
    int found = 0;
    for (long i = 0; i < sc->n_spheres + sc->n_triangles; i++) {
        double t, b1, b2;
        int h = i < sc->n_spheres
                    ? sphere_intersect(&sc->spheres[i], r, &t)
                    : triangle_intersect(sc->triangles[i - sc->n_spheres].p[0],
                                         sc->triangles[i - sc->n_spheres].p[1],
                                         sc->triangles[i - sc->n_spheres].p[2], r, &t, &b1, &b2);
        if (h && (!found || t < *t_best)) {
            found = 1;
            *t_best = t;
            *id_best = i;
        }
    }
    return found;
}

/* A random test ray: from inside or outside the scene's box, sometimes axis-aligned (zero and
 * negative-zero direction components exercise the slab test's infinities), sometimes with a
 * finite (tmin, tmax), sometimes aimed at a primitive's centre. */
static ray random_ray(rng *g, const scene *sc)
{
    ray r = {vec3_make(14 * sym(g), 14 * sym(g), 14 * sym(g)), random_unit(g), 0.0, INFINITY};
    double kind = rng_uniform(g);
    if (kind < 0.15) {
        int axis = (int)(rng_uniform(g) * 3);
        double s = rng_uniform(g) < 0.5 ? -1 : 1;
        double zero = rng_uniform(g) < 0.5 ? -0.0 : 0.0;
        r.d = vec3_make(axis == 0 ? s : zero, axis == 1 ? s : zero, axis == 2 ? s : zero);
    } else if (kind < 0.45 && sc->n_spheres + sc->n_triangles > 0) {
        long i = (long)(rng_uniform(g) * (double)(sc->n_spheres + sc->n_triangles));
        vec3 target = i < sc->n_spheres
                          ? mat4_point(&sc->spheres[i].xf, sc->spheres[i].center)
                          : vec3_scale(vec3_add(vec3_add(sc->triangles[i - sc->n_spheres].p[0],
                                                         sc->triangles[i - sc->n_spheres].p[1]),
                                                sc->triangles[i - sc->n_spheres].p[2]),
                                       1.0 / 3);
        r.d = vec3_normalize(vec3_sub(target, r.o));
    }
    if (rng_uniform(g) < 0.3) {
        r.tmin = 5 * rng_uniform(g);
        r.tmax = r.tmin + 20 * rng_uniform(g);
    }
    return r;
}

/* bvh_intersect and bvh_occluded against brute force on n_rays random rays. */
static void check_against_brute_force(const scene *sc, int n_rays, uint64_t seed)
{
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(sc), NULL, &err), 0);
    rng g;
    rng_seed(&g, seed, 1);
    int hits = 0;
    for (int i = 0; i < n_rays; i++) {
        ray r = random_ray(&g, sc);
        double tb = 0;
        long idb = -1;
        int want = brute_closest(sc, &r, &tb, &idb);
        hit h;
        memset(&h, 0, sizeof h);
        int got = bvh_intersect(&b, &r, &h);
        EXPECT_MSG(got == want, "ray %d: bvh %s, brute force %s (t = %g)", i,
                   got ? "hit" : "missed", want ? "hit" : "missed", tb);
        EXPECT_INT_EQ(bvh_occluded(&b, &r), want);
        if (!want) continue;
        hits++;
        /* same t bit for bit: the same intersection routine on the same numbers */
        EXPECT_MSG(h.t == tb, "ray %d: bvh t = %.17g, brute force t = %.17g", i, h.t, tb);
        long id = h.is_sphere ? h.prim : h.prim + sc->n_spheres;
        if (id != idb) {
            /* a tie (two triangles through one edge): the bvh's primitive must give the same t */
            double t2 = 0, b1, b2;
            const triangle *tr = &sc->triangles[h.prim];
            EXPECT_MSG(!h.is_sphere &&
                           triangle_intersect(tr->p[0], tr->p[1], tr->p[2], &r, &t2, &b1, &b2) &&
                           t2 == tb,
                       "ray %d: bvh hit primitive %ld, brute force %ld", i, id, idb);
        }
        int mat = h.is_sphere ? sc->spheres[h.prim].material : sc->triangles[h.prim].material;
        EXPECT_INT_EQ(h.material, mat);
        vec3 p = vec3_madd(r.o, r.d, h.t);
        EXPECT(vec3_length(vec3_sub(p, h.p)) < 1e-9 * (1 + vec3_length(p)));
        EXPECT_NEAR(vec3_length(h.ng), 1, 1e-12);
    }
    if (n_rays >= 1000) ck_assert_int_gt(hits, n_rays / 10); /* the test saw real work */
    bvh_free(&b);
}

START_TEST(test_bvh_with_3_primitives_builds_no_tree_and_matches_brute_force)
{
    scene sc;
    random_scene(&sc, 3, 41);
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    EXPECT_INT_EQ(b.is_tree, 0);
    EXPECT_INT_EQ(b.n_nodes, 1);
    bvh_free(&b);
    check_against_brute_force(&sc, 3000, 41);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_is_a_tree_only_above_bvh_min_prims)
{
    error err = {0};
    bvh b;
    scene sc;
    random_scene(&sc, BVH_MIN_PRIMS, 42);
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    EXPECT_INT_EQ(b.is_tree, 0);
    bvh_free(&b);
    scene_free(&sc);
    random_scene(&sc, BVH_MIN_PRIMS + 1, 42);
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    EXPECT_INT_EQ(b.is_tree, 1);
    EXPECT_INT_EQ(b.n_prims, BVH_MIN_PRIMS + 1);
    bvh_free(&b);
    bvh_free(&b); /* twice: safe */
    scene_free(&sc);
}
END_TEST

/* The tree's memory is charged before it is built and its build's scratch released afterwards;
 * a budget one byte short refuses with one message naming the scene and the primitives. */
START_TEST(test_bvh_is_charged_to_the_budget_before_it_is_built)
{
    error err = {0};
    bvh b;
    scene sc;
    random_scene(&sc, 1000, 7);
    snprintf(sc.path, sizeof sc.path, "s.test");
    double scratch, keep = bvh_bytes(1000, &scratch);
    EXPECT(keep > 1000 * 2 * sizeof(bvh_node) && scratch > 0);
    EXPECT(bvh_bytes_per_prim() * 1000 >= keep + scratch);
    budget mem;
    budget_init(&mem, keep + scratch - 1);
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), &mem, &err), -1);
    EXPECT(strcmp(err.file, "s.test") == 0 && strstr(err.msg, "the BVH of 1000 primitives x ") &&
           strstr(err.msg, "beyond the memory budget"));
    EXPECT(mem.used == 0 && b.nodes == NULL);
    budget_init(&mem, keep + scratch);
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), &mem, &err), 0);
    EXPECT(mem.used == b.bytes && b.bytes <= keep); /* what the tree keeps; unused nodes released */
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_with_9_primitives_matches_brute_force)
{
    scene sc;
    random_scene(&sc, 9, 43);
    check_against_brute_force(&sc, 5000, 43);
    scene_free(&sc);
}
END_TEST

/* Walk the tree from `node` at `depth` (the root's is 0): every child's box lies inside its
 * parent's, and the deepest node and the largest leaf are recorded. */
static void walk(const bvh *b, int node, int depth, int *deepest, int *largest_leaf)
{
    const bvh_node *nd = &b->nodes[node];
    if (depth + 1 > *deepest) *deepest = depth + 1;
    if (nd->count > 0) {
        if (nd->count > *largest_leaf) *largest_leaf = nd->count;
        return;
    }
    int child[2] = {node + 1, nd->offset}; /* the first follows its parent; the second: offset */
    for (int k = 0; k < 2; k++) {
        const bvh_node *c = &b->nodes[child[k]];
        for (int a = 0; a < 3; a++)
            EXPECT(c->box[0][a] >= nd->box[0][a] && c->box[1][a] <= nd->box[1][a]);
        walk(b, child[k], depth + 1, deepest, largest_leaf);
    }
}

START_TEST(test_bvh_with_1000_primitives_matches_brute_force)
{
    scene sc;
    random_scene(&sc, 1000, 44);
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    EXPECT_INT_EQ(b.is_tree, 1);
    ck_assert_int_le(b.n_nodes, 2 * 1000 - 1);
    ck_assert_int_le(b.depth, BVH_MAX_DEPTH);
    /* every primitive appears exactly once in leaf order */
    char *seen = calloc(1000, 1);
    for (long i = 0; i < b.n_prims; i++) {
        ck_assert_uint_lt(b.prims[i], 1000);
        EXPECT(!seen[b.prims[i]]);
        seen[b.prims[i]] = 1;
    }
    free(seen);
    /* the depth it reports is the tree's; the binned SAH splits this scattered scene down to
     * leaves of a few primitives (a partition that sent a whole bin the wrong way made leaves
     * of hundreds, and every answer stayed right: only the time would show it) */
    int deepest = 0, largest = 0;
    walk(&b, 0, 0, &deepest, &largest);
    EXPECT_INT_EQ(deepest, b.depth);
    ck_assert_int_le(largest, 2 * BVH_LEAF_MAX);
    bvh_free(&b);
    check_against_brute_force(&sc, 3000, 44);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_of_only_spheres_or_only_triangles_matches_brute_force)
{
    scene sc;
    random_scene(&sc, 200, 45);
    long nt = sc.n_triangles;
    sc.n_triangles = 0; /* spheres only */
    check_against_brute_force(&sc, 1500, 45);
    sc.n_triangles = nt;
    sphere *sp = sc.spheres;
    long ns = sc.n_spheres;
    sc.spheres = NULL; /* triangles only */
    sc.n_spheres = 0;
    check_against_brute_force(&sc, 1500, 46);
    sc.spheres = sp;
    sc.n_spheres = ns;
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_of_coincident_primitives_matches_brute_force)
{
    /* 40 copies of one sphere and 40 of one triangle: no split separates equal centroids, so
     * the builder must make big leaves instead of recursing forever */
    scene sc;
    scene_alloc(&sc, 40, 40);
    for (int i = 0; i < 40; i++) {
        set_sphere(&sc.spheres[i], vec3_make(1, 2, 3), 1 + 0.001 * i, mat4_identity(), 0);
        sc.triangles[i] =
            (triangle){.p = {{-5, -5, 0}, {5, -5, 0}, {0, 5, 0.01 * i}}, .material = 1};
    }
    check_against_brute_force(&sc, 3000, 47);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_of_a_geometric_series_stays_within_the_depth_limit)
{
    /* spheres at x = 2^-k: each SAH split peels a few off, so the tree wants to be ~n/4 deep;
     * the builder stops at BVH_MAX_DEPTH and traversal must not overrun its stack (ASan) */
    const int n = 400;
    scene sc;
    scene_alloc(&sc, n, 0);
    for (int k = 0; k < n; k++)
        set_sphere(&sc.spheres[k], vec3_make(ldexp(1, -k), 0, 0), ldexp(0.1, -k), mat4_identity(),
                   0);
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    ck_assert_int_le(b.depth, BVH_MAX_DEPTH);
    rng g;
    rng_seed(&g, 48, 0);
    for (int i = 0; i < 4000; i++) {
        int k = (int)(rng_uniform(&g) * 40);
        vec3 target = vec3_make(ldexp(1, -k), 0, 0);
        vec3 o = vec3_madd(target, random_unit(&g), 3);
        ray r = {o, vec3_normalize(vec3_sub(target, o)), 0.0, INFINITY};
        double tb = 0;
        long idb = -1;
        int want = brute_closest(&sc, &r, &tb, &idb);
        hit h;
        EXPECT_INT_EQ(want, 1);
        EXPECT_INT_EQ(bvh_intersect(&b, &r, &h), 1);
        EXPECT_MSG(h.t == tb, "ray %d (k %d): bvh t %.17g prim %ld, brute %.17g prim %ld", i, k,
                   h.t, h.prim, tb, idb);
        EXPECT_INT_EQ(h.prim, idb);
        EXPECT_INT_EQ(bvh_occluded(&b, &r), 1);
    }
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_of_an_empty_scene_never_hits)
{
    scene sc;
    scene_alloc(&sc, 0, 0);
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    EXPECT_INT_EQ(b.is_tree, 0);
    ray r = {vec3_make(0, 0, 0), vec3_make(0, 0, 1), 0.0, INFINITY};
    hit h;
    EXPECT_INT_EQ(bvh_intersect(&b, &r, &h), 0);
    EXPECT_INT_EQ(bvh_occluded(&b, &r), 0);
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_triangle_hit_fills_barycentrics_and_normals)
{
    scene sc;
    scene_alloc(&sc, 0, 1);
    triangle *t = &sc.triangles[0];
    *t = (triangle){.p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, .material = 1};
    error err = {0};
    bvh b;
    EXPECT_INT_EQ(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    ray r = {vec3_make(0.25, 0.5, 3), vec3_make(0, 0, -1), 0.0, INFINITY};
    hit h;
    EXPECT_INT_EQ(bvh_intersect(&b, &r, &h), 1);
    EXPECT_NEAR(h.bary.u, 0.25, 1e-15);
    EXPECT_NEAR(h.bary.v, 0.5, 1e-15);
    EXPECT_NEAR(h.ng.z, 1, 1e-15); /* counter-clockwise seen from +z: normal +z */
    EXPECT_NEAR(h.ns.z, 1, 1e-15);
    EXPECT_INT_EQ(h.prim, 0);
    EXPECT_INT_EQ(h.is_sphere, 0);
    EXPECT_INT_EQ(h.material, 1);
    /* trinormal: the shading normal interpolates the vertex normals, and the geometric normal
     * turns to their side */
    t->has_normals = 1;
    t->n[0] = t->n[1] = t->n[2] = vec3_make(0, 0, -1);
    t->n[1] = vec3_normalize(vec3_make(1, 0, -1));
    EXPECT_INT_EQ(bvh_intersect(&b, &r, &h), 1);
    vec3 want = vec3_normalize(vec3_add(vec3_scale(vec3_make(0, 0, -1), 0.75),
                                        vec3_scale(vec3_normalize(vec3_make(1, 0, -1)), 0.25)));
    EXPECT_NEAR(h.ns.x, want.x, 1e-15);
    EXPECT_NEAR(h.ns.z, want.z, 1e-15);
    EXPECT_NEAR(h.ng.z, -1, 1e-15);
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_bvh_agrees_with_brute_force_on_rays_through_a_silhouette_edge)
{
    /* 40 triangles fanned like the pages of a half-open book around a shared spine on the x
     * axis: the spine is the lower y and z face of every box in the tree.  Rays aimed exactly
     * at the spine from outside the fan hit it (edges are inside, triangle.h); the boxes must not
     * cull, by rounding in the slab test, what the triangles accept. */
    const int n = 40;
    scene sc;
    scene_alloc(&sc, 0, n);
    for (int k = 0; k < n; k++) {
        double th = 0.5 * M_PI * (k + 0.5) / n;
        sc.triangles[k] =
            (triangle){.p = {{-5.1, 0, 0}, {4.7, 0, 0}, {0.3, 5 * cos(th), 5 * sin(th)}}};
    }
    error err = {0};
    bvh b;
    ck_assert_int_eq(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    ck_assert_int_eq(b.is_tree, 1);
    rng g;
    rng_seed(&g, 49, 0);
    for (int k = 0; k < 5000; k++) {
        vec3 target = vec3_make(-5 + 9.6 * rng_uniform(&g), 0, 0);
        vec3 o = vec3_make(10 * sym(&g), -1 - 9 * rng_uniform(&g), -1 - 9 * rng_uniform(&g));
        ray r = {o, vec3_sub(target, o), 0.0, INFINITY};
        double tb = 0;
        long idb = -1;
        int want = brute_closest(&sc, &r, &tb, &idb);
        hit h;
        EXPECT_MSG(bvh_intersect(&b, &r, &h) == want, "ray %d: the bvh missed the spine", k);
        EXPECT_INT_EQ(bvh_occluded(&b, &r), want);
        if (want)
            EXPECT_MSG(h.t == tb, "ray %d: bvh t %.17g prim %ld, brute %.17g prim %ld", k, h.t,
                       h.prim, tb, idb);
    }
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

/* Right triangles with legs along the axes (their edges lie on their boxes' edges), 1 unit
 * wide near the origin of coordinates, seen from ~500 units away, the rays aimed at points just
 * inside a leg: a float triangle test without its margin (BVH_FILTER_EPS) rejects hits that
 * the double test accepts (the box padding, not only the slabs' origins, keeps these boxes). */
START_TEST(test_bvh_keeps_hits_along_box_edges_seen_from_far_away)
{
    const int n = 200;
    scene sc;
    scene_alloc(&sc, 0, n);
    rng g;
    rng_seed(&g, 50, 0);
    for (int i = 0; i < n; i++) {
        vec3 c = vec3_make(4 * sym(&g), 4 * sym(&g), 4 * sym(&g));
        double w = 0.5 + rng_uniform(&g);
        vec3 px = vec3_add(c, vec3_make(w, 0, 0)), py = vec3_add(c, vec3_make(0, w, 0));
        sc.triangles[i] = (triangle){.p = {c, px, py}};
    }
    error err = {0};
    bvh b;
    ck_assert_int_eq(bvh_build(&b, scene_prims(&sc), NULL, &err), 0);
    int hits = 0;
    for (int k = 0; k < 20000; k++) {
        const triangle *t = &sc.triangles[(int)(rng_uniform(&g) * n)];
        double u = rng_uniform(&g), v = 1e-6 * rng_uniform(&g); /* just inside the x leg */
        if (k % 2) {
            double x = u;
            u = v;
            v = x;
        } /* or the y leg */
        vec3 target = vec3_add(vec3_add(vec3_scale(t->p[0], 1 - u - v), vec3_scale(t->p[1], u)),
                               vec3_scale(t->p[2], v));
        vec3 dir = random_unit(&g);
        if (dir.z < 0.3) dir = vec3_normalize(vec3_make(dir.x, dir.y, 1));
        vec3 o = vec3_madd(target, dir, 500 + rng_uniform(&g));
        ray r = {o, vec3_sub(target, o), 0.0, INFINITY};
        double tb = 0;
        long idb = -1;
        int want = brute_closest(&sc, &r, &tb, &idb);
        hit h;
        EXPECT_MSG(bvh_intersect(&b, &r, &h) == want, "ray %d: bvh and brute force disagree", k);
        EXPECT_INT_EQ(bvh_occluded(&b, &r), want);
        if (want) EXPECT_MSG(h.t == tb, "ray %d: bvh t %.17g, brute force %.17g", k, h.t, tb);
        hits += want;
    }
    ck_assert_int_gt(hits, 10000);
    bvh_free(&b);
    scene_free(&sc);
}
END_TEST

Suite *bvh_suite(void)
{
    Suite *s = suite_create("bvh");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_bvh_with_3_primitives_builds_no_tree_and_matches_brute_force);
    tcase_add_test(tc, test_bvh_is_a_tree_only_above_bvh_min_prims);
    tcase_add_test(tc, test_bvh_is_charged_to_the_budget_before_it_is_built);
    tcase_add_test(tc, test_bvh_with_9_primitives_matches_brute_force);
    tcase_add_test(tc, test_bvh_with_1000_primitives_matches_brute_force);
    tcase_add_test(tc, test_bvh_of_only_spheres_or_only_triangles_matches_brute_force);
    tcase_add_test(tc, test_bvh_of_coincident_primitives_matches_brute_force);
    tcase_add_test(tc, test_bvh_of_a_geometric_series_stays_within_the_depth_limit);
    tcase_add_test(tc, test_bvh_of_an_empty_scene_never_hits);
    tcase_add_test(tc, test_bvh_triangle_hit_fills_barycentrics_and_normals);
    tcase_add_test(tc, test_bvh_agrees_with_brute_force_on_rays_through_a_silhouette_edge);
    tcase_add_test(tc, test_bvh_keeps_hits_along_box_edges_seen_from_far_away);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(bvh_suite)

/* test_cubemap.c - cube map face selection, face orientation, ties, seamless lookup, crosses. */
#include "envtex/envmaps/cubemap.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "unit.h"

#include <float.h>

#define RANDOM_DIRECTIONS 1000000
#define ROUNDTRIP_TOL     1e-6  /* radians; the brief's bound (doubles actually give ~1e-15) */
#define ST_TOL            1e-12 /* face coordinates after a round trip: a few ulps of 1 */

static const vec3 axes[CUBEMAP_FACES] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

/* Catches a wrong major axis or a wrong sign in the table. */
START_TEST(test_cubemap_face_centres_are_the_axes)
{
    for (int f = 0; f < CUBEMAP_FACES; f++) {
        ck_dir_near(cubemap_face_to_dir(f, (uv2){0.5, 0.5}), axes[f], 1e-15);
        int g;
        uv2 st;
        ck_assert_int_eq(cubemap_dir_to_face(axes[f], &g, &st), 0);
        ck_assert_int_eq(g, f);
        ck_assert_double_eq(st.u, 0.5);
        ck_assert_double_eq(st.v, 0.5);
    }
}
END_TEST

/* Known answers from the OpenGL table: where the right edge (s = 1) and the top edge (t = 0)
 * of every face point.  Catches a swapped or negated sc / tc, or t growing up instead of down. */
START_TEST(test_cubemap_face_orientation_follows_the_gl_table)
{
    const double h = sqrt(0.5);
    static const struct {
        int face;
        vec3 right, top;
    } cases[] = {
        {CUBEMAP_POS_X, {1, 0, -1}, {1, 1, 0}}, {CUBEMAP_NEG_X, {-1, 0, 1}, {-1, 1, 0}},
        {CUBEMAP_POS_Y, {1, 1, 0}, {0, 1, -1}}, {CUBEMAP_NEG_Y, {1, -1, 0}, {0, -1, 1}},
        {CUBEMAP_POS_Z, {1, 0, 1}, {0, 1, 1}},  {CUBEMAP_NEG_Z, {-1, 0, -1}, {0, 1, -1}},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        int f = cases[k].face;
        ck_dir_near(cubemap_face_to_dir(f, (uv2){1.0, 0.5}), vec3_scale(cases[k].right, h),
                        1e-15);
        ck_dir_near(cubemap_face_to_dir(f, (uv2){0.5, 0.0}), vec3_scale(cases[k].top, h),
                        1e-15);
        /* the opposite edges are the mirror images through the face centre */
        vec3 left = vec3_sub(vec3_scale(axes[f], 2.0), cases[k].right);
        vec3 bottom = vec3_sub(vec3_scale(axes[f], 2.0), cases[k].top);
        ck_dir_near(cubemap_face_to_dir(f, (uv2){0.0, 0.5}), vec3_normalize(left), 1e-15);
        ck_dir_near(cubemap_face_to_dir(f, (uv2){0.5, 1.0}), vec3_normalize(bottom), 1e-15);
    }
}
END_TEST

/* The lecture's round trip on 10^6 directions.  Catches any inconsistency between the two
 * directions of the table. */
START_TEST(test_cubemap_roundtrip_is_exact_for_random_directions)
{
    rng r;
    rng_seed(&r, 168, 1);
    double worst = 0;
    int bad = 0; /* counted, not asserted, in the loop: Check writes a file on every assert */
    for (int k = 0; k < RANDOM_DIRECTIONS; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        int f;
        uv2 st;
        bad += cubemap_dir_to_face(d, &f, &st) != 0;
        bad += !(st.u >= 0 && st.u <= 1 && st.v >= 0 && st.v <= 1);
        double a = vec3_angle(cubemap_face_to_dir(f, st), d);
        if (!(a <= worst)) worst = a; /* NaN becomes the worst */
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_msg(worst < ROUNDTRIP_TOL, "worst round-trip error %g rad", worst);
}
END_TEST

/* face -> direction -> face on a grid of interior points of every face (no ties there). */
START_TEST(test_cubemap_face_points_come_back_to_the_same_face)
{
    int wrong = 0;        /* counted, not asserted, in the loop: Check writes a file per assert */
    char first[160] = ""; /* the first point that did not come back, for the message */
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 1; j < 64; j++)
            for (int i = 1; i < 64; i++) {
                uv2 st = {i / 64.0, j / 64.0};
                int g = -1;
                uv2 back = {NAN, NAN};
                int rc = cubemap_dir_to_face(cubemap_face_to_dir(f, st), &g, &back);
                if (rc != 0 || g != f ||
                    !(fabs(back.u - st.u) < ST_TOL && fabs(back.v - st.v) < ST_TOL)) {
                    if (!wrong++)
                        snprintf(first, sizeof first,
                                 "face %d (s, t) = (%g, %g) came back as face %d (%g, %g)", f, st.u,
                                 st.v, g, back.u, back.v);
                }
            }
    ck_assert_msg(wrong == 0, "%d of %d points did not come back; the first: %s", wrong,
                  CUBEMAP_FACES * 63 * 63, first);
}
END_TEST

/* The face the tie rule "x before y before z" must pick for a direction. */
static int tie_rule_face(vec3 d)
{
    const double c[3] = {d.x, d.y, d.z};
    int axis = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(c[i]) > fabs(c[axis])) axis = i; /* strictly larger: a tie keeps the earlier */
    return 2 * axis + (c[axis] > 0 ? 0 : 1);
}

/* Every point on every edge of every face (including the corners) maps to a direction that
 * comes back on the face the tie rule names, at the same direction; the face that wins the tie
 * gets back its own coordinates.  Catches a tie rule that differs between the two directions
 * (an edge texel that would jump faces) and a ">" where ">=" belongs. */
START_TEST(test_cubemap_edges_and_corners_follow_the_tie_rule)
{
    int wins = 0;
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int e = 0; e < 4; e++)
            for (int k = 0; k <= 16; k++) {
                double p = k / 16.0;
                uv2 st = e == 0   ? (uv2){0, p}
                         : e == 1 ? (uv2){1, p}
                         : e == 2 ? (uv2){p, 0}
                                  : (uv2){p, 1};
                vec3 d = cubemap_face_to_dir(f, st);
                int g;
                uv2 back;
                ck_assert_int_eq(cubemap_dir_to_face(d, &g, &back), 0);
                ck_assert_int_eq(g, tie_rule_face(d));
                ck_dir_near(cubemap_face_to_dir(g, back), d, 1e-15);
                if (g == f) {
                    wins++;
                    ck_assert_near(back.u, st.u, ST_TOL);
                    ck_assert_near(back.v, st.v, ST_TOL);
                }
            }
    ck_assert_int_gt(wins, 0);
    /* exact ties given directly: the 12 edge midpoints and 8 corners */
    for (int sx = -1; sx <= 1; sx++)
        for (int sy = -1; sy <= 1; sy++)
            for (int sz = -1; sz <= 1; sz++) {
                vec3 d = vec3_make(sx, sy, sz);
                if (vec3_length2(d) < 2) continue; /* face centres and zero: not ties */
                int g;
                uv2 st;
                ck_assert_int_eq(cubemap_dir_to_face(d, &g, &st), 0);
                ck_assert_int_eq(g, tie_rule_face(d));
                ck_assert(st.u == 0 || st.u == 0.5 || st.u == 1);
                ck_assert(st.v == 0 || st.v == 0.5 || st.v == 1);
            }
    /* a corner: (1,1,1) is on +X, at its top-left corner (s: -z -> 0, t: -y -> 0) */
    int g;
    uv2 st;
    cubemap_dir_to_face(vec3_make(1, 1, 1), &g, &st);
    ck_assert_int_eq(g, CUBEMAP_POS_X);
    ck_assert_double_eq(st.u, 0.0);
    ck_assert_double_eq(st.v, 0.0);
}
END_TEST

/* Catches a missing validity check (NaN faces, division by zero). */
START_TEST(test_cubemap_rejects_zero_infinite_and_nan_directions)
{
    const vec3 bad[] = {{0, 0, 0},   {-0.0, 0, -0.0},  {NAN, 0, 1},      {1, NAN, 0},
                        {0, 0, NAN}, {INFINITY, 0, 0}, {1, -INFINITY, 0}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        int f = 77;
        uv2 st = {-5, -5};
        ck_assert_int_eq(cubemap_dir_to_face(bad[k], &f, &st), -1);
        ck_assert_int_eq(f, 77); /* outputs untouched */
        ck_assert_double_eq(st.u, -5);
    }
}
END_TEST

/* Only the direction matters, however long or short, subnormal included.  Catches 1/|ma|
 * overflowing to infinity (0 * inf = NaN) for tiny vectors. */
START_TEST(test_cubemap_ignores_the_length_of_the_direction)
{
    const double scales[] = {1.0, 7.25, 1e-300, 1e300, DBL_MAX / 2};
    rng r;
    rng_seed(&r, 7, 2);
    for (int k = 0; k < 1000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        int f0;
        uv2 st0;
        cubemap_dir_to_face(d, &f0, &st0);
        for (size_t s = 1; s < sizeof scales / sizeof scales[0]; s++) {
            int f;
            uv2 st;
            ck_assert_int_eq(cubemap_dir_to_face(vec3_scale(d, scales[s]), &f, &st), 0);
            ck_assert_int_eq(f, f0);
            ck_assert_near(st.u, st0.u, 1e-15);
            ck_assert_near(st.v, st0.v, 1e-15);
        }
    }
    /* a subnormal axis: exact */
    int f;
    uv2 st;
    ck_assert_int_eq(cubemap_dir_to_face(vec3_make(0, 0, -0x1p-1074), &f, &st), 0);
    ck_assert_int_eq(f, CUBEMAP_NEG_Z);
    ck_assert_double_eq(st.u, 0.5);
    ck_assert_double_eq(st.v, 0.5);
}
END_TEST

/* A cube map whose every texel stores the direction of its own centre as its colour. */
static void fill_with_directions(cubemap *cm)
{
    int n = cm->size;
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                vec3 d = cubemap_face_to_dir(f, (uv2){(i + 0.5) / n, (j + 0.5) / n});
                image_set(&cm->face[f], i, j, rgb_make(d.x, d.y, d.z));
            }
}

/* The lookup's colour read as a direction. */
static vec3 lookup_dir(const cubemap *cm, vec3 d)
{
    rgb c = cubemap_lookup_bilinear(cm, d);
    return vec3_make(c.r, c.g, c.b);
}

/* At a texel centre the lookup is that texel, nothing else.  Catches a half-texel offset. */
START_TEST(test_cubemap_lookup_at_a_texel_centre_returns_the_texel)
{
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, 8, NULL), 0);
    fill_with_directions(&cm);
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 0; j < 8; j++)
            for (int i = 0; i < 8; i++) {
                vec3 d = cubemap_face_to_dir(f, (uv2){(i + 0.5) / 8, (j + 0.5) / 8});
                rgb c = cubemap_lookup_bilinear(&cm, vec3_scale(d, 3.0));
                rgb want = image_get(&cm.face[f], i, j);
                ck_assert_near(c.r, want.r, 1e-12);
                ck_assert_near(c.g, want.g, 1e-12);
                ck_assert_near(c.b, want.b, 1e-12);
            }
    cubemap_free(&cm);
}
END_TEST

/* Faces of one constant colour each: exactly on an edge the lookup is the mean of the two faces,
 * at a corner the mean of the three.  Catches a clamped (seamed) lookup, which returns one
 * face's colour. */
START_TEST(test_cubemap_lookup_on_edges_and_corners_blends_the_faces_that_meet)
{
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, 4, NULL), 0);
    double value[CUBEMAP_FACES] = {1, 2, 4, 8, 16, 32};
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) image_set(&cm.face[f], i, j, rgb_gray(value[f]));
    rgb c = cubemap_lookup_bilinear(&cm, vec3_make(1, 0, 1)); /* +X | +Z edge, midpoint */
    ck_assert_near(c.r, (1 + 16) / 2.0, 1e-12);
    c = cubemap_lookup_bilinear(&cm, vec3_make(0, -1, -1)); /* -Y | -Z */
    ck_assert_near(c.r, (8 + 32) / 2.0, 1e-12);
    c = cubemap_lookup_bilinear(&cm, vec3_make(-1, 1, 0.3)); /* -X | +Y, off the midpoint */
    ck_assert_near(c.r, (2 + 4) / 2.0, 1e-12);
    c = cubemap_lookup_bilinear(&cm, vec3_make(1, 1, 1)); /* corner +X +Y +Z */
    ck_assert_near(c.r, (1 + 4 + 16) / 3.0, 1e-12);
    c = cubemap_lookup_bilinear(&cm, vec3_make(-1, -1, -1)); /* corner -X -Y -Z */
    ck_assert_near(c.r, (2 + 8 + 32) / 3.0, 1e-12);
    /* and far from edges the face's own colour */
    c = cubemap_lookup_bilinear(&cm, vec3_make(0.1, -0.2, -1));
    ck_assert_near(c.r, 32, 1e-12);
    cubemap_free(&cm);
}
END_TEST

/* Just on either side of every edge (and of every corner, from all three faces) the lookups
 * agree: no visible seam.  Catches clamping at face edges, a neighbour texel taken from the
 * wrong row (an edge glued with the wrong orientation), and an asymmetric corner. */
START_TEST(test_cubemap_lookup_has_no_seam_across_edges_and_corners)
{
    const int n = 16;
    const double nudge = 1e-9; /* moves a point off the edge onto one face; lookups vary by
                                  about nudge * N, far below the 1e-6 we ask */
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, n, NULL), 0);
    fill_with_directions(&cm);
    double worst = 0;
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int e = 0; e < 4; e++)
            for (int k = 0; k <= 200; k++) {
                double p = k / 200.0;
                uv2 st = e == 0   ? (uv2){0, p}
                         : e == 1 ? (uv2){1, p}
                         : e == 2 ? (uv2){p, 0}
                                  : (uv2){p, 1};
                vec3 d = cubemap_face_to_dir(f, st);
                /* grow each of the tied largest components in turn: lands on each face */
                double m = vec3_max_abs(d);
                vec3 ref = lookup_dir(&cm, d);
                for (int axis = 0; axis < 3; axis++) {
                    if (fabs(vec3_get(d, axis)) != m) continue;
                    vec3 q = d;
                    if (axis == 0) q.x *= 1 + nudge;
                    if (axis == 1) q.y *= 1 + nudge;
                    if (axis == 2) q.z *= 1 + nudge;
                    double diff = vec3_length(vec3_sub(lookup_dir(&cm, q), ref));
                    if (!(diff <= worst)) worst = diff;
                }
            }
    ck_assert_msg(worst < 1e-6, "lookups differ by %g across an edge", worst);
    cubemap_free(&cm);
}
END_TEST

/* Texels store their own direction, so the lookup should reproduce the direction to within the
 * interpolation error everywhere, edges and corners included.  Catches a neighbour texel that
 * is the wrong one (its direction would be off by up to 2 rad). */
START_TEST(test_cubemap_lookup_reproduces_a_smooth_function_everywhere)
{
    const int n = 16;
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, n, NULL), 0);
    fill_with_directions(&cm);
    rng r;
    rng_seed(&r, 3, 4);
    double worst = 0;
    for (int k = 0; k < 200000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        double a = vec3_angle(lookup_dir(&cm, d), d);
        if (!(a <= worst)) worst = a;
    }
    /* A texel spans about 2/N rad at a face centre; the interpolation error stays well under
     * half of that (measured: about 0.2/N at corners). */
    ck_assert_msg(worst < 0.5 / n, "worst lookup error %g rad", worst);
    cubemap_free(&cm);
}
END_TEST

/* A cross made from direction-coloured faces: every pair of neighbouring pixels inside the
 * cross (both in a face cell) holds nearby directions.  Catches a face in the wrong cell or
 * with the wrong rotation. */
#define assert_cross_is_continuous(cross, n) cross_is_continuous_at(__FILE__, __LINE__, cross, n)
static void cross_is_continuous_at(const char *file, int line, const image *cross, int n)
{
    int pairs = 0;
    for (int y = 0; y < cross->h; y++)
        for (int x = 0; x < cross->w; x++) {
            rgb a = image_get(cross, x, y);
            if (rgb_is_black(a)) continue;
            for (int k = 0; k < 2; k++) {
                int x2 = x + (k == 0), y2 = y + (k == 1);
                if (x2 >= cross->w || y2 >= cross->h) continue;
                rgb b = image_get(cross, x2, y2);
                if (rgb_is_black(b)) continue;
                double ang = vec3_angle(vec3_make(a.r, a.g, a.b), vec3_make(b.r, b.g, b.b));
                /* neighbouring texel centres are at most ~2/N apart (face centres) */
                if (!(ang < 2.2 / n))
                    unit_fail_at(file, line, "pixels (%d,%d) and (%d,%d) are %.17g rad apart, "
                                 "want under %.17g", x, y, x2, y2, ang, 2.2 / n);
                pairs++;
            }
        }
    if (pairs == 0) unit_fail_at(file, line, "no pair of neighbouring pixels in the cross");
}

START_TEST(test_cubemap_crosses_are_continuous_across_internal_edges)
{
    const int n = 12;
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, n, NULL), 0);
    fill_with_directions(&cm);
    image h = {0}, v = {0};
    ck_assert_int_eq(cubemap_to_horizontal_cross(&cm, &h, NULL), 0);
    ck_assert_int_eq(cubemap_to_vertical_cross(&cm, &v, NULL), 0);
    ck_assert_int_eq(h.w, 4 * n);
    ck_assert_int_eq(h.h, 3 * n);
    ck_assert_int_eq(v.w, 3 * n);
    ck_assert_int_eq(v.h, 4 * n);
    assert_cross_is_continuous(&h, n);
    assert_cross_is_continuous(&v, n);
    /* 6 of 12 cells are faces: half the pixels black, half unit directions */
    for (int k = 0; k < 2; k++) {
        const image *im = k ? &v : &h;
        int black = 0;
        for (int y = 0; y < im->h; y++)
            for (int x = 0; x < im->w; x++) black += rgb_is_black(image_get(im, x, y));
        ck_assert_int_eq(black, 6 * n * n);
    }
    image_free(&h);
    image_free(&v);
    cubemap_free(&cm);
}
END_TEST

/* The documented cells: cell centres hold the face centre directions. */
START_TEST(test_cubemap_crosses_put_each_face_in_its_documented_cell)
{
    const int n = 2;
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, n, NULL), 0);
    fill_with_directions(&cm);
    image h = {0}, v = {0};
    cubemap_to_horizontal_cross(&cm, &h, NULL);
    cubemap_to_vertical_cross(&cm, &v, NULL);
    static const int hcell[CUBEMAP_FACES][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}};
    static const int vcell[CUBEMAP_FACES][2] = {{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {1, 3}};
    for (int f = 0; f < CUBEMAP_FACES; f++) {
        /* the four texels around a cell centre average to the face's axis direction */
        for (int k = 0; k < 2; k++) {
            const image *im = k ? &v : &h;
            const int *cell = k ? vcell[f] : hcell[f];
            rgb sum = rgb_gray(0);
            for (int j = 0; j < n; j++)
                for (int i = 0; i < n; i++)
                    sum = rgb_add(sum, image_get(im, cell[0] * n + i, cell[1] * n + j));
            ck_dir_near(vec3_make(sum.r, sum.g, sum.b), axes[f], 1e-6);
        }
    }
    /* -Z in the vertical cross is turned 180 degrees: its top-left pixel is the face's
     * bottom-right texel */
    rgb a = image_get(&v, 1 * n, 3 * n), b = image_get(&cm.face[CUBEMAP_NEG_Z], n - 1, n - 1);
    ck_assert(a.r == b.r && a.g == b.g && a.b == b.b);
    image_free(&h);
    image_free(&v);
    cubemap_free(&cm);
}
END_TEST

static int same_faces(const cubemap *a, const cubemap *b)
{
    if (a->size != b->size) return 0;
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int k = 0; k < 3 * a->size * a->size; k++)
            if (a->face[f].px[k] != b->face[f].px[k]) return 0;
    return 1;
}

/* Splitting a cross undoes assembling it, for both layouts, and cubemap_from_cross recognises
 * each by its shape.  Catches split and assemble using different tables. */
START_TEST(test_cubemap_split_undoes_assemble_for_both_crosses)
{
    const int n = 5;
    cubemap cm = {0}, back = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, n, NULL), 0);
    rng r;
    rng_seed(&r, 11, 0);
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int k = 0; k < 3 * n * n; k++) cm.face[f].px[k] = (float)(0.1 + rng_uniform(&r));
    image cross = {0};
    error err = {0};
    ck_assert_int_eq(cubemap_to_horizontal_cross(&cm, &cross, &err), 0);
    ck_assert_int_eq(cubemap_from_horizontal_cross(&cross, &back, &err), 0);
    ck_assert(same_faces(&cm, &back));
    cubemap_free(&back);
    ck_assert_int_eq(cubemap_from_cross(&cross, &back, &err), 0);
    ck_assert(same_faces(&cm, &back));
    cubemap_free(&back);
    ck_assert_int_eq(cubemap_from_vertical_cross(&cross, &back, &err), -1); /* wrong shape */
    ck_assert_int_eq(back.size, 0);
    image_free(&cross);

    ck_assert_int_eq(cubemap_to_vertical_cross(&cm, &cross, &err), 0);
    ck_assert_int_eq(cubemap_from_vertical_cross(&cross, &back, &err), 0);
    ck_assert(same_faces(&cm, &back));
    cubemap_free(&back);
    ck_assert_int_eq(cubemap_from_cross(&cross, &back, &err), 0);
    ck_assert(same_faces(&cm, &back));
    cubemap_free(&back);
    image_free(&cross);
    cubemap_free(&cm);
}
END_TEST

/* Catches a cross reader that reads past the image for a shape that is not a cross. */
START_TEST(test_cubemap_from_cross_rejects_other_shapes)
{
    const int sizes[][2] = {{8, 6 + 1}, {10, 10}, {7, 5}, {6, 8 + 2}, {5, 3}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        image im = {0};
        ck_assert_int_eq(image_alloc(&im, sizes[k][0], sizes[k][1], NULL), 0);
        cubemap cm = {0};
        error err = {0};
        ck_assert_int_eq(cubemap_from_cross(&im, &cm, &err), -1);
        ck_assert_int_eq(cm.size, 0);
        ck_assert_ptr_null(cm.face[0].px);
        ck_assert(err.msg[0] != 0);
        image_free(&im);
    }
    /* the layouts' own entry points check the face size too: 8 x 3 is 4 x 3 cells but of 2 x 1
     * pixels (cells must be square, or a face would be read past the image's last row) */
    const int cells[2][2] = {{8, 3}, {3, 8}};
    for (int k = 0; k < 2; k++) {
        image im = {0};
        ck_assert_int_eq(image_alloc(&im, cells[k][0], cells[k][1], NULL), 0);
        cubemap cm = {0};
        error err = {0};
        int rc = k == 0 ? cubemap_from_horizontal_cross(&im, &cm, &err)
                        : cubemap_from_vertical_cross(&im, &cm, &err);
        ck_assert_msg(rc == -1, "a %d x %d cross was accepted", cells[k][0], cells[k][1]);
        ck_assert_int_eq(cm.size, 0);
        ck_assert(err.msg[0] != 0);
        image_free(&im);
    }
}
END_TEST

/* Invalid directions give black, never a read outside the faces. */
START_TEST(test_cubemap_lookup_rejects_invalid_directions)
{
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, 2, NULL), 0);
    fill_with_directions(&cm);
    ck_assert(rgb_is_black(cubemap_lookup_bilinear(&cm, vec3_make(0, 0, 0))));
    ck_assert(rgb_is_black(cubemap_lookup_bilinear(&cm, vec3_make(NAN, 1, 0))));
    ck_assert(rgb_is_black(cubemap_lookup_bilinear(&cm, vec3_make(0, -INFINITY, 0))));
    cubemap_free(&cm);
}
END_TEST

/* A 1 x 1 face: every lookup needs neighbours and corners; the result must stay a weighted mean
 * of the six texels (within their range).  Catches index arithmetic that assumes N >= 2. */
START_TEST(test_cubemap_lookup_works_with_one_texel_faces)
{
    cubemap cm = {0};
    ck_assert_int_eq(cubemap_alloc(&cm, 1, NULL), 0);
    for (int f = 0; f < CUBEMAP_FACES; f++) image_set(&cm.face[f], 0, 0, rgb_gray(f + 1));
    rng r;
    rng_seed(&r, 5, 5);
    int outside = 0; /* counted, not asserted, in the loop: Check writes a file per assert */
    for (int k = 0; k < 10000; k++) {
        rgb c =
            cubemap_lookup_bilinear(&cm, sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r)));
        outside += !(c.r >= 1 - 1e-12 && c.r <= 6 + 1e-12);
    }
    ck_assert_int_eq(outside, 0);
    rgb c = cubemap_lookup_bilinear(&cm, vec3_make(0, 0, 1));
    ck_assert_near(c.r, 5, 1e-12);
    cubemap_free(&cm);
}
END_TEST

Suite *cubemap_suite(void)
{
    Suite *s = suite_create("cubemap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_cubemap_face_centres_are_the_axes);
    tcase_add_test(tc, test_cubemap_face_orientation_follows_the_gl_table);
    tcase_add_test(tc, test_cubemap_roundtrip_is_exact_for_random_directions);
    tcase_add_test(tc, test_cubemap_face_points_come_back_to_the_same_face);
    tcase_add_test(tc, test_cubemap_edges_and_corners_follow_the_tie_rule);
    tcase_add_test(tc, test_cubemap_rejects_zero_infinite_and_nan_directions);
    tcase_add_test(tc, test_cubemap_ignores_the_length_of_the_direction);
    tcase_add_test(tc, test_cubemap_lookup_at_a_texel_centre_returns_the_texel);
    tcase_add_test(tc, test_cubemap_lookup_on_edges_and_corners_blends_the_faces_that_meet);
    tcase_add_test(tc, test_cubemap_lookup_has_no_seam_across_edges_and_corners);
    tcase_add_test(tc, test_cubemap_lookup_reproduces_a_smooth_function_everywhere);
    tcase_add_test(tc, test_cubemap_crosses_are_continuous_across_internal_edges);
    tcase_add_test(tc, test_cubemap_crosses_put_each_face_in_its_documented_cell);
    tcase_add_test(tc, test_cubemap_split_undoes_assemble_for_both_crosses);
    tcase_add_test(tc, test_cubemap_from_cross_rejects_other_shapes);
    tcase_add_test(tc, test_cubemap_lookup_rejects_invalid_directions);
    tcase_add_test(tc, test_cubemap_lookup_works_with_one_texel_faces);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(cubemap_suite)

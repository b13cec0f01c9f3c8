/* test_displace.c - tessellation counts and winding, constant heights as offsets along the
 * normal, area-weighted normals, the sphere's closed surface (volume by the divergence
 * theorem), its seam's corner coordinates, and limits checked before allocation. */
#include "envtex/textures/displace.h"

#include "unit.h"

static double constant(void *ctx, vec3 p, vec3 n, uv2 st)
{
    (void)p, (void)n, (void)st;
    return *(const double *)ctx;
}

/* height = s: checks that the callback sees each vertex's st */
static double height_s(void *ctx, vec3 p, vec3 n, uv2 st)
{
    (void)ctx, (void)p, (void)n;
    return st.u;
}

static const vec3 tri_p[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
static const uv2 tri_st[3] = {{0, 0}, {1, 0}, {0, 1}};

START_TEST(test_a_triangle_at_rate_n_has_n_squared_triangles_wound_like_the_original)
{
    displace_mesh m;
    error err = {0};
    double h = 0;
    ck_assert_int_eq(displace_triangle(tri_p, NULL, NULL, tri_st, 5, constant, &h, 1, 0, &m, &err),
                     0);
    ck_assert_int_eq(m.n_tris, 25);
    ck_assert_int_eq(m.n_verts, 21);
    double area = 0;
    for (long i = 0; i < m.n_tris; i++) {
        const long *v = m.tris[i].v;
        vec3 f = vec3_cross(vec3_sub(m.p[v[1]], m.p[v[0]]), vec3_sub(m.p[v[2]], m.p[v[0]]));
        ck_assert_msg(f.z > 0, "triangle %ld is wound backwards", i);
        area += 0.5 * f.z;
    }
    ck_assert_near(area, 2, 1e-12); /* the pieces tile the original exactly */
    displace_mesh_free(&m);
    displace_mesh_free(&m);
}
END_TEST

/* height = the x of the point the callback sees */
static double height_x(void *ctx, vec3 p, vec3 n, uv2 st)
{
    (void)ctx, (void)n, (void)st;
    return p.x;
}

/* With q, the callback sees b0 q0 + b1 q1 + b2 q2 at each vertex (here q = p + (10, 0, 0) with
 * its corners swapped round, so neither p nor an un-swapped q would do); without, p itself. */
START_TEST(test_the_height_callback_sees_the_corners_q_interpolated_like_p)
{
    const vec3 q[3] = {{20, 0, 0}, {10, 0, 0}, {10, 2, 0}};
    displace_mesh m;
    error err = {0};
    for (int with_q = 0; with_q < 2; with_q++) {
        ck_assert_int_eq(displace_triangle(tri_p, with_q ? q : NULL, NULL, tri_st, 4, height_x,
                                           NULL, 1, 0, &m, &err),
                         0);
        for (long k = 0; k < m.n_verts; k++) {
            /* the grid's barycentrics from the undisplaced point (tri_p is a right triangle) */
            double b1 = m.p[k].x / 2, b2 = m.p[k].y / 2;
            ck_assert(m.p[k].z >= 0);
            double want = with_q ? 20 * (1 - b1 - b2) + 10 * b1 + 10 * b2 : m.p[k].x;
            ck_assert_msg(fabs(m.p[k].z - want) < 1e-12, "q %d, vertex %ld: height %g, want %g",
                          with_q, k, m.p[k].z, want);
        }
        displace_mesh_free(&m);
    }
}
END_TEST

START_TEST(test_a_constant_height_lifts_a_flat_triangle_along_its_normal)
{
    displace_mesh m;
    error err = {0};
    double h = 0.5;
    ck_assert_int_eq(
        displace_triangle(tri_p, NULL, NULL, tri_st, 3, constant, &h, 0.2, 0, &m, &err), 0);
    for (long k = 0; k < m.n_verts; k++) {
        ck_assert_near(m.p[k].z, 0.1, 1e-15); /* scale * h */
        ck_assert_near(m.n[k].z, 1, 1e-15);
    }
    displace_mesh_free(&m);
}
END_TEST

START_TEST(test_a_ramp_height_tilts_the_recomputed_normals)
{
    /* z = scale * s = 0.5 * x / 2 on the plane: normal (-0.25, 0, 1) normalized */
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(
        displace_triangle(tri_p, NULL, NULL, tri_st, 4, height_s, NULL, 0.5, 0, &m, &err), 0);
    vec3 want = vec3_normalize(vec3_make(-0.25, 0, 1));
    for (long k = 0; k < m.n_verts; k++)
        ck_assert_msg(vec3_length(vec3_sub(m.n[k], want)) < 1e-12, "vertex %ld", k);
    /* the corner st are the interpolated ones */
    ck_assert_near(m.tris[0].st[1].u, 0.25, 1e-15);
    displace_mesh_free(&m);
}
END_TEST

START_TEST(test_the_sphere_is_closed_outward_and_has_the_documented_counts)
{
    displace_mesh m;
    error err = {0};
    double h = 0;
    ck_assert_int_eq(displace_sphere(8, constant, &h, 1, 0, &m, &err), 0);
    ck_assert_int_eq(m.n_verts, 2 + 7 * 16);
    ck_assert_int_eq(m.n_tris, 4 * 8 * 7);
    /* volume = (1/6) sum a . (b x c): only a closed, consistently outward mesh gives a value near
     * 4 pi / 3 (a flipped or missing triangle shows at once) */
    double vol = 0;
    int outward = 0;
    for (long i = 0; i < m.n_tris; i++) {
        const long *v = m.tris[i].v;
        vec3 a = m.p[v[0]], b = m.p[v[1]], c = m.p[v[2]];
        vol += vec3_dot(a, vec3_cross(b, c)) / 6.0;
        vec3 f = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
        outward += vec3_dot(f, vec3_add(vec3_add(a, b), c)) > 0;
    }
    ck_assert_int_eq(outward, m.n_tris);
    /* inscribed in the unit sphere: a little less than 4 pi / 3 */
    ck_assert_msg(vol > 0.9 * 4 * M_PI / 3 && vol < 4 * M_PI / 3, "volume %g", vol);
    /* closed and consistently wound: every directed edge (a, b) has exactly one (b, a) */
    int unmatched = 0;
    for (long i = 0; i < m.n_tris; i++)
        for (int k = 0; k < 3; k++) {
            long a = m.tris[i].v[k], b = m.tris[i].v[(k + 1) % 3];
            int twins = 0;
            for (long j = 0; j < m.n_tris; j++)
                for (int l = 0; l < 3; l++)
                    twins += m.tris[j].v[l] == b && m.tris[j].v[(l + 1) % 3] == a;
            unmatched += twins != 1;
        }
    ck_assert_int_eq(unmatched, 0);
    for (long k = 0; k < m.n_verts; k++)
        ck_assert_msg(vec3_dot(m.n[k], m.p[k]) > 0.99, "normal of vertex %ld", k);
    displace_mesh_free(&m);
}
END_TEST

START_TEST(test_a_constant_height_grows_the_sphere)
{
    displace_mesh m;
    error err = {0};
    double h = 2;
    ck_assert_int_eq(displace_sphere(4, constant, &h, 0.25, 0, &m, &err), 0);
    for (long k = 0; k < m.n_verts; k++) ck_assert_near(vec3_length(m.p[k]), 1.5, 1e-12);
    displace_mesh_free(&m);
}
END_TEST

START_TEST(test_sphere_corners_at_the_seam_read_s_one_not_zero)
{
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(displace_sphere(3, NULL, NULL, 0, 0, &m, &err), 0);
    int seam = 0;
    for (long i = 0; i < m.n_tris; i++)
        for (int k = 0; k < 3; k++) {
            double s = m.tris[i].st[k].u;
            ck_assert(s >= 0 && s <= 1);
            seam += s == 1.0;
        }
    ck_assert_int_gt(seam, 0);
    /* the last segment's triangles span s in [5/6, 1]: none jumps back across the image */
    for (long i = 0; i < m.n_tris; i++) {
        double lo = 1, hi = 0;
        for (int k = 0; k < 3; k++) {
            lo = fmin(lo, m.tris[i].st[k].u);
            hi = fmax(hi, m.tris[i].st[k].u);
        }
        ck_assert_msg(hi - lo <= 1.0 / 6 + 1e-12, "triangle %ld spans s %g..%g", i, lo, hi);
    }
    displace_mesh_free(&m);
}
END_TEST

/* What the height callback of a triangle sees at each vertex (displace.h): the barycentric
 * interpolation of the corners' st, both coordinates, and the normalized interpolation of the
 * corner normals.  On tri_p, b1 = x / 2 and b2 = y / 2 at vertex (x, y, 0).  The callback
 * records its largest error in the context. */
typedef struct seen {
    const uv2 *st; /* the triangle's corner st (NULL: the sphere's mapping) */
    const vec3 *n; /* the corner normals */
    double err;    /* largest error so far */
    long calls;
} seen;

static double check_triangle_vertex(void *ctx, vec3 p, vec3 n, uv2 st)
{
    seen *c = ctx;
    double b1 = p.x / 2, b2 = p.y / 2, b0 = 1 - b1 - b2;
    double u = b0 * c->st[0].u + b1 * c->st[1].u + b2 * c->st[2].u;
    double v = b0 * c->st[0].v + b1 * c->st[1].v + b2 * c->st[2].v;
    vec3 want = vec3_normalize(vec3_add(vec3_add(vec3_scale(c->n[0], b0), vec3_scale(c->n[1], b1)),
                                        vec3_scale(c->n[2], b2)));
    c->err = fmax(c->err, fmax(fabs(st.u - u), fabs(st.v - v)));
    c->err = fmax(c->err, vec3_length(vec3_sub(n, want)));
    c->calls++;
    return 0.1;
}

START_TEST(test_a_triangles_height_sees_the_interpolated_st_and_normal)
{
    const uv2 st[3] = {{0.1, 0.2}, {0.9, 0.3}, {0.4, 0.8}};
    const vec3 n[3] = {{0, 0, 1}, {0.6, 0, 0.8}, {0, -0.28, 0.96}};
    seen c = {st, n, 0, 0};
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(
        displace_triangle(tri_p, NULL, n, st, 4, check_triangle_vertex, &c, 1, 0, &m, &err), 0);
    ck_assert_int_eq(c.calls, m.n_verts);
    ck_assert_msg(c.err < 1e-15, "the callback saw st or n off by %g", c.err);
    displace_mesh_free(&m);
}
END_TEST

/* The sphere's (s, t) as displace.h defines them: s = phi / 2 pi in [0, 1), t = 1 - theta / pi,
 * (0, 1) at the north pole and (0, 0) at the south pole; p is the unit sphere's point. */
static uv2 sphere_st(vec3 p)
{
    if (p.z >= 1) return (uv2){0, 1};
    if (p.z <= -1) return (uv2){0, 0};
    double phi = atan2(p.y, p.x);
    if (phi < 0) phi += 2 * M_PI;
    double s = phi / (2 * M_PI);
    return (uv2){s >= 1 - 1e-12 ? 0 : s, 1 - acos(p.z) / M_PI};
}

static double check_sphere_vertex(void *ctx, vec3 p, vec3 n, uv2 st)
{
    seen *c = ctx;
    uv2 want = sphere_st(p);
    c->err = fmax(c->err, fmax(fabs(st.u - want.u), fabs(st.v - want.v)));
    c->err = fmax(c->err, vec3_length(vec3_sub(n, p))); /* the unit sphere's normal is p */
    c->calls++;
    return 0;
}

/* The sphere's mapping, at the callback and at every triangle corner: the callback sees each
 * vertex's own (s, t) (poles (0, 1) and (0, 0)); a corner carries the same t and the same s,
 * except s = 1 instead of 0 on the seam's far side, and a pole corner takes the middle s of its
 * segment (the mean of its two other corners').  Catches t flipped (theta / pi), s shifted by a
 * segment, a pole's t, the pole rows' t swapped, and a pole corner at its segment's start. */
START_TEST(test_the_sphere_maps_s_and_t_as_documented_at_vertices_and_corners)
{
    seen c = {NULL, NULL, 0, 0};
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(displace_sphere(5, check_sphere_vertex, &c, 1, 0, &m, &err), 0);
    ck_assert_int_eq(c.calls, m.n_verts);
    ck_assert_msg(c.err < 1e-12, "the callback saw st or n off by %g", c.err);
    for (long i = 0; i < m.n_tris; i++) {
        const displace_tri *tr = &m.tris[i];
        for (int k = 0; k < 3; k++) {
            vec3 p = m.p[tr->v[k]];
            uv2 want = sphere_st(p), got = tr->st[k];
            ck_assert_msg(fabs(got.v - want.v) < 1e-12, "triangle %ld corner %d: t %g, want %g", i,
                          k, got.v, want.v);
            if (fabs(p.z) >= 1) { /* a pole: the middle of the other two corners' s */
                double mid = 0.5 * (tr->st[(k + 1) % 3].u + tr->st[(k + 2) % 3].u);
                ck_assert_msg(fabs(got.u - mid) < 1e-12, "pole corner s %g, want %g", got.u, mid);
            } else if (!(fabs(got.u - want.u) < 1e-12)) {
                ck_assert_msg(want.u == 0 && got.u == 1, "triangle %ld corner %d: s %g, want %g", i,
                              k, got.u, want.u);
            }
        }
    }
    displace_mesh_free(&m);
}
END_TEST

/* Where the corner normals cancel (b0 n0 + b1 n1 = 0 halfway along the edge p0 p1 when
 * n1 = -n0), the vertex moves along corner 0's normal (displace.h), not some fixed axis. */
static double record_normal_at_edge_middle(void *ctx, vec3 p, vec3 n, uv2 st)
{
    (void)st;
    if (p.x == 1 && p.y == 0) *(vec3 *)ctx = n;
    return 0;
}

START_TEST(test_cancelling_corner_normals_fall_back_to_corner_0s)
{
    const vec3 n[3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}};
    vec3 seen_n = {0, 0, 0};
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(displace_triangle(tri_p, NULL, n, tri_st, 2, record_normal_at_edge_middle,
                                       &seen_n, 1, 0, &m, &err),
                     0);
    ck_assert_msg(seen_n.x == 1 && seen_n.y == 0 && seen_n.z == 0, "(%g %g %g)", seen_n.x, seen_n.y,
                  seen_n.z);
    displace_mesh_free(&m);
}
END_TEST

/* The limit is on "more than max_tris triangles" (displace.h): exactly max_tris is allowed. */
START_TEST(test_exactly_max_tris_triangles_is_allowed)
{
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(
        displace_triangle(tri_p, NULL, NULL, tri_st, 100, NULL, NULL, 1, 10000, &m, &err), 0);
    ck_assert_int_eq(m.n_tris, 10000);
    displace_mesh_free(&m);
    ck_assert_int_eq(displace_sphere(10, NULL, NULL, 1, 4 * 10 * 9, &m, &err), 0);
    displace_mesh_free(&m);
    ck_assert_int_eq(displace_sphere(10, NULL, NULL, 1, 4 * 10 * 9 - 1, &m, &err), -1);
}
END_TEST

START_TEST(test_limits_and_bad_input_are_errors_before_allocation)
{
    displace_mesh m;
    error err = {0};
    ck_assert_int_eq(
        displace_triangle(tri_p, NULL, NULL, tri_st, 100, NULL, NULL, 1, 9999, &m, &err), -1);
    ck_assert_ptr_null(m.p);
    ck_assert_int_eq(displace_triangle(tri_p, NULL, NULL, tri_st, 0, NULL, NULL, 1, 0, &m, &err),
                     -1);
    ck_assert_int_eq(displace_sphere(1, NULL, NULL, 1, 0, &m, &err), -1);
    ck_assert_int_eq(displace_sphere(DISPLACE_MAX_RATE, NULL, NULL, 1, 1000, &m, &err), -1);
    ck_assert_ptr_null(m.tris);
    const vec3 line[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    ck_assert_int_eq(displace_triangle(line, NULL, NULL, tri_st, 2, NULL, NULL, 1, 0, &m, &err),
                     -1);
    const vec3 nz[3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    ck_assert_int_eq(displace_triangle(line, NULL, nz, tri_st, 2, NULL, NULL, 1, 0, &m, &err), 0);
    /* every facet of a line has zero area: the vertices keep their normals (displace.h) */
    for (long k = 0; k < m.n_verts; k++)
        ck_assert_msg(m.n[k].x == 0 && m.n[k].y == 0 && m.n[k].z == 1, "vertex %ld", k);
    displace_mesh_free(&m);
}
END_TEST

Suite *displace_suite(void)
{
    Suite *s = suite_create("displace");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_a_triangle_at_rate_n_has_n_squared_triangles_wound_like_the_original);
    tcase_add_test(tc, test_the_height_callback_sees_the_corners_q_interpolated_like_p);
    tcase_add_test(tc, test_a_constant_height_lifts_a_flat_triangle_along_its_normal);
    tcase_add_test(tc, test_a_ramp_height_tilts_the_recomputed_normals);
    tcase_add_test(tc, test_the_sphere_is_closed_outward_and_has_the_documented_counts);
    tcase_add_test(tc, test_a_constant_height_grows_the_sphere);
    tcase_add_test(tc, test_sphere_corners_at_the_seam_read_s_one_not_zero);
    tcase_add_test(tc, test_a_triangles_height_sees_the_interpolated_st_and_normal);
    tcase_add_test(tc, test_the_sphere_maps_s_and_t_as_documented_at_vertices_and_corners);
    tcase_add_test(tc, test_exactly_max_tris_triangles_is_allowed);
    tcase_add_test(tc, test_cancelling_corner_normals_fall_back_to_corner_0s);
    tcase_add_test(tc, test_limits_and_bad_input_are_errors_before_allocation);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(displace_suite)

/* cubemap.c - cube maps: direction <-> (face, s, t), seamless bilinear lookup, cross layouts
 * (see include/envtex/envmaps/cubemap.h). */
#include "envtex/envmaps/cubemap.h"

#include <assert.h>
#include <math.h>

#include "envtex/core/stepcheck.h"

/* (sc, tc, ma) of d for face f: one row of the OpenGL face table (cubemap.h). */
static void face_axes(int f, vec3 d, double *sc, double *tc, double *ma)
{
    switch (f) {
    case CUBEMAP_POS_X:
        *sc = -d.z;
        *tc = -d.y;
        *ma = d.x;
        break;
    case CUBEMAP_NEG_X:
        *sc = d.z;
        *tc = -d.y;
        *ma = d.x;
        break;
    case CUBEMAP_POS_Y:
        *sc = d.x;
        *tc = d.z;
        *ma = d.y;
        break;
    case CUBEMAP_NEG_Y:
        *sc = d.x;
        *tc = -d.z;
        *ma = d.y;
        break;
    case CUBEMAP_POS_Z:
        *sc = d.x;
        *tc = -d.y;
        *ma = d.z;
        break;
    default:
        *sc = -d.x;
        *tc = -d.y;
        *ma = d.z;
        break; /* CUBEMAP_NEG_Z */
    }
}

/* st of d on face f: s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2.  |ma| > 0 by the caller. */
static uv2 face_st(int f, vec3 d)
{
    double sc, tc, ma;
    face_axes(f, d, &sc, &tc, &ma);
    /* STEP(cubemap): a face's coordinates, slide 9 (Environment Map Representations):
     * "divide/renorm by it [the biggest] to get coords", then map them to [0, 1] (cubemap.h) */
    /* STUB: (void)sc; (void)tc; (void)ma; return (uv2){0.5, 0.5}; */
    double m = fabs(ma); /* divide, not multiply by 1/|ma|: 1/|ma| overflows for subnormal d */
    return (uv2){0.5 * (sc / m + 1.0), 0.5 * (tc / m + 1.0)};
    /* END STEP(cubemap) */
}

/* Major axis with the tie rule x before y before z; d non-zero. */
static int major_face(vec3 d)
{
    /* STEP(cubemap): pick the face, slide 9 (Environment Map Representations): "take biggest (abs)
     * of (x,y,z)", its sign choosing + or -; a tie goes to x before y before z (cubemap.h) */
    /* STUB: (void)d; return CUBEMAP_POS_X; */
    double ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
    if (ax >= ay && ax >= az) return d.x > 0 ? CUBEMAP_POS_X : CUBEMAP_NEG_X;
    if (ay >= az) return d.y > 0 ? CUBEMAP_POS_Y : CUBEMAP_NEG_Y;
    return d.z > 0 ? CUBEMAP_POS_Z : CUBEMAP_NEG_Z;
    /* END STEP(cubemap) */
}

int cubemap_dir_to_face(vec3 d, int *face, uv2 *st)
{
    /* "take biggest abs of (x,y,z), divide by it": the ratio sc/|ma| needs no normalizing, and
     * dividing by the largest component cannot overflow or underflow. */
    if (!vec3_is_finite(d) || vec3_max_abs(d) == 0) return -1;
    int f = major_face(d);
    STEPCHECK_INDEX(f, CUBEMAP_FACES, "cubemap", "face");
    uv2 c = face_st(f, d);
    STEPCHECK_COORD(c.u, 0.0, 1.0, "cubemap", "s");
    STEPCHECK_COORD(c.v, 0.0, 1.0, "cubemap", "t");
    *face = f;
    *st = c;
    return 0;
}

/* The point (sc, tc, ma = +-1) on face f's plane, not normalized: the table read backwards. */
static vec3 face_point(int f, uv2 st)
{
    /* STEP(cubemap): the way back, slide 9 (Environment Map Representations): "cubemap coord to
     * vec": the point of face f's plane at (s, t), the caller normalizes it (cubemap.h) */
    /* STUB: (void)f; (void)st; return vec3_make(1, 0, 0); */
    double sc = 2.0 * st.u - 1.0, tc = 2.0 * st.v - 1.0;
    switch (f) {
    case CUBEMAP_POS_X: return vec3_make(1.0, -tc, -sc);
    case CUBEMAP_NEG_X: return vec3_make(-1.0, -tc, sc);
    case CUBEMAP_POS_Y: return vec3_make(sc, 1.0, tc);
    case CUBEMAP_NEG_Y: return vec3_make(sc, -1.0, -tc);
    case CUBEMAP_POS_Z: return vec3_make(sc, -tc, 1.0);
    default: return vec3_make(-sc, -tc, -1.0); /* CUBEMAP_NEG_Z */
    }
    /* END STEP(cubemap) */
}

vec3 cubemap_face_to_dir(int face, uv2 st)
{
    assert(face >= 0 && face < CUBEMAP_FACES);
    return vec3_normalize(face_point(face, st)); /* "cubemap coord to vec: normalize" */
}

int cubemap_alloc(cubemap *cm, int size, error *err)
{
    cm->size = 0;
    for (int f = 0; f < CUBEMAP_FACES; f++) cm->face[f] = (image){0, 0, NULL};
    for (int f = 0; f < CUBEMAP_FACES; f++) {
        if (image_alloc(&cm->face[f], size, size, err)) {
            cubemap_free(cm);
            return error_prefix(err, "cube map face");
        }
    }
    cm->size = size;
    return 0;
}

void cubemap_free(cubemap *cm)
{
    if (!cm) return;
    for (int f = 0; f < CUBEMAP_FACES; f++) image_free(&cm->face[f]);
    cm->size = 0;
}

static int clamp_index(double x, int n)
{
    if (!(x >= 0)) return 0;
    if (x >= n - 1) return n - 1;
    return (int)x;
}

/* Texel (i, j) of face f, where i or j may be one step outside 0..N-1 (seamless fetch). */
static rgb fetch(const cubemap *cm, int f, int i, int j)
{
    int n = cm->size;
    int out_i = i < 0 || i >= n, out_j = j < 0 || j >= n;
    if (!out_i && !out_j) return image_get(&cm->face[f], i, j);
    if (!out_i || !out_j) {
        /* Across one edge: the texel's centre on the plane extended, seen from the cube's
         * centre, falls inside the neighbour texel that shares the edge (its s or t is scaled
         * by N/(N+1), which keeps it within that texel; see cubemap.h). */
        vec3 p = face_point(f, (uv2){(i + 0.5) / n, (j + 0.5) / n});
        int g = major_face(p);
        STEPCHECK_INDEX(g, CUBEMAP_FACES, "cubemap", "face");
        uv2 st = face_st(g, p);
        return image_get(&cm->face[g], clamp_index(floor(st.u * n), n),
                         clamp_index(floor(st.v * n), n));
    }
    /* Beyond a corner: average of the three texels touching the cube corner c = (+-1,+-1,+-1). */
    vec3 c = face_point(f, (uv2){i < 0 ? 0.0 : 1.0, j < 0 ? 0.0 : 1.0});
    rgb sum = rgb_gray(0.0);
    for (int axis = 0; axis < 3; axis++) {
        int g = 2 * axis + (vec3_get(c, axis) < 0);
        uv2 st = face_st(g, c); /* each coordinate exactly 0 or 1 */
        sum = rgb_add(sum, image_get(&cm->face[g], st.u > 0.5 ? n - 1 : 0, st.v > 0.5 ? n - 1 : 0));
    }
    return rgb_scale(sum, 1.0 / 3.0);
}

rgb cubemap_lookup_bilinear(const cubemap *cm, vec3 d)
{
    assert(cm->size > 0);
    int f;
    uv2 st;
    if (cubemap_dir_to_face(d, &f, &st)) return rgb_gray(0.0);
    int n = cm->size;
    /* texel centres sit at (i + 0.5)/N: x = s N - 0.5, x in [-0.5, N - 0.5] */
    double x = st.u * n - 0.5, y = st.v * n - 0.5;
    double x0 = floor(x), y0 = floor(y);
    double fx = x - x0, fy = y - y0;
    int i = (int)x0, j = (int)y0; /* in -1 .. N-1 */
    rgb c00 = fetch(cm, f, i, j), c10 = fetch(cm, f, i + 1, j);
    rgb c01 = fetch(cm, f, i, j + 1), c11 = fetch(cm, f, i + 1, j + 1);
    /* bilinear: (1-fx)(1-fy) c00 + fx (1-fy) c10 + (1-fx) fy c01 + fx fy c11 */
    rgb top = rgb_add(rgb_scale(c00, 1.0 - fx), rgb_scale(c10, fx));
    rgb bottom = rgb_add(rgb_scale(c01, 1.0 - fx), rgb_scale(c11, fx));
    return rgb_add(rgb_scale(top, 1.0 - fy), rgb_scale(bottom, fy));
}

/* ---- cross layouts ------------------------------------------------------------------------ */

typedef struct cross_cell {
    int col, row; /* cell of the face, in face sizes */
    int rot180;   /* 1 if the face is turned by 180 degrees in the cross */
} cross_cell;

static const cross_cell horizontal_cells[CUBEMAP_FACES] = {
    [CUBEMAP_POS_X] = {2, 1, 0}, [CUBEMAP_NEG_X] = {0, 1, 0}, [CUBEMAP_POS_Y] = {1, 0, 0},
    [CUBEMAP_NEG_Y] = {1, 2, 0}, [CUBEMAP_POS_Z] = {1, 1, 0}, [CUBEMAP_NEG_Z] = {3, 1, 0},
};

static const cross_cell vertical_cells[CUBEMAP_FACES] = {
    [CUBEMAP_POS_X] = {2, 1, 0}, [CUBEMAP_NEG_X] = {0, 1, 0}, [CUBEMAP_POS_Y] = {1, 0, 0},
    [CUBEMAP_NEG_Y] = {1, 2, 0}, [CUBEMAP_POS_Z] = {1, 1, 0}, [CUBEMAP_NEG_Z] = {1, 3, 1},
};

/* Cross pixel holding texel (i, j) of a face in `cell`. */
static void cross_pixel(const cross_cell *cell, int n, int i, int j, int *x, int *y)
{
    if (cell->rot180) {
        i = n - 1 - i;
        j = n - 1 - j;
    }
    *x = cell->col * n + i;
    *y = cell->row * n + j;
}

static int split_cross(const image *cross, const cross_cell *cells, int cols, int rows,
                       const char *name, cubemap *cm, error *err)
{
    cm->size = 0;
    for (int f = 0; f < CUBEMAP_FACES; f++) cm->face[f] = (image){0, 0, NULL};
    if (cross->w <= 0 || cross->h <= 0 || cross->w % cols != 0 || cross->h % rows != 0 ||
        cross->w / cols != cross->h / rows)
        return error_set(err, NULL, 0, "a %s cross must be %dN x %dN pixels, not %d x %d", name,
                         cols, rows, cross->w, cross->h);
    int n = cross->w / cols;
    if (cubemap_alloc(cm, n, err)) return -1;
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                int x, y;
                cross_pixel(&cells[f], n, i, j, &x, &y);
                image_set(&cm->face[f], i, j, image_get(cross, x, y));
            }
    return 0;
}

static int join_cross(const cubemap *cm, const cross_cell *cells, int cols, int rows, image *out,
                      error *err)
{
    int n = cm->size;
    assert(n > 0);
    if (image_alloc(out, cols * n, rows * n, err)) return error_prefix(err, "cube map cross");
    for (int f = 0; f < CUBEMAP_FACES; f++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                int x, y;
                cross_pixel(&cells[f], n, i, j, &x, &y);
                image_set(out, x, y, image_get(&cm->face[f], i, j));
            }
    return 0;
}

int cubemap_from_horizontal_cross(const image *cross, cubemap *cm, error *err)
{
    return split_cross(cross, horizontal_cells, 4, 3, "horizontal", cm, err);
}

int cubemap_from_vertical_cross(const image *cross, cubemap *cm, error *err)
{
    return split_cross(cross, vertical_cells, 3, 4, "vertical", cm, err);
}

int cubemap_from_cross(const image *cross, cubemap *cm, error *err)
{
    /* 4:3 without overflow: w * 3 == h * 4, both sides at most IMAGE_MAX_SIDE */
    if ((long)cross->w * 3 == (long)cross->h * 4)
        return cubemap_from_horizontal_cross(cross, cm, err);
    if ((long)cross->w * 4 == (long)cross->h * 3)
        return cubemap_from_vertical_cross(cross, cm, err);
    cm->size = 0;
    for (int f = 0; f < CUBEMAP_FACES; f++) cm->face[f] = (image){0, 0, NULL};
    return error_set(err, NULL, 0,
                     "a %d x %d image is not a cube-map cross (4N x 3N or 3N x 4N pixels)",
                     cross->w, cross->h);
}

int cubemap_to_horizontal_cross(const cubemap *cm, image *out, error *err)
{
    return join_cross(cm, horizontal_cells, 4, 3, out, err);
}

int cubemap_to_vertical_cross(const cubemap *cm, image *out, error *err)
{
    return join_cross(cm, vertical_cells, 3, 4, out, err);
}

/* prefilter.c - irradiance and Phong-lobe maps, and the 9 spherical-harmonic coefficients of an
 * environment (see include/envtex/envlight/prefilter.h). */
#include "envtex/envlight/prefilter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/envmaps/angular.h"
#include "envtex/envmaps/cubemap.h"
#include "envtex/envmaps/cylindrical.h"
#include "envtex/envmaps/equalarea.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/envmaps/mirrorball.h"

/* The basis's constants (prefilter.h), to the last digit of a double. */
#define SH_K0  0.28209479177387814 /* 1 / (2 sqrt pi) */
#define SH_K1  0.4886025119029199  /* sqrt(3 / (4 pi)) */
#define SH_K2  1.0925484305920792  /* sqrt(15 / (4 pi)) */
#define SH_K20 0.31539156525252005 /* sqrt(5 / (16 pi)) */
#define SH_K22 0.5462742152960396  /* sqrt(15 / (16 pi)) */

/* A disc texel's centre outside the disc is pulled this fraction inside the rim (for rounding). */
#define RIM_PULL 1e-9

static const int sh_l[PREFILTER_SH9] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
static const int sh_m[PREFILTER_SH9] = {0, -1, 0, 1, -2, -1, 0, 1, 2};

int prefilter_sh9_l(int k) { return k >= 0 && k < PREFILTER_SH9 ? sh_l[k] : -1; }
int prefilter_sh9_m(int k) { return k >= 0 && k < PREFILTER_SH9 ? sh_m[k] : 0; }

/* ---- the input's texels -------------------------------------------------------------------- */

static int is_rows_kind(convert_kind k)
{
    return k == CONVERT_LATLONG || k == CONVERT_EQUALAREA || k == CONVERT_CYLINDRICAL;
}

/* The direction of texel (c, r) of face f at its centre; a disc texel whose centre is outside
 * the disc at its centre pulled onto the rim.  -1 where the representation holds none. */
static int texel_centre(const convert_env *env, int f, int c, int r, vec3 *d)
{
    const image *im = convert_face_image(env, f);
    uv2 uv = {(c + 0.5) / im->w, (r + 0.5) / im->h};
    switch (env->kind) {
    case CONVERT_LATLONG: *d = latlong_uv_to_dir(uv); return 0;
    case CONVERT_EQUALAREA: *d = equalarea_uv_to_dir(uv); return 0;
    case CONVERT_CYLINDRICAL: return cylindrical_uv_to_dir(uv, env->max_height, d);
    case CONVERT_CUBE: *d = cubemap_face_to_dir(f, uv); return 0;
    case CONVERT_MIRRORBALL:
    case CONVERT_ANGULAR: {
        double a = 2.0 * uv.u - 1.0, b = 1.0 - 2.0 * uv.v, rho = sqrt(a * a + b * b);
        if (rho > 1.0 - RIM_PULL) { /* on or past the rim: pull it in */
            double k = (1.0 - RIM_PULL) / rho;
            uv = (uv2){(a * k + 1.0) / 2.0, (1.0 - b * k) / 2.0};
        }
        if (env->kind == CONVERT_MIRRORBALL) return mirrorball_uv_to_dir(uv, d);
        return angular_uv_to_dir(uv, d);
    }
    default: return -1;
    }
}

/* A map of rows: per row the centre's cos and sin theta and a texel's solid angle, per column
 * the centre's cos and sin phi (one allocation, `mem`). */
typedef struct rows {
    const image *img;
    int w, h;
    double *cos_t, *sin_t, *omega, *cos_p, *sin_p;
    double *mem;
} rows;

static int rows_build(const convert_env *env, rows *rw, error *err)
{
    const image *im = convert_face_image(env, 0);
    int w = im->w, h = im->h;
    memset(rw, 0, sizeof *rw);
    rw->mem = malloc((3 * (size_t)h + 2 * (size_t)w) * sizeof *rw->mem);
    if (!rw->mem) return error_set(err, NULL, 0, "out of memory for a %d x %d map's rows", w, h);
    rw->img = im;
    rw->w = w;
    rw->h = h;
    rw->cos_t = rw->mem;
    rw->sin_t = rw->cos_t + h;
    rw->omega = rw->sin_t + h;
    rw->cos_p = rw->omega + h;
    rw->sin_p = rw->cos_p + w;
    for (int r = 0; r < h; r++) {
        vec3 d = vec3_make(0, 0, 1);
        texel_centre(env, 0, 0, r, &d); /* never fails for these kinds */
        rw->cos_t[r] = d.z;
        rw->sin_t[r] = sqrt(d.x * d.x + d.y * d.y);
        rw->omega[r] = convert_texel_solid_angle(env, 0, 0, r); /* the same along a row */
    }
    for (int c = 0; c < w; c++) {
        double phi = 2.0 * M_PI * (c + 0.5) / w; /* column c's centre, every rows kind */
        rw->cos_p[c] = cos(phi);
        rw->sin_p[c] = sin(phi);
    }
    return 0;
}

static void rows_free(rows *rw)
{
    free(rw->mem);
    memset(rw, 0, sizeof *rw);
}

/* Every texel that holds some of the environment: its centre direction and L dOmega. */
typedef struct texel_list {
    long n;
    double *d;  /* 3 n: unit directions */
    double *lw; /* 3 n: L dOmega per channel */
} texel_list;

static long count_texels(const convert_env *env)
{
    long n = 0;
    for (int f = 0; f < convert_faces(env); f++) {
        const image *im = convert_face_image(env, f);
        n += (long)im->w * im->h;
    }
    return n;
}

static void list_free(texel_list *tl)
{
    free(tl->d);
    free(tl->lw);
    memset(tl, 0, sizeof *tl);
}

static int list_build(const convert_env *env, texel_list *tl, error *err)
{
    long cap = count_texels(env);
    memset(tl, 0, sizeof *tl);
    tl->d = malloc(3 * (size_t)cap * sizeof *tl->d);
    tl->lw = malloc(3 * (size_t)cap * sizeof *tl->lw);
    if (!tl->d || !tl->lw) {
        list_free(tl);
        return error_set(err, NULL, 0, "out of memory for a list of %ld texels", cap);
    }
    for (int f = 0; f < convert_faces(env); f++) {
        const image *im = convert_face_image(env, f);
        for (int r = 0; r < im->h; r++)
            for (int c = 0; c < im->w; c++) {
                vec3 d;
                double om = convert_texel_solid_angle(env, f, c, r);
                if (om == 0 || texel_centre(env, f, c, r, &d)) continue; /* outside the disc */
                d = vec3_normalize(d);
                const float *L = image_px(im, c, r);
                double *pd = tl->d + 3 * tl->n, *pl = tl->lw + 3 * tl->n;
                pd[0] = d.x, pd[1] = d.y, pd[2] = d.z;
                for (int k = 0; k < 3; k++) pl[k] = L[k] * om; /* L dOmega */
                tl->n++;
            }
    }
    return 0;
}

/* ---- spherical harmonics ---------------------------------------------------------------- */

void prefilter_sh9_basis(vec3 d, double y[PREFILTER_SH9])
{
    /* STEP(sh9): the 9 real spherical harmonics at the unit direction d, in Ramamoorthi &
     * Hanrahan's order and with +z up (no slide: Ramamoorthi & Hanrahan 2001; prefilter.h) */
    /* STUB: (void)d; for (int k = 0; k < PREFILTER_SH9; k++) y[k] = 0; */
    double x = d.x, yy = d.y, z = d.z;
    y[0] = SH_K0;                      /* Y00 */
    y[1] = SH_K1 * yy;                 /* Y1-1 */
    y[2] = SH_K1 * z;                  /* Y10 */
    y[3] = SH_K1 * x;                  /* Y11 */
    y[4] = SH_K2 * x * yy;             /* Y2-2 */
    y[5] = SH_K2 * yy * z;             /* Y2-1 */
    y[6] = SH_K20 * (3.0 * z * z - 1); /* Y20 */
    y[7] = SH_K2 * x * z;              /* Y21 */
    y[8] = SH_K22 * (x * x - yy * yy); /* Y22 */
    /* END STEP(sh9) */
}

/* L_lm += L times the integral of Y_lm over one texel, y[k] (row sums in acc, in double) */
static void project_texel(double acc[PREFILTER_SH9][3], const float *L,
                          const double y[PREFILTER_SH9])
{
    /* STEP(sh9): the projection of the map onto the 9 functions: this texel's share of each
     * coefficient L_lm, per channel, from y, the integral of each function over the texel
     * (Ramamoorthi & Hanrahan 2001; prefilter.h) */
    /* STUB: (void)acc; (void)L; (void)y; */
    for (int k = 0; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) acc[k][ch] += L[ch] * y[k];
    /* END STEP(sh9) */
}

static void add_into(prefilter_sh9 *out, double acc[PREFILTER_SH9][3])
{
    for (int k = 0; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) {
            out->L[k][ch] += acc[k][ch];
            acc[k][ch] = 0;
        }
}

/* A rows kind's row edge e (0 .. h) at the top of row e: cos and sin theta, and theta. */
static void row_edge(const convert_env *env, int e, double *z, double *s, double *theta)
{
    const image *im = convert_face_image(env, 0);
    uv2 uv = {0, (double)e / im->h};
    vec3 d = vec3_make(0, 0, 1);
    if (env->kind == CONVERT_LATLONG)
        d = latlong_uv_to_dir(uv);
    else if (env->kind == CONVERT_EQUALAREA)
        d = equalarea_uv_to_dir(uv);
    else
        cylindrical_uv_to_dir(uv, env->max_height, &d); /* v in [0, 1]: never fails */
    *z = d.z;
    *s = sqrt(d.x * d.x + d.y * d.y);
    *theta = env->kind == CONVERT_LATLONG ? M_PI * uv.v : atan2(*s, *z);
}

/* The integrals over row r (z = cos theta from z1 at its bottom edge to z0 at its top) of the
 * z parts of the 9 functions, with s = sqrt(1 - z^2) = sin theta:
 * a[0] = int dz, a[1] = int z dz, a[2] = int s dz, a[3] = int z s dz, a[4] = int s^2 dz,
 * a[5] = int (3 z^2 - 1) dz. */
static void row_integrals(const convert_env *env, int r, double a[6])
{
    double z0, s0, t0, z1, s1, t1;
    row_edge(env, r, &z0, &s0, &t0);
    row_edge(env, r + 1, &z1, &s1, &t1);
    double dz = z0 - z1, zz = z0 * z0 + z0 * z1 + z1 * z1; /* (z0^3 - z1^3) = dz zz */
    a[0] = dz;
    a[1] = dz * (z0 + z1) / 2;
    a[2] = (z0 * s0 - z1 * s1 + (t1 - t0)) / 2; /* (z s + asin z) / 2, asin z = pi / 2 - theta */
    a[3] = (s1 * s1 * s1 - s0 * s0 * s0) / 3;  /* -(1 - z^2)^(3/2) / 3 */
    a[4] = dz * (1 - zz / 3);
    a[5] = dz * (zz - 1);
}

/* The integrals over column c of a w-column map (phi from 2 pi c / w to 2 pi (c + 1) / w) of
 * the phi parts: b[0] = int dphi, b[1] = int cos, b[2] = int sin, b[3] = int cos 2 phi,
 * b[4] = int sin 2 phi. */
static void column_integrals(int c, int w, double b[5])
{
    double p0 = 2.0 * M_PI * c / w, p1 = 2.0 * M_PI * (c + 1) / w;
    b[0] = p1 - p0;
    b[1] = sin(p1) - sin(p0);
    b[2] = cos(p0) - cos(p1);
    b[3] = (sin(2 * p1) - sin(2 * p0)) / 2;
    b[4] = (cos(2 * p0) - cos(2 * p1)) / 2;
}

/* The integral of each of the 9 functions over a texel of a rows kind, exactly, for the map as
 * the light sees it (constant over the texel's rectangle in (cos theta, phi)): from its row's
 * and its column's parts, x = s cos phi, y = s sin phi. */
static void texel_integrals(const double a[6], const double b[5], double y[PREFILTER_SH9])
{
    y[0] = SH_K0 * a[0] * b[0];       /* Y00 */
    y[1] = SH_K1 * a[2] * b[2];       /* Y1-1: y */
    y[2] = SH_K1 * a[1] * b[0];       /* Y10: z */
    y[3] = SH_K1 * a[2] * b[1];       /* Y11: x */
    y[4] = SH_K2 * a[4] * b[4] / 2;   /* Y2-2: x y = s^2 sin 2 phi / 2 */
    y[5] = SH_K2 * a[3] * b[2];       /* Y2-1: y z */
    y[6] = SH_K20 * a[5] * b[0];      /* Y20: 3 z^2 - 1 */
    y[7] = SH_K2 * a[3] * b[1];       /* Y21: x z */
    y[8] = SH_K22 * a[4] * b[3];      /* Y22: x^2 - y^2 = s^2 cos 2 phi */
}

int prefilter_sh9_project(const convert_env *env, prefilter_sh9 *out, error *err)
{
    memset(out, 0, sizeof *out);
    double acc[PREFILTER_SH9][3] = {{0}}, y[PREFILTER_SH9];
    if (is_rows_kind(env->kind)) { /* exact: per row and per column integrals */
        const image *im = convert_face_image(env, 0);
        double (*b)[5] = malloc((size_t)im->w * sizeof *b);
        if (!b) return error_set(err, NULL, 0, "out of memory for a %d-wide map's columns", im->w);
        for (int c = 0; c < im->w; c++) column_integrals(c, im->w, b[c]);
        for (int r = 0; r < im->h; r++) {
            double a[6];
            row_integrals(env, r, a);
            for (int c = 0; c < im->w; c++) {
                texel_integrals(a, b[c], y);
                project_texel(acc, image_px(im, c, r), y);
            }
            add_into(out, acc); /* a row at a time: the long sum in double, in row sums */
        }
        free(b);
        return 0;
    }
    for (int f = 0; f < convert_faces(env); f++) { /* the others: at each texel's centre */
        const image *im = convert_face_image(env, f);
        for (int r = 0; r < im->h; r++) {
            for (int c = 0; c < im->w; c++) {
                vec3 w;
                double om = convert_texel_solid_angle(env, f, c, r);
                if (om == 0 || texel_centre(env, f, c, r, &w)) continue; /* outside the disc */
                prefilter_sh9_basis(vec3_normalize(w), y);
                for (int k = 0; k < PREFILTER_SH9; k++) y[k] *= om; /* Y_lm(w) dOmega */
                project_texel(acc, image_px(im, c, r), y);
            }
            add_into(out, acc);
        }
    }
    return 0;
}

rgb prefilter_sh9_irradiance(const prefilter_sh9 *sh, vec3 n)
{
    /* STEP(sh9): the irradiance at the normal n from the 9 coefficients, per channel: a convolution
     * with the clamped cosine is a product in spherical harmonics (Ramamoorthi & Hanrahan 2001;
     * prefilter.h) */
    /* STUB: (void)sh; (void)n; return rgb_gray(0); */
    static const double A[3] = {M_PI, 2.0 * M_PI / 3.0, M_PI / 4.0}; /* A_l, l = 0, 1, 2 */
    double y[PREFILTER_SH9], e[3] = {0, 0, 0};
    prefilter_sh9_basis(n, y);
    for (int k = 0; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) e[ch] += A[sh_l[k]] * sh->L[k][ch] * y[k];
    return rgb_make(e[0], e[1], e[2]);
    /* END STEP(sh9) */
}

void prefilter_sh9_matrix(const prefilter_sh9 *sh, prefilter_sh9_quadratic *q)
{
    /* STEP(sh9): the same irradiance as a quadratic form in (n, 1): Ramamoorthi & Hanrahan 2001's
     * symmetric 4 x 4 matrix per channel, their equation 12 (prefilter.h) */
    /* STUB: (void)sh; memset(q, 0, sizeof *q); */
    const double c1 = M_PI / 4.0 * SH_K2 / 2.0, c2 = 2.0 * M_PI / 3.0 * SH_K1 / 2.0;
    const double c3 = 3.0 * M_PI / 4.0 * SH_K20, c4 = M_PI * SH_K0, c5 = M_PI / 4.0 * SH_K20;
    for (int ch = 0; ch < 3; ch++) {
        const double L00 = sh->L[0][ch], L1m1 = sh->L[1][ch], L10 = sh->L[2][ch];
        const double L11 = sh->L[3][ch];
        const double L2m2 = sh->L[4][ch], L2m1 = sh->L[5][ch], L20 = sh->L[6][ch];
        const double L21 = sh->L[7][ch], L22 = sh->L[8][ch];
        const double m[4][4] = {{c1 * L22, c1 * L2m2, c1 * L21, c2 * L11},
                                {c1 * L2m2, -c1 * L22, c1 * L2m1, c2 * L1m1},
                                {c1 * L21, c1 * L2m1, c3 * L20, c2 * L10},
                                {c2 * L11, c2 * L1m1, c2 * L10, c4 * L00 - c5 * L20}};
        memcpy(q->m[ch], m, sizeof m);
    }
    /* END STEP(sh9) */
}

rgb prefilter_sh9_quadratic_eval(const prefilter_sh9_quadratic *q, vec3 n)
{
    const double v[4] = {n.x, n.y, n.z, 1.0};
    double e[3];
    for (int ch = 0; ch < 3; ch++) {
        double s = 0;
        for (int i = 0; i < 4; i++) {
            double row = 0;
            for (int j = 0; j < 4; j++) row += q->m[ch][i][j] * v[j];
            s += v[i] * row; /* (n, 1)^T M (n, 1) */
        }
        e[ch] = s;
    }
    return rgb_make(e[0], e[1], e[2]);
}

/* ---- output maps --------------------------------------------------------------------------- */

int prefilter_check_width(long width, error *err)
{
    if (width < 2 || width > PREFILTER_MAX_WIDTH || width % 2)
        return error_set(err, NULL, 0,
                         "the map's width must be an even number from 2 to %d, "
                         "got %ld",
                         PREFILTER_MAX_WIDTH, width);
    return 0;
}

/* The W x W/2 output in *out and the direction of its texel (c, r) at its centre. */
static int alloc_map(int width, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (prefilter_check_width(width, err)) return -1;
    return image_alloc(out, width, width / 2, err);
}

static vec3 map_dir(const image *out, int c, int r)
{
    return latlong_uv_to_dir((uv2){(c + 0.5) / out->w, (r + 0.5) / out->h});
}

int prefilter_irradiance_sh9(const prefilter_sh9 *sh, int width, image *out, error *err)
{
    if (alloc_map(width, out, err)) return -1;
    for (int r = 0; r < out->h; r++)
        for (int c = 0; c < out->w; c++)
            image_set(out, c, r,
                      rgb_scale(prefilter_sh9_irradiance(sh, map_dir(out, c, r)), 1.0 / M_PI));
    return 0;
}

/* t^S, t = r . w > 0: by squaring when S is whole (si = S; within a few ulps of pow), else pow */
static double pow_s(double t, double s, long si)
{
    if (si < 0) return pow(t, s);
    double p = 1.0;
    for (double b = t; si; si >>= 1, b *= b)
        if (si & 1) p *= b;
    return p;
}

static long whole_exponent(double s) { return s == floor(s) && s <= 2147483647.0 ? (long)s : -1; }

/* The kernels of the plain sums, at t = n . w > 0: max(0, n . w) / pi for irradiance (s is
 * not used), (S + 1) / (2 pi) (r . w)^S for the Phong lobe of exponent s. */
typedef double (*brute_kernel)(double cos_t, double s);
static double cosine_kernel(double t, double s) { return (void)s, t / M_PI; }
static double phong_kernel(double t, double s) { return (s + 1.0) / (2.0 * M_PI) * pow(t, s); }

/* The plain sums of prefilter_irradiance_brute and prefilter_phong_brute: every output texel
 * against every input texel, weighted by kernel. */
static int brute(const convert_env *env, brute_kernel kernel, double s, int width, image *out,
                 error *err)
{
    texel_list tl;
    if (alloc_map(width, out, err)) return -1;
    if (list_build(env, &tl, err)) {
        image_free(out);
        return -1;
    }
    for (int r = 0; r < out->h; r++)
        for (int c = 0; c < out->w; c++) {
            vec3 n = map_dir(out, c, r); /* the normal, or the lobe's axis r */
            double e[3] = {0, 0, 0};
            for (long t = 0; t < tl.n; t++) {
                const double *d = tl.d + 3 * t, *lw = tl.lw + 3 * t;
                double cos_t = n.x * d[0] + n.y * d[1] + n.z * d[2]; /* n . w */
                if (!(cos_t > 0)) continue;
                double k = kernel(cos_t, s);
                for (int ch = 0; ch < 3; ch++) e[ch] += lw[ch] * k;
            }
            image_set(out, c, r, rgb_make(e[0], e[1], e[2]));
        }
    list_free(&tl);
    return 0;
}

int prefilter_irradiance_brute(const convert_env *env, int width, image *out, error *err)
{
    return brute(env, cosine_kernel, 0, width, out, err);
}

static int check_shininess(double s, error *err)
{
    if (!(s >= 0 && s <= PREFILTER_MAX_SHININESS))
        return error_set(err, NULL, 0, "the Phong exponent must be a number from 0 to %g, got %g",
                         PREFILTER_MAX_SHININESS, s);
    return 0;
}

int prefilter_phong_brute(const convert_env *env, double s, int width, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (check_shininess(s, err)) return -1;
    return brute(env, phong_kernel, s, width, out, err);
}

/* ---- the fast exact sums over a map of rows ------------------------------------------------ */

/* The columns k of a w-column row with |k + 0.5 - x| <= half (x, half in columns): n of them
 * from *start on, wrapping round the row (the whole row: start 0, n = w).  Returns n. */
static int arc_columns(double x, double half, int w, int *start)
{
    *start = 0;
    if (half >= 0.5 * w) return w;
    long k0 = (long)ceil(x - half - 0.5), k1 = (long)floor(x + half - 0.5);
    if (k1 < k0) return 0;
    long n = k1 - k0 + 1, s = k0 % w;
    *start = (int)(s < 0 ? s + w : s);
    return n > w ? w : (int)n;
}

/* On an input row at (cos, sin) theta = (ct, st), the output direction at (ctn, stn) sees
 * r . w = a + b cos(phi - phi_n), a = ctn ct, b = stn st >= 0.  Above c it is on the columns
 * within half columns of phi_n: 0 if none (a + b <= c), the whole row if a - b > c. */
static int arc_half_width(double a, double b, double c, int w, double *half)
{
    if (!(a + b > c)) return 0;
    if (a - b > c || !(b > 0))
        *half = w;
    else
        *half = acos((c - a) / b) * w / (2.0 * M_PI); /* cos(dphi) = (c - a) / b in [-1, 1) */
    return 1;
}

/* Running sums over row r of L, L cos phi and L sin phi: pre[9 k + 3 q + ch] is the sum over
 * the first k columns (k = 0..w), q = 0, 1, 2 (the nine of a k side by side). */
static void row_running_sums(const rows *rw, int r, double *pre)
{
    for (int q = 0; q < 9; q++) pre[q] = 0;
    for (int k = 0; k < rw->w; k++) {
        const float *L = image_px(rw->img, k, r);
        const double f[3] = {1.0, rw->cos_p[k], rw->sin_p[k]};
        double *p = pre + 9 * (size_t)k;
        for (int q = 0; q < 3; q++)
            for (int ch = 0; ch < 3; ch++) p[9 + 3 * q + ch] = p[3 * q + ch] + L[ch] * f[q];
    }
}

/* The output map's directions: per row cos and sin theta, per column cos and sin phi. */
static double *out_trig(int wo, int ho, error *err)
{
    double *t = malloc((2 * (size_t)ho + 2 * (size_t)wo) * sizeof *t);
    if (!t) {
        error_set(err, NULL, 0, "out of memory for a %d x %d map", wo, ho);
        return NULL;
    }
    for (int i = 0; i < ho; i++) {
        t[i] = cos(M_PI * (i + 0.5) / ho);
        t[ho + i] = sin(M_PI * (i + 0.5) / ho);
    }
    for (int j = 0; j < wo; j++) {
        t[2 * ho + j] = cos(2.0 * M_PI * (j + 0.5) / wo);
        t[2 * ho + wo + j] = sin(2.0 * M_PI * (j + 0.5) / wo);
    }
    return t;
}

/* Input row r's share of E at every output texel, into acc (3 per texel): on the arc where
 * n . w > 0 the row's sum of L (a + b cos(phi - phi_n)) dOmega is
 * (a S0 + b (cos phi_n Sc + sin phi_n Ss)) dOmega, from the running sums. */
static void arcs_row(const rows *rw, int r, const double *pre, const double *tr, int wo, int ho,
                     double *acc)
{
    int wi = rw->w;
    const double *ctn = tr, *stn = tr + ho, *cpn = tr + 2 * ho, *spn = cpn + wo;
    for (int i = 0; i < ho; i++) {
        double a = ctn[i] * rw->cos_t[r], b = stn[i] * rw->sin_t[r], half;
        if (!arc_half_width(a, b, 0.0, wi, &half)) continue; /* the row is below the horizon */
        for (int j = 0; j < wo; j++) {
            int k0, n = arc_columns(wi * (j + 0.5) / wo, half, wi, &k0);
            int k1 = k0 + n < wi ? k0 + n : wi, wrap = k0 + n - k1; /* [k0, k1) and [0, wrap) */
            double *e = acc + 3 * ((size_t)i * wo + j);
            const double *p1 = pre + 9 * (size_t)k1, *p0 = pre + 9 * (size_t)k0;
            const double *pw = pre + 9 * (size_t)wrap;
            for (int ch = 0; ch < 3; ch++) {
                double S[3] = {0, 0, 0}; /* sums of L, L cos phi, L sin phi over the arc */
                for (int q = 0; q < 3; q++) {
                    int x = 3 * q + ch;
                    S[q] = p1[x] - p0[x] + pw[x] - pre[x]; /* [k0, k1) and [0, wrap) */
                }
                double v = a * S[0] + b * (cpn[j] * S[1] + spn[j] * S[2]);
                if (v > 0) e[ch] += v * rw->omega[r]; /* (rounding can leave a tiny negative) */
            }
        }
    }
}

/* acc (3 doubles a texel) times k into the float map */
static void store_scaled(image *out, const double *acc, double k)
{
    for (int r = 0; r < out->h; r++)
        for (int c = 0; c < out->w; c++) {
            const double *e = acc + 3 * ((size_t)r * out->w + c);
            image_set(out, c, r, rgb_make(e[0] * k, e[1] * k, e[2] * k));
        }
}

int prefilter_irradiance_arcs(const convert_env *env, int width, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (!is_rows_kind(env->kind))
        return error_set(err, NULL, 0,
                         "the arc sums need a map of rows (lat-long, equal-area or "
                         "cylindrical), not %s",
                         convert_kind_name(env->kind));
    if (alloc_map(width, out, err)) return -1;
    rows rw;
    if (rows_build(env, &rw, err)) {
        image_free(out);
        return -1;
    }
    int wo = out->w, ho = out->h, status = -1;
    double *acc = calloc(3 * (size_t)wo * ho, sizeof *acc);
    double *pre = malloc(9 * ((size_t)rw.w + 1) * sizeof *pre);
    double *tr = out_trig(wo, ho, err);
    if (!acc || !pre) error_set(err, NULL, 0, "out of memory for the sums of a %d-wide map", rw.w);
    if (acc && pre && tr) {
        for (int r = 0; r < rw.h; r++) {
            row_running_sums(&rw, r, pre);
            arcs_row(&rw, r, pre, tr, wo, ho, acc);
        }
        store_scaled(out, acc, 1.0 / M_PI); /* E / pi */
        status = 0;
    }
    free(acc);
    free(pre);
    free(tr);
    rows_free(&rw);
    if (status) image_free(out);
    return status;
}

/* ---- exact maps, with their cost checked first ------------------------------------------- */

static int refuse_work(const convert_env *env, const char *what, int width, double work,
                       double limit, error *err)
{
    const image *im = convert_face_image(env, 0);
    return error_set(err, NULL, 0,
                     "%s %d x %d map from this %s map (%d x %d%s) would evaluate its "
                     "kernel %.3g times, over the limit of %.3g: use a smaller --width, or a "
                     "smaller input (envtex convert IN small.exr --to latlong --width W)",
                     what, width, width / 2, convert_kind_name(env->kind), im->w, im->h,
                     env->kind == CONVERT_CUBE ? " a face" : "", work, limit);
}

int prefilter_irradiance_exact(const convert_env *env, int width, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (prefilter_check_width(width, err)) return -1;
    if (is_rows_kind(env->kind)) return prefilter_irradiance_arcs(env, width, out, err);
    double work = (double)width * (width / 2) * (double)count_texels(env);
    if (work > PREFILTER_MAX_LIST_WORK)
        return refuse_work(env, "an exact irradiance", width, work, PREFILTER_MAX_LIST_WORK, err);
    return prefilter_irradiance_brute(env, width, out, err);
}

/* The cosine below which prefilter_phong leaves texels out: c^S = DROP / (2 (S + 1)). */
static double phong_cut(double s)
{
    if (!(s > 0)) return 0.0; /* S = 0: the hemisphere, nothing to leave out */
    return pow(PREFILTER_PHONG_DROP / (2.0 * (s + 1.0)), 1.0 / s);
}

/* The Phong sum over a map of rows.  Output column j and input column k see the same
 * phi_k - phi_j as j + p and k + q, where g = gcd(W_in, W_out), p = W_out / g, q = W_in / g:
 * so for each output row and input row the kernel is computed once for the p columns
 * j < p, and the other columns reuse it shifted by q input columns (p = 1 when W_out divides
 * W_in: the kernel once per input column instead of once per pair). */
typedef struct phong_job {
    const rows *rw;
    double s, cut;
    long si; /* whole_exponent(s) */
    int wo, ho, p, q, g;
    const double *tr; /* out_trig */
    double *kern;     /* W_in: the kernel over one arc */
    double *acc;      /* 3 per output texel */
} phong_job;

static int gcd(int a, int b) { return b ? gcd(b, a % b) : a; }

/* e += sum over m in [m0, m1) of L(column c0 + m - m0) kern[m] (even and odd m summed apart) */
static void dot_span(const float *L, const double *kern, int m0, int m1, double e[3])
{
    double a0 = 0, a1 = 0, a2 = 0, b0 = 0, b1 = 0, b2 = 0;
    int m = m0;
    for (; m + 1 < m1; m += 2, L += 6) {
        a0 += L[0] * kern[m], a1 += L[1] * kern[m], a2 += L[2] * kern[m];
        b0 += L[3] * kern[m + 1], b1 += L[4] * kern[m + 1], b2 += L[5] * kern[m + 1];
    }
    if (m < m1) a0 += L[0] * kern[m], a1 += L[1] * kern[m], a2 += L[2] * kern[m];
    e[0] += a0 + b0, e[1] += a1 + b1, e[2] += a2 + b2;
}

/* sum over m < n of L(column (k0 + m) mod w, row r) kern[m], per channel, added to e */
static void arc_dot(const image *img, int r, int k0, int n, const double *kern, double e[3])
{
    int n1 = n < img->w - k0 ? n : img->w - k0;
    dot_span(image_px(img, k0, r), kern, 0, n1, e);
    dot_span(image_px(img, 0, r), kern, n1, n, e); /* the arc wraps past the last column */
}

/* Row r's share of each Phong texel: sum L (r . w)^S dOmega where r . w > c ((S+1)/2pi later) */
static void phong_row(phong_job *job, int r)
{
    const rows *rw = job->rw;
    int wi = rw->w, wo = job->wo, ho = job->ho;
    const double *ctn = job->tr, *stn = ctn + ho, *cpn = ctn + 2 * ho, *spn = cpn + wo;
    for (int i = 0; i < ho; i++) {
        double a = ctn[i] * rw->cos_t[r], b = stn[i] * rw->sin_t[r], half;
        if (!arc_half_width(a, b, job->cut, wi, &half)) continue; /* the lobe misses the row */
        for (int j0 = 0; j0 < job->p; j0++) {
            int k0, n = arc_columns(wi * (j0 + 0.5) / wo, half, wi, &k0);
            double bc = b * cpn[j0], bs = b * spn[j0];
            for (int m = 0; m < n; m++) {
                int k = k0 + m < wi ? k0 + m : k0 + m - wi;
                double t = a + bc * rw->cos_p[k] + bs * rw->sin_p[k]; /* r . w */
                job->kern[m] = t > job->cut ? pow_s(t, job->s, job->si) : 0.0;
            }
            for (int sh = 0; sh < job->g; sh++) { /* output column j0 + sh p, input k + sh q */
                int j = j0 + sh * job->p, ks = (int)(((long)k0 + (long)sh * job->q) % wi);
                double e[3] = {0, 0, 0}, *o = job->acc + 3 * ((size_t)i * wo + j);
                arc_dot(rw->img, r, ks, n, job->kern, e);
                for (int ch = 0; ch < 3; ch++) o[ch] += e[ch] * rw->omega[r];
            }
        }
    }
}

static int phong_rows(const convert_env *env, double s, double cut, image *out, error *err)
{
    rows rw;
    if (rows_build(env, &rw, err)) return -1;
    phong_job job = {&rw, s, cut, whole_exponent(s), out->w, out->h, 0, 0, 0, NULL, NULL, NULL};
    job.g = gcd(rw.w, out->w);
    job.p = out->w / job.g;
    job.q = rw.w / job.g;
    int status = -1;
    job.acc = calloc(3 * (size_t)out->w * out->h, sizeof *job.acc);
    job.kern = malloc((size_t)rw.w * sizeof *job.kern);
    double *tr = out_trig(out->w, out->h, err);
    job.tr = tr;
    if (!job.acc || !job.kern)
        error_set(err, NULL, 0, "out of memory for a %d x %d map", out->w, out->h);
    if (job.acc && job.kern && tr) {
        for (int r = 0; r < rw.h; r++) phong_row(&job, r);
        store_scaled(out, job.acc, (s + 1.0) / (2.0 * M_PI));
        status = 0;
    }
    free(job.acc);
    free(job.kern);
    free(tr);
    rows_free(&rw);
    return status;
}

/* Any other kind: every texel of the list against every output texel, those above the cut. */
static int phong_list(const convert_env *env, double s, double cut, image *out, error *err)
{
    texel_list tl;
    if (list_build(env, &tl, err)) return -1;
    long si = whole_exponent(s);
    for (int r = 0; r < out->h; r++)
        for (int c = 0; c < out->w; c++) {
            vec3 n = map_dir(out, c, r);
            double e[3] = {0, 0, 0};
            for (long t = 0; t < tl.n; t++) {
                const double *d = tl.d + 3 * t, *lw = tl.lw + 3 * t;
                double cos_t = n.x * d[0] + n.y * d[1] + n.z * d[2]; /* r . w */
                if (!(cos_t > cut)) continue;
                double p = pow_s(cos_t, s, si);
                for (int ch = 0; ch < 3; ch++) e[ch] += lw[ch] * p;
            }
            double k = (s + 1.0) / (2.0 * M_PI);
            image_set(out, c, r, rgb_make(e[0] * k, e[1] * k, e[2] * k));
        }
    list_free(&tl);
    return 0;
}

int prefilter_phong(const convert_env *env, double s, int width, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (check_shininess(s, err) || prefilter_check_width(width, err)) return -1;
    double cut = phong_cut(s), texels = (double)count_texels(env);
    /* the rows kinds visit the cap r . w > c, (1 - c) / 2 of the sphere; the others every texel */
    int by_rows = is_rows_kind(env->kind);
    double work = (double)width * (width / 2) * texels * (by_rows ? (1 - cut) / 2 : 1);
    double limit = by_rows ? PREFILTER_MAX_ROW_WORK : PREFILTER_MAX_LIST_WORK;
    if (work > limit) return refuse_work(env, "a Phong", width, work, limit, err);
    if (alloc_map(width, out, err)) return -1;
    int rc = by_rows ? phong_rows(env, s, cut, out, err) : phong_list(env, s, cut, out, err);
    if (rc) image_free(out);
    return rc;
}

int prefilter_phong_width(double s)
{
    double want = 4.0 * M_PI * sqrt(s > 0 ? s : 0); /* two texels across a lobe of 1 / sqrt(S) */
    int w = 64;
    while (w < want && w < 1024) w *= 2;
    return w;
}

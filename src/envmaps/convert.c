/* convert.c - an environment in any representation: lookup, texel solid angles, power, and
 * solid-angle-averaged resampling (see include/envtex/envmaps/convert.h). */
#include "envtex/envmaps/convert.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/envmaps/angular.h"
#include "envtex/envmaps/cylindrical.h"
#include "envtex/envmaps/equalarea.h"
#include "envtex/io/imageio.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/envmaps/mirrorball.h"

/* Below this disc radius the angular map's Jacobian pi sin(pi rho) / rho is replaced by its
 * limit pi^2: sin(pi rho) / rho loses nothing there (relative error ~ (pi rho)^2 / 6 < 1e-23),
 * and rho = 0 exactly would divide by zero. */
#define ANGULAR_RHO_EPS 1e-12

/* A rim texel of a disc output that meets the disc but none of whose K x K points falls inside
 * it is looked up at its point nearest the centre, pulled this fraction inwards so that it is
 * inside despite rounding (mirrorball_uv_to_dir allows 1e-15 of slack). */
#define DISC_PULL 1e-9

/* Sub-cells per side of the midpoint rule for an angular texel's solid angle (no closed form):
 * ceil(ANGULAR_OMEGA_SPAN / size) clamped to [4, 16], so the sub-cells are about 1/256 of the
 * disc's diameter or finer from 16 x 16 up (a smaller disc gets 16 per texel: 112 across at
 * 7 x 7).  Measured, the whole disc sums to 4 pi within (relative) 5.5e-6 at 8 x 8, 3.6e-6 at
 * 9 x 9, 1.1e-6 at 33 x 33, 3.3e-8 at 128 x 128, 1.5e-7 at 130 x 130: within 6e-6 from 7 x 7 up
 * and 1.5e-7 from 128 x 128 up, not monotone in the size. */
#define ANGULAR_OMEGA_SPAN      256
#define ANGULAR_OMEGA_MIN_STEPS 4
#define ANGULAR_OMEGA_MAX_STEPS 16

static const char *const kind_names[CONVERT_KINDS] = {"latlong", "cube",        "mirrorball",
                                                      "angular", "cylindrical", "equalarea"};

/* ---- kinds -------------------------------------------------------------------------------- */

int convert_kind_parse(const char *word, convert_kind *kind)
{
    if (!word) return -1;
    if (strcmp(word, "cross") == 0) {
        *kind = CONVERT_CUBE;
        return 0;
    }
    for (int k = 0; k < CONVERT_KINDS; k++)
        if (strcmp(word, kind_names[k]) == 0) {
            *kind = (convert_kind)k;
            return 0;
        }
    return -1;
}

const char *convert_kind_name(convert_kind kind)
{
    return kind >= 0 && kind < CONVERT_KINDS ? kind_names[kind] : "unknown";
}

int convert_kind_detect(int w, int h, convert_kind *kind, error *err)
{
    long lw = w, lh = h;
    if (lw >= 1 && lh >= 1) {
        if (lw == 2 * lh) {
            *kind = CONVERT_LATLONG;
            return 0;
        }
        if (3 * lw == 4 * lh || 4 * lw == 3 * lh) {
            *kind = CONVERT_CUBE;
            return 0;
        }
    }
    if (lw == lh)
        return error_set(err, NULL, 0,
                         "a square image (%d x %d) could be a mirror ball or an angular map: "
                         "name it (mirrorball, angular, cube, cross, latlong, cylindrical, "
                         "equalarea)",
                         w, h);
    return error_set(err, NULL, 0,
                     "cannot tell the representation of a %d x %d image (2:1 is lat-long, 4:3 "
                     "or 3:4 a cube cross): name it (latlong, cross, mirrorball, angular, "
                     "cylindrical, equalarea)",
                     w, h);
}

double convert_cylindrical_height(int w, int h)
{
    if (w < 1 || h < 1) return 0;
    return M_PI * h / w; /* 2 h / H = 2 pi / W: square texels on the horizon */
}

convert_env convert_view(const convert_map *m)
{
    convert_env e;
    e.kind = m->kind;
    e.img = m->kind == CONVERT_CUBE ? NULL : &m->img;
    e.cube = m->kind == CONVERT_CUBE ? &m->cube : NULL;
    e.max_height = m->max_height;
    return e;
}

void convert_map_free(convert_map *m)
{
    if (!m) return;
    image_free(&m->img);
    cubemap_free(&m->cube);
    memset(m, 0, sizeof *m);
}

int convert_faces(const convert_env *env) { return env->kind == CONVERT_CUBE ? CUBEMAP_FACES : 1; }

const image *convert_face_image(const convert_env *env, int face)
{
    assert(face >= 0 && face < convert_faces(env));
    return env->kind == CONVERT_CUBE ? &env->cube->face[face] : env->img;
}

/* ---- lookups ------------------------------------------------------------------------------ */

/* Does texel (i, j) of a w x h disc image meet the unit disc?  Its square in disc coordinates
 * is a in [2i/w - 1, 2(i+1)/w - 1], b in [1 - 2(j+1)/h, 1 - 2j/h]; the point of it nearest the
 * centre is each interval clamped to 0. */
static int disc_texel_valid(int i, int j, int w, int h)
{
    double a0 = 2.0 * i / w - 1.0, a1 = 2.0 * (i + 1) / w - 1.0;
    double b0 = 1.0 - 2.0 * (j + 1) / h, b1 = 1.0 - 2.0 * j / h;
    double a = a0 > 0 ? a0 : (a1 < 0 ? a1 : 0.0);
    double b = b0 > 0 ? b0 : (b1 < 0 ? b1 : 0.0);
    return a * a + b * b < 1.0;
}

/* (u, v) of the point of texel (i, j)'s square nearest the disc's centre, pulled inwards by
 * DISC_PULL. */
static uv2 disc_nearest_uv(int i, int j, int w, int h)
{
    double a0 = 2.0 * i / w - 1.0, a1 = 2.0 * (i + 1) / w - 1.0;
    double b0 = 1.0 - 2.0 * (j + 1) / h, b1 = 1.0 - 2.0 * j / h;
    double a = a0 > 0 ? a0 : (a1 < 0 ? a1 : 0.0);
    double b = b0 > 0 ? b0 : (b1 < 0 ? b1 : 0.0);
    a *= 1.0 - DISC_PULL;
    b *= 1.0 - DISC_PULL;
    return (uv2){(a + 1.0) / 2.0, (1.0 - b) / 2.0};
}

/* Bilinear lookup at (u, v) of a disc image over the texels that meet the disc:
 * L = sum_k w_k [valid_k] c_k / sum_k w_k [valid_k]; black if none is valid.  Clamped at the
 * image edges like mirrorball_lookup_bilinear. */
static rgb disc_lookup(const image *im, uv2 uv)
{
    int w = im->w, h = im->h;
    double x = uv.u * w - 0.5, y = uv.v * h - 0.5; /* texel centres at integers */
    double fx = floor(x), fy = floor(y);
    double ax = x - fx, ay = y - fy;
    int i[2] = {(int)fx, (int)fx + 1}, j[2] = {(int)fy, (int)fy + 1};
    double wx[2] = {1.0 - ax, ax}, wy[2] = {1.0 - ay, ay};
    for (int k = 0; k < 2; k++) {
        if (i[k] < 0) i[k] = 0;
        if (i[k] > w - 1) i[k] = w - 1;
        if (j[k] < 0) j[k] = 0;
        if (j[k] > h - 1) j[k] = h - 1;
    }
    rgb sum = rgb_gray(0);
    double wsum = 0;
    for (int b = 0; b < 2; b++)
        for (int a = 0; a < 2; a++) {
            double wt = wx[a] * wy[b];
            if (wt == 0 || !disc_texel_valid(i[a], j[b], w, h)) continue;
            sum = rgb_madd(sum, image_get(im, i[a], j[b]), wt);
            wsum += wt;
        }
    return wsum > 0 ? rgb_scale(sum, 1.0 / wsum) : rgb_gray(0); /* guard: no texel meets the disc */
}

rgb convert_lookup(const convert_env *env, vec3 d)
{
    uv2 uv;
    switch (env->kind) {
    case CONVERT_LATLONG: return latlong_lookup_bilinear(env->img, d);
    case CONVERT_CUBE: return cubemap_lookup_bilinear(env->cube, d);
    case CONVERT_MIRRORBALL:
        if (mirrorball_dir_to_uv(d, &uv)) return rgb_gray(0);
        return disc_lookup(env->img, uv);
    case CONVERT_ANGULAR:
        if (angular_dir_to_uv(d, &uv)) return rgb_gray(0);
        return disc_lookup(env->img, uv);
    case CONVERT_CYLINDRICAL: return cylindrical_lookup_bilinear(env->img, env->max_height, d);
    case CONVERT_EQUALAREA: return equalarea_lookup_bilinear(env->img, d);
    default: assert(!"convert_lookup: bad kind"); return rgb_gray(0);
    }
}

/* ---- solid angles ------------------------------------------------------------------------- */

/* Area of {0 <= s <= x, 0 <= t <= y, s^2 + t^2 <= 1} for x, y >= 0: the rectangle's part of
 * the unit disc's first quadrant.  Past the point s* = sqrt(1 - y^2) the circle is the lower
 * of the two bounds, and  integral_0^s sqrt(1 - q^2) dq = (s sqrt(1 - s^2) + asin s) / 2. */
static double quadrant_area(double x, double y)
{
    if (x > 1) x = 1;
    if (y > 1) y = 1;
    if (x * x + y * y <= 1) return x * y;
    double s = sqrt(1.0 - y * y); /* < x here */
    double sx = 0.5 * (x * sqrt(1.0 - x * x) + asin(x)),
           ss = 0.5 * (s * sqrt(1.0 - s * s) + asin(s));
    return y * s + (sx - ss);
}

/* The same, signed (odd in each argument), so a rectangle anywhere is four corner terms. */
static double corner_area(double x, double y)
{
    double a = quadrant_area(fabs(x), fabs(y));
    return (x < 0) != (y < 0) ? -a : a;
}

/* Area of [a0, a1] x [b0, b1] inside the unit disc, by inclusion-exclusion. */
static double rect_disc_area(double a0, double a1, double b0, double b1)
{
    return corner_area(a1, b1) - corner_area(a0, b1) - corner_area(a1, b0) + corner_area(a0, b0);
}

/* Solid angle seen from the centre of [x0, x1] x [y0, y1] on a plane at distance 1:
 * F(x, y) = atan2(x y, sqrt(1 + x^2 + y^2)),  Omega = F(x1,y1) - F(x0,y1) - F(x1,y0) + F(x0,y0). */
static double plane_corner(double x, double y) { return atan2(x * y, sqrt(1.0 + x * x + y * y)); }
static double plane_rect_solid_angle(double x0, double x1, double y0, double y1)
{
    return plane_corner(x1, y1) - plane_corner(x0, y1) - plane_corner(x1, y0) +
           plane_corner(x0, y0);
}

/* d(omega) / (da db) of the angular map at disc radius rho <= 1: pi sin(pi rho) / rho. */
static double angular_jacobian_ab(double rho)
{
    if (rho < ANGULAR_RHO_EPS) return M_PI * M_PI;
    return M_PI * sin(M_PI * rho) / rho;
}

double convert_texel_solid_angle(const convert_env *env, int face, int c, int r)
{
    const image *im = convert_face_image(env, face);
    int w = im->w, h = im->h;
    assert(c >= 0 && c < w && r >= 0 && r < h);
    switch (env->kind) {
    case CONVERT_LATLONG: return latlong_texel_solid_angle(r, w, h);
    case CONVERT_EQUALAREA: return equalarea_texel_solid_angle(w, h);
    case CONVERT_CYLINDRICAL: {
        /* z_cyl = (1/2 - v) 2h; integral dz / (1 + z^2)^(3/2) = z / sqrt(1 + z^2) */
        double hh = env->max_height;
        double zt = (0.5 - (double)r / h) * 2.0 * hh, zb = (0.5 - (double)(r + 1) / h) * 2.0 * hh;
        return 2.0 * M_PI / w * (zt / sqrt(1.0 + zt * zt) - zb / sqrt(1.0 + zb * zb));
    }
    case CONVERT_CUBE: {
        /* sc = 2 s - 1 and tc = 2 t - 1 are the coordinates on the face's plane at distance 1 */
        double x0 = 2.0 * c / w - 1.0, x1 = 2.0 * (c + 1) / w - 1.0;
        double y0 = 2.0 * r / h - 1.0, y1 = 2.0 * (r + 1) / h - 1.0;
        return plane_rect_solid_angle(x0, x1, y0, y1);
    }
    case CONVERT_MIRRORBALL: {
        /* omega(rho) = 4 pi rho^2 (the cap seen inside radius rho): d(omega) = 4 da db */
        if (!disc_texel_valid(c, r, w, h)) return 0; /* (its four corner terms cancel to ~1e-16) */
        double a0 = 2.0 * c / w - 1.0, a1 = 2.0 * (c + 1) / w - 1.0;
        double b0 = 1.0 - 2.0 * (r + 1) / h, b1 = 1.0 - 2.0 * r / h;
        double area = rect_disc_area(a0, a1, b0, b1);
        return area > 0 ? 4.0 * area : 0.0; /* a sliver may round below 0 */
    }
    case CONVERT_ANGULAR: {
        if (!disc_texel_valid(c, r, w, h)) return 0;
        int side = w < h ? w : h;
        int n = (ANGULAR_OMEGA_SPAN + side - 1) / side;
        if (n < ANGULAR_OMEGA_MIN_STEPS) n = ANGULAR_OMEGA_MIN_STEPS;
        if (n > ANGULAR_OMEGA_MAX_STEPS) n = ANGULAR_OMEGA_MAX_STEPS;
        double da = 2.0 / w / n, db = 2.0 / h / n, sum = 0;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double a = 2.0 * c / w - 1.0 + (i + 0.5) * da;
                double b = 1.0 - 2.0 * r / h - (j + 0.5) * db;
                double rho = sqrt(a * a + b * b);
                if (rho <= 1.0) sum += angular_jacobian_ab(rho);
            }
        return sum * da * db;
    }
    default: assert(!"convert_texel_solid_angle: bad kind"); return 0;
    }
}

rgb convert_power(const convert_env *env)
{
    double p[3] = {0, 0, 0};
    for (int f = 0; f < convert_faces(env); f++) {
        const image *im = convert_face_image(env, f);
        for (int r = 0; r < im->h; r++) {
            double row[3] = {0, 0, 0};
            for (int c = 0; c < im->w; c++) {
                double om = convert_texel_solid_angle(env, f, c, r);
                if (om == 0) continue; /* outside the disc: not part of the environment */
                const float *px = image_px(im, c, r);
                for (int k = 0; k < 3; k++) row[k] += px[k] * om; /* P = sum L Omega */
            }
            for (int k = 0; k < 3; k++) p[k] += row[k];
        }
    }
    return rgb_make(p[0], p[1], p[2]);
}

/* ---- resampling --------------------------------------------------------------------------- */

/* The direction through point uv of the output (face `face` of a cube) and the Jacobian
 * J = d(omega) / (du dv) there (convert.h lists them).  -1 where uv holds no direction. */
static int sample_dir(convert_kind to, int face, double hh, uv2 uv, vec3 *d, double *jac)
{
    switch (to) {
    case CONVERT_LATLONG:
        *d = latlong_uv_to_dir(uv);
        *jac = 2.0 * M_PI * M_PI * sin(M_PI * uv.v); /* sin theta dtheta dphi, theta = pi v */
        return 0;
    case CONVERT_EQUALAREA:
        *d = equalarea_uv_to_dir(uv);
        *jac = 4.0 * M_PI; /* d(cos theta) d(phi) = 2 dv 2 pi du */
        return 0;
    case CONVERT_CYLINDRICAL: {
        if (cylindrical_uv_to_dir(uv, hh, d)) return -1;
        double z = (0.5 - uv.v) * 2.0 * hh;
        *jac = 4.0 * M_PI * hh / pow(1.0 + z * z, 1.5); /* dphi dz / (1 + z^2)^(3/2) */
        return 0;
    }
    case CONVERT_CUBE: {
        *d = cubemap_face_to_dir(face, uv);
        double sc = 2.0 * uv.u - 1.0, tc = 2.0 * uv.v - 1.0;
        *jac = 4.0 / pow(1.0 + sc * sc + tc * tc, 1.5); /* cos / r^2 on the plane at distance 1 */
        return 0;
    }
    case CONVERT_MIRRORBALL:
        if (mirrorball_uv_to_dir(uv, d)) return -1;
        *jac = 16.0; /* d(omega) = 4 da db, da db = 4 du dv */
        return 0;
    case CONVERT_ANGULAR: {
        if (angular_uv_to_dir(uv, d)) return -1;
        double a = 2.0 * uv.u - 1.0, b = 1.0 - 2.0 * uv.v;
        *jac = 4.0 * angular_jacobian_ab(sqrt(a * a + b * b));
        return 0;
    }
    default: assert(!"sample_dir: bad kind"); return -1;
    }
}

/* One stratum of an output texel: the square [u0, u1] x [v0, v1] of face `face`, adding
 * w J L and w J to sum and jsum at its centre, w = 2^-splits its share of the unsplit stratum.
 * The default K assumes that a texel spans about 2 pi / E_out radians in each direction, but
 * some span far more along one axis: the top row of an equal-area map reaches from the pole
 * to 7 degrees (rows are uniform in z, and theta ~ 2 sqrt(v) near the pole), a mirror ball's
 * rim texels reach 10 degrees towards -x.  A single centre there misses or over-counts a sun
 * smaller than that (measured: a 0.5-degree sun at the zenith lost 67% of the power to a
 * default equal-area map, one behind a mirror ball gained 20%).  So with the default samples a
 * stratum whose centre lines span more than max_angle (half an input texel, 2 pi / E_in / 2,
 * the spacing the default K aims at) is halved along the longer one, up to
 * CONVERT_MAX_SPLITS times.  Strata within it (everywhere on most maps) are the K x K grid. */
typedef struct stratum_job {
    const convert_env *in;
    convert_kind to;
    int face;
    double hh;        /* a cylindrical output's h */
    double max_angle; /* radians; 0: never split (samples given explicitly) */
    int split;        /* this texel's strata may split (texel_may_split) */
    rgb sum;          /* sum w J L */
    double jsum;      /* sum w J */
} stratum_job;

/* Halvings of one stratum at most: 2^12 = 4096 centres, enough for the pole row of a
 * 32768-wide equal-area map. */
#define CONVERT_MAX_SPLITS 12

/* The direction through uv of the output, a point outside a disc output's circle taken on the
 * circle (pulled in by DISC_PULL): a rim stratum spans from its inside to the rim's -x. */
static int span_dir(const stratum_job *job, uv2 uv, vec3 *d)
{
    double jac;
    if (sample_dir(job->to, job->face, job->hh, uv, d, &jac) == 0) return 0;
    if (job->to != CONVERT_MIRRORBALL && job->to != CONVERT_ANGULAR) return -1;
    double a = 2.0 * uv.u - 1.0, b = 1.0 - 2.0 * uv.v, k = (1.0 - DISC_PULL) / sqrt(a * a + b * b);
    return sample_dir(job->to, job->face, job->hh, (uv2){(a * k + 1.0) / 2.0, (1.0 - b * k) / 2.0},
                      d, &jac);
}

/* Angle between the directions through uv points a and b of the output (span_dir); 0 if either
 * holds none (beyond a cylinder's extent: nothing to resolve there). */
static double span_angle(const stratum_job *job, uv2 a, uv2 b)
{
    vec3 da, db;
    if (span_dir(job, a, &da) || span_dir(job, b, &db)) return 0;
    return atan2(vec3_length(vec3_cross(da, db)), vec3_dot(da, db));
}

/* Can a K x K stratum of texel [u0, u1] x [v0, v1] be wider than max_angle?  The texel's centre
 * lines, over K, against max_angle: where that holds, the texel is split no further and costs
 * what it always did (most texels of most maps); the pole rows and rim rings fail it. */
static int texel_may_split(const stratum_job *job, double u0, double u1, double v0, double v1,
                           int k)
{
    if (!(job->max_angle > 0)) return 0;
    double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    double au = span_angle(job, (uv2){u0, vm}, (uv2){u1, vm});
    double av = span_angle(job, (uv2){um, v0}, (uv2){um, v1});
    return fmax(au, av) > k * job->max_angle;
}

static void stratum(stratum_job *job, double u0, double u1, double v0, double v1, int splits)
{
    double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    if (job->split && splits < CONVERT_MAX_SPLITS) {
        double au = span_angle(job, (uv2){u0, vm}, (uv2){u1, vm});
        double av = span_angle(job, (uv2){um, v0}, (uv2){um, v1});
        if (au > job->max_angle || av > job->max_angle) {
            if (au >= av) {
                stratum(job, u0, um, v0, v1, splits + 1);
                stratum(job, um, u1, v0, v1, splits + 1);
            } else {
                stratum(job, u0, u1, v0, vm, splits + 1);
                stratum(job, u0, u1, vm, v1, splits + 1);
            }
            return;
        }
    }
    vec3 d;
    double jac;
    if (sample_dir(job->to, job->face, job->hh, (uv2){um, vm}, &d, &jac)) return;
    jac = ldexp(jac, -splits); /* w J, w = 2^-splits (exact: 1 when unsplit) */
    job->sum = rgb_madd(job->sum, convert_lookup(job->in, d), jac); /* sum w J L */
    job->jsum += jac;
}

/* "Equivalent lat-long width": texels per 2 pi radians of the map (convert.h). */
static long equivalent_width(convert_kind kind, long width)
{
    switch (kind) {
    case CONVERT_CUBE: return 4 * width;        /* four faces around the horizon */
    case CONVERT_MIRRORBALL: return 2 * width;  /* the 90-degree circle is pi W / sqrt 2 ~ 2.2 W */
    case CONVERT_ANGULAR: return 3 * width / 2; /* the 90-degree circle is pi W / 2 ~ 1.6 W */
    default: return width;
    }
}

static long input_equivalent_width(const convert_env *in)
{
    return equivalent_width(in->kind, convert_face_image(in, 0)->w);
}

int convert_default_width(const convert_env *in, convert_kind to)
{
    long e = input_equivalent_width(in), w;
    switch (to) {
    case CONVERT_CUBE: w = e / 4; break;
    case CONVERT_MIRRORBALL: w = e / 2; break;
    case CONVERT_ANGULAR: w = 2 * e / 3; break;
    default: w = e; break;
    }
    return w < 1 ? 1 : (int)w;
}

int convert_default_samples(const convert_env *in, convert_kind to, int width)
{
    long eo = equivalent_width(to, width < 1 ? 1 : width);
    long k = (2 * input_equivalent_width(in) + eo - 1) / eo; /* ceil(2 E_in / E_out) */
    if (k < 4) k = 4;
    if (k > CONVERT_MAX_SAMPLES) k = CONVERT_MAX_SAMPLES;
    return (int)k;
}

/* Allocate the output of `to` at `width` into *out. */
static int alloc_output(convert_kind to, int width, convert_map *out, error *err)
{
    memset(out, 0, sizeof *out);
    out->kind = to;
    switch (to) {
    case CONVERT_CUBE:
        if (image_check_size(width, width, NULL, err)) return error_prefix(err, "cube face");
        return cubemap_alloc(&out->cube, width, err);
    case CONVERT_MIRRORBALL:
    case CONVERT_ANGULAR: return image_alloc(&out->img, width, width, err);
    default: {
        int h = width / 2 < 1 ? 1 : width / 2;
        if (image_alloc(&out->img, width, h, err)) return -1;
        if (to == CONVERT_CYLINDRICAL) out->max_height = convert_cylindrical_height(width, h);
        return 0;
    }
    }
}

/* Same kind, same size (and cylinder): the conversion is the identity. */
static int same_layout(const convert_env *in, const convert_map *out)
{
    if (in->kind != out->kind) return 0;
    convert_env o = convert_view(out);
    const image *a = convert_face_image(in, 0), *b = convert_face_image(&o, 0);
    if (a->w != b->w || a->h != b->h) return 0;
    return in->kind != CONVERT_CYLINDRICAL || in->max_height == out->max_height;
}

int convert_resample(const convert_env *in, convert_kind to, int width, int samples,
                     convert_map *out, error *err)
{
    assert(in && out && to >= 0 && to < CONVERT_KINDS);
    memset(out, 0, sizeof *out);
    if (width <= 0) width = convert_default_width(in, to);
    int adaptive = samples <= 0;
    if (samples <= 0) samples = convert_default_samples(in, to, width);
    if (samples > CONVERT_MAX_SAMPLES)
        return error_set(err, NULL, 0, "samples per side must be in [1, %d], got %d",
                         CONVERT_MAX_SAMPLES, samples);
    if (alloc_output(to, width, out, err)) {
        convert_map_free(out);
        return -1;
    }
    convert_env ov = convert_view(out);
    if (same_layout(in, out)) {
        for (int f = 0; f < convert_faces(in); f++) {
            const image *a = convert_face_image(in, f);
            memcpy(convert_face_image(&ov, f)->px, a->px,
                   (size_t)a->w * (size_t)a->h * 3 * sizeof(float));
        }
        return 0;
    }
    int k = samples;
    stratum_job job = {in, to, 0, out->max_height, 0, 0, rgb_gray(0), 0};
    /* the default also splits a stratum wider than half an input texel (see stratum_job) */
    job.max_angle = adaptive ? M_PI / (double)input_equivalent_width(in) : 0;
    for (int f = 0; f < convert_faces(&ov); f++) {
        image *o = (image *)convert_face_image(&ov, f); /* out owns it: writable */
        job.face = f;
        for (int r = 0; r < o->h; r++)
            for (int c = 0; c < o->w; c++) {
                job.sum = rgb_gray(0);
                job.jsum = 0;
                job.split = texel_may_split(&job, (double)c / o->w, (c + 1.0) / o->w,
                                            (double)r / o->h, (r + 1.0) / o->h, k);
                for (int j = 0; j < k; j++)
                    for (int i = 0; i < k; i++) /* stratum (i, j) of the texel's square */
                        stratum(&job, (c + (double)i / k) / o->w, (c + (i + 1.0) / k) / o->w,
                                (r + (double)j / k) / o->h, (r + (j + 1.0) / k) / o->h, 0);
                rgb sum = job.sum;
                double jsum = job.jsum;
                if (jsum == 0 && (to == CONVERT_MIRRORBALL || to == CONVERT_ANGULAR) &&
                    disc_texel_valid(c, r, o->w, o->h)) {
                    /* a sliver of the disc: its nearest point to the centre stands for it */
                    uv2 uv = disc_nearest_uv(c, r, o->w, o->h);
                    vec3 d;
                    double jac;
                    if (sample_dir(to, f, out->max_height, uv, &d, &jac) == 0) {
                        sum = convert_lookup(in, d);
                        jsum = 1;
                    }
                }
                /* L_out = sum J L / sum J; no valid point (outside the disc): 0 */
                image_set(o, c, r, jsum > 0 ? rgb_scale(sum, 1.0 / jsum) : rgb_gray(0));
            }
    }
    return 0;
}

/* ---- files -------------------------------------------------------------------------------- */

static const char *const face_suffix[CUBEMAP_FACES] = {"_px", "_nx", "_py", "_ny", "_pz", "_nz"};

/* Where the extension of `path` starts (its last '.' after the last '/'), or its end. */
static size_t extension_at(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? (size_t)(dot - path) : strlen(path);
}

/* PATH with `insert` before its extension. */
static int insert_before_extension(const char *path, const char *insert, char *out, size_t size,
                                   error *err)
{
    size_t e = extension_at(path);
    int n = snprintf(out, size, "%.*s%s%s", (int)e, path, insert, path + e);
    if (n < 0 || (size_t)n >= size)
        return error_set(err, path, 0, "file name is too long for its cube-face suffix");
    return 0;
}

int convert_face_path(const char *path, int face, char *out, size_t size, error *err)
{
    assert(face >= 0 && face < CUBEMAP_FACES);
    return insert_before_extension(path, face_suffix[face], out, size, err);
}

/* Re-file an error under `path` (the library functions below it name no file). */
static int refile(error *err, const char *path)
{
    if (!err) return -1;
    char msg[ERROR_MSG_MAX];
    memcpy(msg, err->msg, sizeof msg);
    return error_set(err, path, 0, "%s", msg);
}

static int read_six_faces(const char *path, convert_map *out, budget *mem, error *err)
{
    char name[ERROR_FILE_MAX];
    for (int f = 0; f < CUBEMAP_FACES; f++) {
        image *im = &out->cube.face[f];
        if (convert_face_path(path, f, name, sizeof name, err) || imageio_read(name, im, mem, err))
            return -1;
        if (im->w != im->h)
            return error_set(err, name, 0, "a cube face must be square, not %d x %d", im->w, im->h);
        if (f > 0 && im->w != out->cube.face[0].w)
            return error_set(err, name, 0, "cube faces differ in size: %d x %d here, %d x %d in +X",
                             im->w, im->h, out->cube.face[0].w, out->cube.face[0].h);
    }
    out->cube.size = out->cube.face[0].w;
    return 0;
}

int convert_read(const char *path, const char *from, convert_map *out, budget *mem, error *err)
{
    memset(out, 0, sizeof *out);
    convert_kind kind = CONVERT_LATLONG;
    if (from && convert_kind_parse(from, &kind))
        return error_set(err, path, 0,
                         "unknown representation '%s' (latlong, cube, cross, "
                         "mirrorball, angular, cylindrical, equalarea)",
                         from);
    int rc = -1;
    image img = {0};
    out->kind = kind;
    if (from && strcmp(from, "cube") == 0) {
        if (read_six_faces(path, out, mem, err)) goto done;
        rc = 0;
        goto done;
    }
    if (imageio_read(path, &img, mem, err)) goto done;
    if (!from && convert_kind_detect(img.w, img.h, &kind, err)) {
        refile(err, path);
        goto done;
    }
    out->kind = kind;
    if (kind == CONVERT_CUBE) { /* six faces: half the cross's texels, the cross then freed */
        double cross = (double)img.w * img.h * IMAGE_TEXEL_BYTES;
        if (budget_charge(mem, cross / 2, path, 0, err,
                          "six %d x %d cube faces of %d bytes a texel", img.w / 4, img.w / 4,
                          IMAGE_TEXEL_BYTES))
            goto done;
        if (cubemap_from_cross(&img, &out->cube, err)) {
            refile(err, path);
            goto done;
        }
        budget_release(mem, cross);
    } else {
        out->img = img;
        img = (image){0};
        if (kind == CONVERT_CYLINDRICAL)
            out->max_height = convert_cylindrical_height(out->img.w, out->img.h);
    }
    rc = 0;
done:
    image_free(&img);
    if (rc) {
        convert_map_free(out);
        return rc;
    }
    /* radiance is finite and >= 0: a bad value becomes 0 once, here (convert.h) */
    convert_env v = convert_view(out);
    for (int f = 0; f < convert_faces(&v); f++)
        out->bad_texels += image_zero_nonfinite_or_negative((image *)convert_face_image(&v, f));
    return 0;
}

int convert_write(const char *path, const convert_map *m, error *err)
{
    if (m->kind != CONVERT_CUBE) return imageio_write(path, &m->img, NULL, err);
    /* six faces as a set (imageio_write_set): no face replaced unless all six are written */
    char name[CUBEMAP_FACES][ERROR_FILE_MAX];
    const char *paths[CUBEMAP_FACES];
    const image *faces[CUBEMAP_FACES];
    for (int f = 0; f < CUBEMAP_FACES; f++) {
        if (convert_face_path(path, f, name[f], sizeof name[f], err)) return -1;
        paths[f] = name[f];
        faces[f] = &m->cube.face[f];
    }
    return imageio_write_set(CUBEMAP_FACES, paths, faces, NULL, NULL, err);
}

int convert_write_cross(const char *path, const convert_map *m, error *err)
{
    assert(m->kind == CONVERT_CUBE);
    image cross = {0};
    int rc = cubemap_to_horizontal_cross(&m->cube, &cross, err);
    if (rc == 0) rc = imageio_write(path, &cross, NULL, err);
    image_free(&cross);
    return rc;
}

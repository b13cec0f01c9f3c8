/* texture.c - texture objects and their filtered evaluation (texture.h). */
#include "envtex/textures/texture.h"

#include <assert.h>
#include <string.h>

#include "envtex/textures/perlin.h"

/* ---- names ------------------------------------------------------------------------------ */

static const char *const filter_names[] = {"nearest", "bilinear", "trilinear", "ewa"};
static const char *const kind_names[] = {"image",      "checker", "perlin", "fbm",
                                         "turbulence", "marble",  "wood"};

int texture_filter_parse(const char *name, texture_filter *out)
{
    for (int k = 0; k < 4; k++)
        if (strcmp(name, filter_names[k]) == 0) {
            *out = (texture_filter)k;
            return 0;
        }
    return -1;
}

const char *texture_filter_name(texture_filter f)
{
    assert(f >= TEXFILTER_NEAREST && f <= TEXFILTER_EWA);
    return filter_names[f];
}

int texture_kind_parse(const char *name, texture_kind *out)
{
    for (int k = TEXTURE_CHECKER; k <= TEXTURE_WOOD; k++)
        if (strcmp(name, kind_names[k]) == 0) {
            *out = (texture_kind)k;
            return 0;
        }
    return -1;
}

const char *texture_kind_name(texture_kind k)
{
    assert(k >= TEXTURE_IMAGE && k <= TEXTURE_WOOD);
    return kind_names[k];
}

/* ---- construction ----------------------------------------------------------------------- */

void texture_init_image(texture *t, const image *img, wrap_mode wrap)
{
    assert(img && img->w > 0 && img->h > 0 && img->px);
    memset(t, 0, sizeof *t);
    t->kind = TEXTURE_IMAGE;
    t->img = img;
    t->wrap = wrap;
}

int texture_init_checker(texture *t, rgb c0, rgb c1, double frequency, error *err)
{
    memset(t, 0, sizeof *t);
    if (!(frequency > 0) || !isfinite(frequency))
        return error_set(err, NULL, 0, "checker frequency must be a finite number > 0, got %g",
                         frequency);
    t->kind = TEXTURE_CHECKER;
    t->c0 = c0;
    t->c1 = c1;
    t->frequency = frequency;
    return 0;
}

int texture_init_solid(texture *t, texture_kind kind, const texture_solid_params *sp, error *err)
{
    assert(kind >= TEXTURE_PERLIN && kind <= TEXTURE_WOOD);
    memset(t, 0, sizeof *t);
    const char *name = kind_names[kind];
    if (!(sp->scale > 0) || !isfinite(sp->scale))
        return error_set(err, NULL, 0, "%s scale must be a finite number > 0, got %g", name,
                         sp->scale);
    int uses_octaves = kind == TEXTURE_FBM || kind == TEXTURE_TURBULENCE || kind == TEXTURE_MARBLE;
    if (uses_octaves && (sp->octaves < 1 || sp->octaves > PERLIN_MAX_OCTAVES))
        return error_set(err, NULL, 0, "%s octaves must be in [1, %d], got %d", name,
                         PERLIN_MAX_OCTAVES, sp->octaves);
    if (!(sp->frequency >= 0) || !isfinite(sp->frequency) || !(sp->rings >= 0) ||
        !isfinite(sp->rings) || !isfinite(sp->amplitude))
        return error_set(err, NULL, 0, "%s parameters must be finite (frequency, rings >= 0)",
                         name);
    t->kind = kind;
    t->solid = *sp;
    return 0;
}

int texture_needs_prepare(const texture *t, texture_filter filter)
{
    if (t->kind != TEXTURE_IMAGE) return 0;
    if (filter == TEXFILTER_TRILINEAR || filter == TEXFILTER_EWA) return !t->has_mip;
    return 0;
}

int texture_prepare(texture *t, texture_filter filter, budget *mem, error *err)
{
    if (!texture_needs_prepare(t, filter)) return 0;
    /* the pyramid, charged before it is built (its scratch only while it is) */
    mipmap_cost c = mipmap_cost_of(t->img->w, t->img->h);
    if (budget_charge(mem, c.levels + c.scratch, NULL, 0, err, "a mip pyramid of %d x %d texels",
                      t->img->w, t->img->h))
        return -1;
    int rc = mipmap_build(&t->mip, t->img, t->wrap, err);
    budget_release(mem, c.scratch + (rc ? c.levels : 0));
    if (rc) return -1;
    t->has_mip = 1;
    return 0;
}

void texture_free(texture *t)
{
    if (!t) return;
    if (t->has_mip) mipmap_free(&t->mip);
    memset(t, 0, sizeof *t);
}

/* ---- evaluation ------------------------------------------------------------------------- */

static double uv_dot(uv2 a, uv2 b) { return a.u * b.u + a.v * b.v; }

static double smoothstep(double a, double b, double x)
{
    double u = (x - a) / (b - a); /* callers pass a < b */
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    return u * u * (3 - 2 * u);
}

/* The odd-square indicator of a 1D checker, floor(x) mod 2, and its antiderivative
 *     F(x) = floor(x / 2) + max(0, x - 2 floor(x / 2) - 1)
 * (each period [2k, 2k + 2) holds one unit of "odd" in its second half). */
static double odd_point(double x) { return x - 2.0 * floor(0.5 * x) >= 1.0 ? 1.0 : 0.0; }
static double odd_integral(double x)
{
    double k = floor(0.5 * x);
    double r = x - 2.0 * k - 1.0;
    return k + (r > 0 ? r : 0.0);
}

/* Mean of the odd indicator over [x - hw, x + hw] (hw = 0: the point value). */
static double odd_box(double x, double hw)
{
    if (!(hw > 0)) return odd_point(x);
    double a = x - hw, b = x + hw;
    if (floor(a) == floor(b)) return odd_point(x);            /* inside one square */
    double m = (odd_integral(b) - odd_integral(a)) / (b - a); /* b > a: hw > 0 and finite */
    if (!isfinite(m)) return 0.5;
    return m < 0 ? 0 : m > 1 ? 1 : m;
}

static rgb eval_checker(const texture *t, const texture_query *q)
{
    double f = t->frequency;
    double hs = 0, ht = 0;
    if (q->filter == TEXFILTER_TRILINEAR || q->filter == TEXFILTER_EWA) {
        /* a box as wide as one pixel's step in each of s and t, in squares */
        hs = 0.5 * f * fmax(fabs(q->dst_dx.u), fabs(q->dst_dy.u));
        ht = 0.5 * f * fmax(fabs(q->dst_dx.v), fabs(q->dst_dy.v));
    }
    double a = odd_box(f * q->st.u, hs), b = odd_box(f * q->st.v, ht);
    /* colour c1 where exactly one of the two is odd: P = a + b - 2ab (independent boxes) */
    double w = a + b - 2.0 * a * b;
    return rgb_add(rgb_scale(t->c0, 1.0 - w), rgb_scale(t->c1, w));
}

/* Footprint of a solid texture at the query, in units of scale P (0: none). */
static double solid_footprint(const texture *t, const texture_query *q)
{
    if (q->filter != TEXFILTER_TRILINEAR && q->filter != TEXFILTER_EWA) return 0;
    double w = t->solid.scale * fmax(vec3_length(q->dp_dx), vec3_length(q->dp_dy));
    return isfinite(w) ? w : 0;
}

/* The solid texture's value v in [0, 1] at object point p with footprint w (units of scale p). */
static double solid_value(const texture *t, vec3 p, double w)
{
    const texture_solid_params *s = &t->solid;
    vec3 x = vec3_scale(p, s->scale);
    double v = 0;
    switch (t->kind) {
    case TEXTURE_PERLIN: /* one octave of lattice frequency 1 */
        v = 0.5 +
            0.5 * (w > 0 ? perlin_fbm_filtered(x, w, 1, 2.0, 0.5) : perlin_noise(x.x, x.y, x.z));
        break;
    case TEXTURE_FBM: v = 0.5 + 0.5 * perlin_fbm_filtered(x, w, s->octaves, 2.0, 0.5); break;
    case TEXTURE_TURBULENCE: v = perlin_turbulence_filtered(x, w, s->octaves, 2.0, 0.5); break;
    case TEXTURE_MARBLE:
        if (w > 0) {
            /* the veins have s->frequency / 2 pi cycles per unit: fade them to their mean as
             * perlin.h fades an octave, a = 1 - smoothstep(1/2, 1, cycles w) */
            double a = 1.0 - smoothstep(0.5, 1.0, s->frequency / (2 * M_PI) * w);
            double turb = perlin_turbulence_filtered(x, w, s->octaves, 2.0, 0.5);
            v = 0.5 + 0.5 * a * perlin_marble_veins(s->frequency * x.x + s->amplitude * turb);
        } else {
            v = perlin_marble(x, s->frequency, s->amplitude, s->octaves);
        }
        break;
    case TEXTURE_WOOD: {
        v = perlin_wood(x, s->rings, s->amplitude);
        /* rings per unit: the sawtooth fades to its mean 1/2 in the same band */
        double a = smoothstep(0.5, 1.0, s->rings * w);
        v = (1.0 - a) * v + 0.5 * a;
        break;
    }
    default: assert(!"not a solid texture");
    }
    return v < 0 ? 0 : v > 1 ? 1 : v;
}

/* Trilinear's footprint width, w = sqrt(|dst/dx| |dst/dy|): the side of the square with the
 * area of the pixel's footprint when its axes are perpendicular (docs/texture-mapping.md on why
 * not pbrt's longer axis).  Each axis is measured in units of the longer side's texels,
 * (ds W, dt H) / max(W, H): every level halves both sides, so a footprint one texel each way on
 * a 2:1 image is level 0, not 0.5. */
static double trilinear_width(const texture *t, const texture_query *q)
{
    double side = t->img->w > t->img->h ? t->img->w : t->img->h;
    double ks = t->img->w / side, kt = t->img->h / side;
    uv2 a = {q->dst_dx.u * ks, q->dst_dx.v * kt}, b = {q->dst_dy.u * ks, q->dst_dy.v * kt};
    return sqrt(sqrt(uv_dot(a, a)) * sqrt(uv_dot(b, b)));
}

rgb texture_eval(const texture *t, const texture_query *q)
{
    switch (t->kind) {
    case TEXTURE_IMAGE:
        switch (q->filter) {
        case TEXFILTER_NEAREST: return texlookup_nearest(t->img, q->st, t->wrap);
        case TEXFILTER_BILINEAR: return texlookup_bilinear(t->img, q->st, t->wrap);
        case TEXFILTER_TRILINEAR:
            assert(t->has_mip && "texture_prepare(t, TEXFILTER_TRILINEAR) first");
            return mipmap_lookup_trilinear(&t->mip, q->st, trilinear_width(t, q));
        case TEXFILTER_EWA:
            assert(t->has_mip && "texture_prepare(t, TEXFILTER_EWA) first");
            return mipmap_lookup_ewa(&t->mip, q->st, q->dst_dx, q->dst_dy);
        }
        break;
    case TEXTURE_CHECKER: return eval_checker(t, q);
    default: {
        double v = solid_value(t, q->p, solid_footprint(t, q));
        /* (1 - v) c0 + v c1 */
        return rgb_add(rgb_scale(t->solid.c0, 1.0 - v), rgb_scale(t->solid.c1, v));
    }
    }
    return rgb_gray(0);
}

double texture_eval_scalar(const texture *t, const texture_query *q)
{
    return rgb_avg(texture_eval(t, q));
}

/* h at the query moved by (ds, dt) in texture space or by dp in object space */
static double h_at_st(const texture *t, const texture_query *q, double ds, double dt)
{
    texture_query m = *q;
    m.st.u += ds;
    m.st.v += dt;
    return texture_eval_scalar(t, &m);
}

static double h_at_p(const texture *t, const texture_query *q, vec3 dp)
{
    texture_query m = *q;
    m.p = vec3_add(m.p, dp);
    return texture_eval_scalar(t, &m);
}

void texture_height_derivs(const texture *t, const texture_query *q, double *h, double *dh_ds,
                           double *dh_dt)
{
    *h = texture_eval_scalar(t, q);
    *dh_ds = *dh_dt = 0;
    if (t->kind == TEXTURE_IMAGE || t->kind == TEXTURE_CHECKER) {
        double min_s, min_t;
        if (t->kind == TEXTURE_IMAGE) {
            min_s = TEXTURE_BUMP_MIN_TEXELS / t->img->w;
            min_t = TEXTURE_BUMP_MIN_TEXELS / t->img->h;
        } else {
            min_s = min_t = TEXTURE_BUMP_MIN_FEATURE / t->frequency;
        }
        double es = fmax(0.5 * (fabs(q->dst_dx.u) + fabs(q->dst_dy.u)), min_s);
        double et = fmax(0.5 * (fabs(q->dst_dx.v) + fabs(q->dst_dy.v)), min_t);
        if (!isfinite(es) || !isfinite(et)) return;
        /* dh/ds = (h(s + es) - h(s - es)) / (2 es), es >= min_s > 0 */
        *dh_ds = (h_at_st(t, q, es, 0) - h_at_st(t, q, -es, 0)) / (2 * es);
        *dh_dt = (h_at_st(t, q, 0, et) - h_at_st(t, q, 0, -et)) / (2 * et);
        return;
    }
    double dist = fmax(0.5 * (vec3_length(q->dp_dx) + vec3_length(q->dp_dy)),
                       TEXTURE_BUMP_MIN_FEATURE / t->solid.scale);
    vec3 tang[2] = {q->dp_ds, q->dp_dt};
    double *out[2] = {dh_ds, dh_dt};
    for (int k = 0; k < 2; k++) {
        double len = vec3_length(tang[k]);
        if (!(len > 0) || !isfinite(len) || !isfinite(dist)) continue; /* no tangent: 0 */
        double e = dist / len;                                         /* e |dP/ds| = dist */
        vec3 d = vec3_scale(tang[k], e);
        /* dh/ds = (h(P + e dP/ds) - h(P - e dP/ds)) / (2 e) */
        *out[k] = (h_at_p(t, q, d) - h_at_p(t, q, vec3_neg(d))) / (2 * e);
    }
}

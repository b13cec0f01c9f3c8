/* mipmap.c - image pyramid, trilinear and EWA lookups (see include/envtex/textures/mipmap.h). */
#include "envtex/textures/mipmap.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/stepcheck.h"

/* ---- building ------------------------------------------------------------------------------ */

/* Taps of one destination texel along one axis: an interval of length r <= 3 plus a tent's
 * reach of 1 each side touches at most 7 source texels. */
#define MIPMAP_MAX_TAPS 8

typedef struct taps {
    int n;                      /* number of taps used */
    int index[MIPMAP_MAX_TAPS]; /* source texel, already wrapped into [0, n_src) */
    double weight[MIPMAP_MAX_TAPS];
} taps;

/* T(t) = integral_{-inf}^t tent(u) du, tent(u) = max(0, 1 - |u|) */
static double tent_integral(double t)
{
    if (t <= -1.0) return 0.0;
    if (t <= 0.0) return 0.5 * (t + 1.0) * (t + 1.0);
    if (t < 1.0) return 1.0 - 0.5 * (1.0 - t) * (1.0 - t);
    return 1.0;
}

/* The taps of destination texel x of n_dst from n_src source texels:
 * weight_j = (1/r) (T(b - c_j) - T(a - c_j)), [a, b] = [x r, (x+1) r], c_j = j + 1/2. */
static void make_taps(taps *tp, int x, int n_src, int n_dst, wrap_mode wrap)
{
    double r = (double)n_src / n_dst; /* n_dst >= 1 */
    double a = x * r, b = (x + 1) * r;
    int j0 = (int)floor(a - 1.5), j1 = (int)ceil(b + 0.5); /* centres within 1 of [a, b] */
    tp->n = 0;
    for (int j = j0; j <= j1; j++) {
        double c = j + 0.5;
        double w = (tent_integral(b - c) - tent_integral(a - c)) / r;
        if (w <= 0.0) continue;
        assert(tp->n < MIPMAP_MAX_TAPS);
        tp->index[tp->n] = texlookup_wrap(j, n_src, wrap);
        tp->weight[tp->n] = w;
        tp->n++;
    }
}

/* dst (allocated here) = src filtered down to max(1, w/2) x max(1, h/2), separably: first
 * along x into a w_dst x h_src buffer of doubles, then along y. */
static int downsample(const image *src, image *dst, wrap_mode wrap, error *err)
{
    int ws = src->w, hs = src->h;
    int wd = ws / 2 > 1 ? ws / 2 : 1, hd = hs / 2 > 1 ? hs / 2 : 1;
    int status = -1;
    double *tmp = NULL;
    taps *tx = NULL, *ty = NULL;
    if (image_alloc(dst, wd, hd, err)) goto cleanup;
    tmp = malloc((size_t)wd * (size_t)hs * 3 * sizeof *tmp);
    tx = malloc((size_t)wd * sizeof *tx);
    ty = malloc((size_t)hd * sizeof *ty);
    if (!tmp || !tx || !ty) {
        error_set(err, NULL, 0, "out of memory for a %d x %d mipmap level", wd, hd);
        goto cleanup;
    }
    for (int x = 0; x < wd; x++) make_taps(&tx[x], x, ws, wd, wrap);
    /* rows are counted from the top in the image but from the bottom in texture space; the
     * tents are symmetric and wrap modes reflect the same way at both ends, so filtering the
     * rows in image order gives the same level */
    for (int y = 0; y < hd; y++) make_taps(&ty[y], y, hs, hd, wrap);

    for (int y = 0; y < hs; y++) /* along x */
        for (int x = 0; x < wd; x++) {
            double acc[3] = {0, 0, 0};
            for (int k = 0; k < tx[x].n; k++) {
                const float *p = image_px(src, tx[x].index[k], y);
                for (int c = 0; c < 3; c++) acc[c] += tx[x].weight[k] * p[c];
            }
            memcpy(tmp + 3 * ((size_t)y * wd + x), acc, sizeof acc);
        }
    for (int y = 0; y < hd; y++) /* along y */
        for (int x = 0; x < wd; x++) {
            double acc[3] = {0, 0, 0};
            for (int k = 0; k < ty[y].n; k++) {
                const double *p = tmp + 3 * ((size_t)ty[y].index[k] * wd + x);
                for (int c = 0; c < 3; c++) acc[c] += ty[y].weight[k] * p[c];
            }
            image_set(dst, x, y, (rgb){acc[0], acc[1], acc[2]});
        }
    status = 0;
cleanup:
    if (status) image_free(dst);
    free(tmp);
    free(tx);
    free(ty);
    return status;
}

int mipmap_build(mipmap *m, const image *base, wrap_mode wrap, error *err)
{
    memset(m, 0, sizeof *m);
    if (!base || base->w < 1 || base->h < 1 || !base->px)
        return error_set(err, NULL, 0, "mipmap of an empty image");
    if (wrap != WRAP_REPEAT && wrap != WRAP_CLAMP && wrap != WRAP_MIRROR)
        return error_set(err, NULL, 0, "mipmap: unknown wrap mode %d", (int)wrap);
    m->wrap = wrap;
    m->level[0] = *base; /* shallow: shares the caller's pixels */
    m->nlevels = 1;
    while (m->level[m->nlevels - 1].w > 1 || m->level[m->nlevels - 1].h > 1) {
        assert(m->nlevels < MIPMAP_MAX_LEVELS); /* sides <= 2^15 */
        if (downsample(&m->level[m->nlevels - 1], &m->level[m->nlevels], wrap, err)) {
            int failed = m->nlevels; /* mipmap_free zeroes m */
            mipmap_free(m);
            return error_prefix(err, "mipmap level %d", failed);
        }
        m->nlevels++;
    }
    for (int i = 0; i < MIPMAP_EWA_LUT_SIZE; i++) {
        double r2 = (double)i / (MIPMAP_EWA_LUT_SIZE - 1);
        /* a Gaussian, 0 at r = 1 */
        m->ewa_weight[i] = exp(-MIPMAP_EWA_ALPHA * r2) - exp(-MIPMAP_EWA_ALPHA);
    }
    return 0;
}

mipmap_cost mipmap_cost_of(int w, int h)
{
    mipmap_cost c = {0, 0};
    while (w > 1 || h > 1) {
        int wd = w / 2 > 1 ? w / 2 : 1, hd = h / 2 > 1 ? h / 2 : 1;
        /* downsample's buffers: a wd x h grid of double RGB and the taps of each axis */
        double scratch = (double)wd * h * 3 * sizeof(double) + (double)(wd + hd) * sizeof(taps);
        if (scratch > c.scratch) c.scratch = scratch;
        c.levels += (double)wd * hd * IMAGE_TEXEL_BYTES;
        w = wd;
        h = hd;
    }
    return c;
}

void mipmap_free(mipmap *m)
{
    if (!m) return;
    for (int l = 1; l < m->nlevels && l < MIPMAP_MAX_LEVELS; l++) image_free(&m->level[l]);
    memset(m, 0, sizeof *m);
}

int mipmap_levels(const mipmap *m) { return m->nlevels; }

const image *mipmap_level(const mipmap *m, int l)
{
    assert(l >= 0 && l < m->nlevels);
    return &m->level[l];
}

/* ---- trilinear ----------------------------------------------------------------------------- */

static inline int max_side(const image *im) { return im->w > im->h ? im->w : im->h; }

double mipmap_level_for_footprint(const mipmap *m, double width_in_texels)
{
    if (!(width_in_texels > 1.0)) return 0.0; /* magnification, or NaN */
    double top = m->nlevels - 1;
    double l = log2(width_in_texels); /* one level per doubling of the footprint */
    return l < top ? l : top;
}

/* Level l of the pyramid, its index checked (stepcheck.h): the trilinear step reads levels here. */
static inline const image *level(const mipmap *m, int l)
{
    STEPCHECK_INDEX(l, m->nlevels, "mipmap", "level");
    return &m->level[l];
}

rgb mipmap_lookup_trilinear(const mipmap *m, uv2 st, double footprint_width)
{
    /* the level from log2 of the footprint in texels: lod = l + f, l = floor(lod) */
    double lod = mipmap_level_for_footprint(m, footprint_width * max_side(&m->level[0]));
    int l = (int)lod;
    double f = lod - l; /* 0 at the top level, which has no level above */
    /* STEP(mipmap): trilinear filtering, slides 39-40 (Mip Maps): "linearly interpolate between two
     * closest levels"; the footprint's level is l + f (given; mipmap.h); level(m, l)
     * reads level l */
    /* STUB: (void)l; (void)f; return texlookup_bilinear(level(m, 0), st, m->wrap); */
    rgb c = texlookup_bilinear(level(m, l), st, m->wrap);
    if (f > 0) {
        rgb c1 = texlookup_bilinear(level(m, l + 1), st, m->wrap);
        c = rgb_add(rgb_scale(c, 1 - f), rgb_scale(c1, f)); /* (1 - f) c_l + f c_(l+1) */
    }
    return c;
    /* END STEP(mipmap) */
}

/* ---- EWA ----------------------------------------------------------------------------------- */

/* Half-widths of the ellipse's bounding box past which a level is not filtered (the mean is
 * returned instead).  The level choice keeps them below about 17 texels; this only stops
 * pathological input from looping for long. */
#define MIPMAP_EWA_MAX_RADIUS 64.0

/* Move the continuous texel coordinate x (n texels) by a whole number of periods (repeat: n,
 * mirror: 2n) or, for clamp, by whole texels while the box [x - rad, x + rad] stays entirely
 * past the same border, so it fits an int.  The offsets of the texels from x, hence the
 * weights and the texels read, are unchanged. */
static double reduce_coordinate(double x, int n, double rad, wrap_mode wrap)
{
    if (fabs(x) < 0x1p24) return x; /* already small: nothing to do */
    if (wrap == WRAP_CLAMP) {
        double margin = ceil(rad) + 2.0;
        if (x < 0) return x - floor(x) - margin; /* frac(x) - margin < -rad - 1 */
        return x - floor(x) + n + margin;        /* > n + rad + 1 */
    }
    /* fmod is exact (x - period floor(x / period) is not once x passes 2^53 texels: x / period
     * rounds, and a 3-texel texture read the wrong texel there) */
    double period = wrap == WRAP_MIRROR ? 2.0 * n : (double)n;
    return fmod(x, period); /* in (-period, period), x's fraction kept: small enough */
}

/* The EWA filter on one level; d0, d1 in texture units. */
static rgb ewa_level(const mipmap *m, int l, uv2 st, uv2 d0, uv2 d1)
{
    const image *im = &m->level[l];
    int w = im->w, h = im->h;
    double x = st.u * w - 0.5, y = st.v * h - 0.5; /* texel centres at integers, y up */
    double e0x = d0.u * w, e0y = d0.v * h, e1x = d1.u * w, e1y = d1.v * h; /* in texels */
    /* covariance of the footprint plus one texel^2: S = J J^T + I; the ellipse is
     * x^T S^-1 x < 1, i.e. A x^2 + B x y + C y^2 < 1 after dividing by F = det S >= 1 */
    double A = e0y * e0y + e1y * e1y + 1.0;
    double B = -2.0 * (e0x * e0y + e1x * e1y);
    double C = e0x * e0x + e1x * e1x + 1.0;
    double F = A * C - 0.25 * B * B; /* det S >= 1: never zero */
    A /= F;
    B /= F;
    C /= F;
    /* bounding box half-widths: sqrt(S_xx) = 2 sqrt(C / det), det = 4AC - B^2 */
    double det = 4.0 * A * C - B * B;
    double ru = 2.0 * sqrt(C / det), rv = 2.0 * sqrt(A / det);
    if (!(ru <= MIPMAP_EWA_MAX_RADIUS && rv <= MIPMAP_EWA_MAX_RADIUS))
        return image_get(&m->level[m->nlevels - 1], 0, 0);
    x = reduce_coordinate(x, w, ru, m->wrap);
    y = reduce_coordinate(y, h, rv, m->wrap);
    if (!(isfinite(x) && isfinite(y))) return texlookup_bilinear(im, st, m->wrap);
    int i0 = (int)ceil(x - ru), i1 = (int)floor(x + ru);
    int j0 = (int)ceil(y - rv), j1 = (int)floor(y + rv);
    double sum[3] = {0, 0, 0}, wsum = 0.0;
    for (int j = j0; j <= j1; j++) {
        double dy = j - y;
        int row = im->h - 1 - texlookup_wrap(j, h, m->wrap); /* rows from the top */
        for (int i = i0; i <= i1; i++) {
            double dx = i - x;
            double r2 = A * dx * dx + B * dx * dy + C * dy * dy;
            if (r2 >= 1.0) continue;
            /* the table holds the weight at r^2 = k / (SIZE - 1): read it there, linearly
             * interpolated (within 3.1e-5 of the Gaussian: h^2 / 8 max|w''|, h = 1 / 127) */
            double kf = r2 * (MIPMAP_EWA_LUT_SIZE - 1);
            int k = (int)kf; /* 0 <= r2 < 1: k <= SIZE - 2 */
            double wt = m->ewa_weight[k] + (kf - k) * (m->ewa_weight[k + 1] - m->ewa_weight[k]);
            const float *p = image_px(im, texlookup_wrap(i, w, m->wrap), row);
            sum[0] += wt * p[0];
            sum[1] += wt * p[1];
            sum[2] += wt * p[2];
            wsum += wt;
        }
    }
    /* the ellipse holds a disc of radius 1 texel, hence a texel centre at r^2 <= 1/2 with
     * weight > 0; the guard is for safety only */
    if (!(wsum > 0.0)) return texlookup_bilinear(im, st, m->wrap);
    return (rgb){sum[0] / wsum, sum[1] / wsum, sum[2] / wsum};
}

rgb mipmap_lookup_ewa(const mipmap *m, uv2 st, uv2 dst_dx, uv2 dst_dy)
{
    /* the axes in level-0 texels, (ds W, dt H): every level halves both sides, so the level
     * and the anisotropy are measured there (texture units would stretch a non-square image's
     * shorter side: a footprint of one texel each way on a 2:1 image would read half a level up) */
    double W = m->level[0].w, H = m->level[0].h;
    uv2 d0 = {dst_dx.u * W, dst_dx.v * H}, d1 = {dst_dy.u * W, dst_dy.v * H};
    double l0 = d0.u * d0.u + d0.v * d0.v, l1 = d1.u * d1.u + d1.v * d1.v;
    if (!(isfinite(l0) && isfinite(l1))) return image_get(&m->level[m->nlevels - 1], 0, 0);
    if (l0 < l1) { /* d0 is the major axis */
        uv2 t = d0;
        d0 = d1;
        d1 = t;
    }
    double major = sqrt(l0 > l1 ? l0 : l1), minor = sqrt(l0 > l1 ? l1 : l0);
    if (major == 0.0) return texlookup_bilinear(&m->level[0], st, m->wrap);
    if (minor * MIPMAP_MAX_ANISOTROPY < major) {
        /* too eccentric: lengthen the minor axis to major / MAX_ANISOTROPY (along the
         * perpendicular of the major axis if it has no direction of its own) */
        double target = major / MIPMAP_MAX_ANISOTROPY;
        if (minor > 0.0) {
            double s = target / minor;
            d1 = (uv2){d1.u * s, d1.v * s};
        } else {
            double s = target / major;
            d1 = (uv2){-d0.v * s, d0.u * s};
        }
        minor = target;
    }
    double lod = mipmap_level_for_footprint(m, minor); /* minor is in texels */
    if (lod >= m->nlevels - 1) return image_get(&m->level[m->nlevels - 1], 0, 0); /* 1 x 1 */
    d0 = (uv2){d0.u / W, d0.v / H}; /* back to texture units */
    d1 = (uv2){d1.u / W, d1.v / H};
    int l = (int)lod;
    double f = lod - l;
    rgb c0 = ewa_level(m, l, st, d0, d1);
    if (f <= 0.0) return c0;
    rgb c1 = ewa_level(m, l + 1, st, d0, d1);
    return rgb_madd(rgb_scale(c0, 1.0 - f), c1, f); /* (1 - f) c0 + f c1 */
}

/* texlookup.c - wrap modes, nearest and bilinear texture lookups (texlookup.h). */
#include "envtex/textures/texlookup.h"

#include <assert.h>
#include <math.h>
#include <string.h>

int texlookup_wrap(int i, int n, wrap_mode wrap)
{
    assert(n >= 1);
    if ((unsigned)i < (unsigned)n) return i; /* inside: the common case, every mode agrees */
    switch (wrap) {
    case WRAP_CLAMP: return i < 0 ? 0 : n - 1;
    case WRAP_MIRROR: {
        long long period = 2LL * n;               /* 2n overflows an int for n > 2^30 */
        long long r = i % period;                 /* in (-2n, 2n) */
        if (r < 0) r += period;                   /* [0, 2n) */
        return (int)(r < n ? r : period - 1 - r); /* the second copy runs backwards */
    }
    case WRAP_REPEAT:
    default: {
        assert(wrap == WRAP_REPEAT);
        int r = i % n; /* in (-n, n) */
        return r < 0 ? r + n : r;
    }
    }
}

/* Past this magnitude floor(x) is wrapped in double; below it, converted to int and wrapped
 * there (texlookup.h) */
#define WRAP_INT_SAFE TEXLOOKUP_INT_SAFE

/* An integer-valued double f (already floored) wrapped into [0, n). */
static inline int wrap_integer(double f, int n, wrap_mode wrap)
{
    if (fabs(f) < WRAP_INT_SAFE) return texlookup_wrap((int)f, n, wrap); /* false for NaN */
    if (isnan(f)) return 0;
    if (wrap == WRAP_CLAMP) return f < 0 ? 0 : n - 1;
    if (!isfinite(f)) return 0;
    /* fmod is exact, so the remainder of an integer-valued f is an exact integer */
    double period = wrap == WRAP_MIRROR ? 2.0 * n : (double)n;
    double r = fmod(f, period); /* (-period, period) */
    if (r < 0) r += period;     /* [0, period) */
    if (wrap == WRAP_MIRROR && r >= n) r = period - 1 - r;
    return (int)r;
}

int texlookup_wrap_floor(double x, int n, wrap_mode wrap)
{
    assert(n >= 1);
    return wrap_integer(floor(x), n, wrap);
}

static const char *const wrap_names[] = {"repeat", "clamp", "mirror"};

int texlookup_wrap_parse(const char *name, wrap_mode *out)
{
    for (int k = 0; k < 3; k++)
        if (name && strcmp(name, wrap_names[k]) == 0) {
            *out = (wrap_mode)k;
            return 0;
        }
    return -1;
}

const char *texlookup_wrap_name(wrap_mode wrap)
{
    return (unsigned)wrap < 3 ? wrap_names[wrap] : "unknown";
}

/* i in any int range wrapped into [0, n), with the cheap cases first: inside, then repeat by a
 * mask when n is a power of two (the usual texture), else texlookup_wrap (a division) */
static inline int wrap_fast(int i, int n, wrap_mode wrap)
{
    if ((unsigned)i < (unsigned)n) return i;
    if (wrap == WRAP_REPEAT && (n & (n - 1)) == 0) return i & (n - 1); /* two's complement mod */
    return texlookup_wrap(i, n, wrap);
}

/* texlookup_bilinear_axis past its inline fast path: an index outside [0, n - 1) (wrapped, the
 * integer path first) or |x| >= TEXLOOKUP_INT_SAFE, NaN and infinities (wrapped in double). */
texlookup_axis texlookup_bilinear_axis_far(double x, int n, wrap_mode wrap)
{
    if (fabs(x) < WRAP_INT_SAFE) { /* false for NaN and infinities */
        int k = texlookup_fast_floor(x);
        return (texlookup_axis){wrap_fast(k, n, wrap), wrap_fast(k + 1, n, wrap), x - k};
    }
    double x0 = floor(x), fx = x - x0;
    return (texlookup_axis){wrap_integer(x0, n, wrap), wrap_integer(x0 + 1.0, n, wrap),
                            fx >= 0.0 ? fx : 0.0}; /* NaN (non-finite x) -> f = 0 */
}

/* floor(x) wrapped, the integer path first (as texlookup_bilinear_axis) */
static inline int nearest_axis(double x, int n, wrap_mode wrap)
{
    if (fabs(x) < WRAP_INT_SAFE) return wrap_fast(texlookup_fast_floor(x), n, wrap);
    return wrap_integer(floor(x), n, wrap);
}

rgb texlookup_nearest(const image *im, uv2 st, wrap_mode wrap)
{
    assert(im->w >= 1 && im->h >= 1);
    int i = nearest_axis(st.u * im->w, im->w, wrap); /* i = floor(s W) */
    int j = nearest_axis(st.v * im->h, im->h, wrap); /* j = floor(t H), from the bottom */
    return image_get(im, i, im->h - 1 - j);
}

rgb texlookup_bilinear(const image *im, uv2 st, wrap_mode wrap)
{
    assert(im->w >= 1 && im->h >= 1);
    int w = im->w, h = im->h;
    texlookup_axis ax = texlookup_bilinear_axis(st.u * w - 0.5, w, wrap); /* x = s W - 1/2 */
    texlookup_axis ay = texlookup_bilinear_axis(st.v * h - 0.5, h, wrap); /* y = t H - 1/2 */
    int i0 = ax.i0, i1 = ax.i1, j0 = ay.i0, j1 = ay.i1;
    double fx = ax.f, fy = ay.f;
    const float *r0 = image_px(im, 0, h - 1 - j0); /* row of j0 (rows counted from the top) */
    const float *r1 = image_px(im, 0, h - 1 - j1);
    const float *c00 = r0 + 3 * i0, *c10 = r0 + 3 * i1, *c01 = r1 + 3 * i0, *c11 = r1 + 3 * i1;
    /* c = (1-fy) [(1-fx) c00 + fx c10] + fy [(1-fx) c01 + fx c11] */
    double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
    return (rgb){w00 * c00[0] + w10 * c10[0] + w01 * c01[0] + w11 * c11[0],
                 w00 * c00[1] + w10 * c10[1] + w01 * c01[1] + w11 * c11[1],
                 w00 * c00[2] + w10 * c10[2] + w01 * c01[2] + w11 * c11[2]};
}

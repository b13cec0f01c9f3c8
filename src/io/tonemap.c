/* tonemap.c - linear HDR to 8-bit sRGB (see include/envtex/io/tonemap.h). */
#include "envtex/io/tonemap.h"

#include <math.h>
#include <string.h>

tonemap_params tonemap_defaults(void)
{
    return (tonemap_params){.exposure = 0.0, .op = TONEMAP_CLAMP, .gamma = 0.0};
}

int tonemap_op_parse(const char *name, tonemap_op *op)
{
    if (!strcmp(name, "clamp"))
        *op = TONEMAP_CLAMP;
    else if (!strcmp(name, "reinhard"))
        *op = TONEMAP_REINHARD;
    else if (!strcmp(name, "aces"))
        *op = TONEMAP_ACES;
    else
        return -1;
    return 0;
}

/* IEC 61966-2-1: the linear segment below 0.0031308 (encoded 0.04045) avoids an infinite slope
 * at 0.  Values outside [0,1] follow the same two pieces (negatives take the linear one). */
double tonemap_srgb_encode(double l)
{
    /* STEP(tonemap): the sRGB transfer curve for display (IEC 61966-2-1; tonemap.h), slide 10 (High
     * Dynamic Range): "tonemap as needed for display" */
    /* STUB: return l; */
    return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
    /* END STEP(tonemap) */
}

double tonemap_srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* One channel through the whole pipeline to [0,1]; NaN -> 0, +Inf -> 1, -Inf -> 0. */
static double tonemap_channel(const tonemap_params *tm, double scale, double c)
{
    if (isnan(c)) return 0.0;
    if (isinf(c))
        return c > 0 ? 1.0 : 0.0; /* before the scale: Inf * 0 when 2^exposure underflows */
    /* STEP(tonemap): exposure in stops: the radiance scaled by 2^exposure (slide 10 (High Dynamic
     * Range); tonemap.h) */
    /* STUB: (void)scale;
     * double x = c; */
    double x = c * scale; /* c * 2^exposure: finite * finite, never NaN */
    /* END STEP(tonemap) */
    if (x <= 0.0) return 0.0; /* display values are never negative; also guards 1 + x = 0 below */
    if (isinf(x)) return 1.0;
    switch (tm->op) {
    case TONEMAP_CLAMP: break;
    case TONEMAP_REINHARD: x = x / (1.0 + x); break; /* x / (1 + x), x >= 0 so no zero division */
    case TONEMAP_ACES:
        /* Narkowicz 2015: (x (a x + b)) / (x (c x + d) + e), a=2.51 b=0.03 c=2.43 d=0.59 e=0.14;
         * the denominator is >= 0.14 for x >= 0.  The raw fit: no 0.6 pre-exposure.  It reaches
         * 1 at x = 7.24 (0.08 x^2 - 0.56 x - 0.14 = 0) and stays above (-> 2.51 / 2.43): white
         * from x = 8 on, before x^2 can overflow (x > 1e154 gave Inf / Inf = NaN) */
        if (x >= 8.0) return 1.0;
        x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
        break;
    }
    if (x >= 1.0) return 1.0;
    x = tm->gamma > 0.0 ? pow(x, 1.0 / tm->gamma) : tonemap_srgb_encode(x); /* c^(1/gamma) */
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

static uint8_t to_byte(double v) { return (uint8_t)(v * 255.0 + 0.5); } /* v in [0,1] */

void tonemap_pixel(const tonemap_params *tm, rgb c, uint8_t out[3])
{
    double scale = exp2(tm->exposure);
    out[0] = to_byte(tonemap_channel(tm, scale, c.r));
    out[1] = to_byte(tonemap_channel(tm, scale, c.g));
    out[2] = to_byte(tonemap_channel(tm, scale, c.b));
}

long tonemap_image(const tonemap_params *tm, const image *im, uint8_t *out)
{
    double scale = exp2(tm->exposure);
    long bad = 0;
    size_t n = (size_t)im->w * (size_t)im->h;
    for (size_t i = 0; i < n; i++) {
        const float *p = im->px + 3 * i;
        bad += !image_px_is_finite(p);
        for (int k = 0; k < 3; k++) out[3 * i + k] = to_byte(tonemap_channel(tm, scale, p[k]));
    }
    return bad;
}

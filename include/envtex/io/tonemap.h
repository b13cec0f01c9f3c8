/* tonemap.h - linear HDR radiance to 8-bit sRGB (slide 10 (High Dynamic Range): HDR must be tone
 * mapped to show).
 *
 *     tonemap_params tm = tonemap_defaults();   // 0 EV, clamp, sRGB
 *     uint8_t px[3]; tonemap_pixel(&tm, c, px);
 *
 * Per channel: c 2^exposure (negatives 0) -> operator -> encode (sRGB if gamma <= 0, else
 * c^(1/gamma)) -> clamp to [0,1] -> floor(255 v + 0.5).  NaN, -Inf give 0, +Inf 1.
 */
#ifndef ENVTEX_TONEMAP_H
#define ENVTEX_TONEMAP_H

#include <stdint.h>

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

typedef enum tonemap_op {
    TONEMAP_CLAMP,    /* identity, then clamp */
    TONEMAP_REINHARD, /* c / (1 + c) */
    TONEMAP_ACES      /* Narkowicz's ACES fit x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
                       * without the 0.6 pre-exposure (exposure -0.737 EV adds it) */
} tonemap_op;

typedef struct tonemap_params {
    double exposure; /* EV: multiply by 2^exposure first */
    tonemap_op op;
    double gamma; /* <= 0: the sRGB curve; > 0: c^(1/gamma) */
} tonemap_params;

tonemap_params tonemap_defaults(void);

/* "clamp", "reinhard", "aces" -> *op: 0, or -1 if unknown. */
int tonemap_op_parse(const char *name, tonemap_op *op);

/* The sRGB curve (IEC 61966-2-1), linear -> encoded and back; outside [0,1] the same two
 * pieces (negatives the linear one), no clamping. */
double tonemap_srgb_encode(double linear);
double tonemap_srgb_decode(double encoded);

/* One pixel to 8-bit sRGB (or gamma-encoded) bytes. */
void tonemap_pixel(const tonemap_params *tm, rgb c, uint8_t out[3]);

/* The image into out (w * h * 3 bytes, caller owned, row 0 at the top); returns how many
 * pixels had a NaN or Inf channel. */
long tonemap_image(const tonemap_params *tm, const image *im, uint8_t *out);

#endif

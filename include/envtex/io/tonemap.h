/* tonemap.h - from linear HDR radiance to displayable 8-bit sRGB (lecture slide 10: HDR images
 * have to be tone mapped to be shown).
 *
 *     tonemap_params tm = tonemap_defaults();  // exposure 0 EV, clamp, sRGB curve
 *     tm.op = TONEMAP_REINHARD;
 *     uint8_t px[3]; tonemap_pixel(&tm, c, px);
 *
 * Pipeline per channel: c * 2^exposure -> operator -> encode -> clamp to [0,1] -> round to 8 bit
 * (byte = floor(255 v + 0.5)).  Negative values become 0 before the operator.
 * Encode is the sRGB curve when gamma <= 0 (the default 0), else c^(1/gamma) (the course's
 * `gamma` command).  NaN maps to 0, +Inf to 1 and -Inf to 0 (such a pixel is counted by
 * tonemap_image so callers can report it).
 */
#ifndef ENVTEX_TONEMAP_H
#define ENVTEX_TONEMAP_H

#include <stdint.h>

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

typedef enum tonemap_op {
    TONEMAP_CLAMP,    /* identity, then clamp */
    TONEMAP_REINHARD, /* c / (1 + c) */
    TONEMAP_ACES      /* Narkowicz's fit of the ACES filmic curve, as published:
                       * x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), no 0.6 pre-exposure
                       * (use exposure log2(0.6) = -0.737 EV to match engines that apply it) */
} tonemap_op;

typedef struct tonemap_params {
    double exposure; /* EV: multiply by 2^exposure first */
    tonemap_op op;
    double gamma;    /* <= 0: sRGB transfer curve; > 0: c^(1/gamma) (pngfile_write labels the
                      * file with the curve: an sRGB chunk, or a gAMA chunk of 1/gamma) */
} tonemap_params;

tonemap_params tonemap_defaults(void);

/* Parse "clamp", "reinhard", "aces"; 0 on success, -1 if unknown. */
int tonemap_op_parse(const char *name, tonemap_op *op);

/* Linear value in [0,1] -> sRGB-encoded value in [0,1] (IEC 61966-2-1) and back.  Outside [0,1]
 * the same two pieces are applied (negatives take the linear piece); no clamping. */
double tonemap_srgb_encode(double linear);
double tonemap_srgb_decode(double encoded);

/* One pixel to 8-bit sRGB (or gamma-encoded) bytes. */
void tonemap_pixel(const tonemap_params *tm, rgb c, uint8_t out[3]);

/* The whole image into out (w * h * 3 bytes, caller owned, row 0 at the top); returns the
 * number of pixels that had a NaN or Inf channel (a pixel counts once). */
long tonemap_image(const tonemap_params *tm, const image *im, uint8_t *out);

#endif

/* tonemap.h - from linear HDR radiance to displayable 8-bit sRGB (lecture slide 10: HDR images
 * have to be tone mapped to be shown).
 *
 *     tonemap_params tm = tonemap_defaults();  // exposure 0 EV, clamp, sRGB curve
 *     tm.op = TONEMAP_REINHARD;
 *     uint8_t px[3]; tonemap_pixel(&tm, c, px);
 *
 * Pipeline per channel: c * 2^exposure -> operator -> encode -> clamp to [0,1] -> round to 8 bit.
 * Encode is the sRGB curve when gamma == 0, else c^(1/gamma) (the course's `gamma` command).
 * NaN maps to 0 and +Inf to 1 (the pixel is counted by tonemap_image so callers can report it).
 */
#ifndef ENVTEX_TONEMAP_H
#define ENVTEX_TONEMAP_H

#include <stdint.h>

#include "envtex/image.h"
#include "envtex/vec.h"

typedef enum tonemap_op {
    TONEMAP_CLAMP,    /* identity, then clamp */
    TONEMAP_REINHARD, /* c / (1 + c) */
    TONEMAP_ACES      /* Narkowicz's fit of the ACES filmic curve */
} tonemap_op;

typedef struct tonemap_params {
    double exposure; /* EV: multiply by 2^exposure first */
    tonemap_op op;
    double gamma;    /* 0: sRGB transfer curve; > 0: c^(1/gamma) */
} tonemap_params;

tonemap_params tonemap_defaults(void);

/* Parse "clamp", "reinhard", "aces"; 0 on success, -1 if unknown. */
int tonemap_op_parse(const char *name, tonemap_op *op);

/* Linear value in [0,1] -> sRGB-encoded value in [0,1] (IEC 61966-2-1) and back. */
double tonemap_srgb_encode(double linear);
double tonemap_srgb_decode(double encoded);

/* One pixel to 8-bit. */
void tonemap_pixel(const tonemap_params *tm, rgb c, uint8_t out[3]);

/* The whole image into out (w * h * 3 bytes, caller owned); returns the number of pixels that
 * had a NaN or Inf channel. */
long tonemap_image(const tonemap_params *tm, const image *im, uint8_t *out);

#endif

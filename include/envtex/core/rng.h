/* rng.h - deterministic random numbers: PCG32 (O'Neill 2014), one independent stream per pixel,
 * so an image depends only on the scene, spp and the seed, never on the order pixels run in.
 *
 *     rng r; rng_seed(&r, seed, pixel_index);
 *     double xi = rng_uniform(&r);   // in [0, 1), never 1
 */
#ifndef ENVTEX_RNG_H
#define ENVTEX_RNG_H

#include <stdint.h>

typedef struct rng {
    uint64_t state, inc;
} rng;

/* The next 32 random bits. */
static inline uint32_t rng_u32(rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc; /* LCG step */
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31)); /* XSH RR output */
}

/* Start stream `stream` of generator `seed`; distinct streams are independent. */
static inline void rng_seed(rng *r, uint64_t seed, uint64_t stream)
{
    r->state = 0;
    r->inc = (stream << 1u) | 1u; /* the increment must be odd */
    rng_u32(r);
    r->state += seed;
    rng_u32(r);
}

/* Uniform in [0, 1): 32 bits times 2^-32, at most 1 - 2^-32. */
static inline double rng_uniform(rng *r) { return rng_u32(r) * 0x1p-32; }

#endif

/* perlin.c - Improved Noise and the solid textures built on it (perlin.h). */
#include "envtex/textures/perlin.h"

#include <math.h>

/* Perlin's permutation of 0..255 (the reference implementation's `permutation`). */
#define PERLIN_PERMUTATION                                                                         \
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,   \
        142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252,  \
        219, 203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, \
        68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60,     \
        211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1,   \
        216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86,   \
        164, 100, 109, 198, 173, 186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118,    \
        126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, \
        213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, \
        253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34,  \
        242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49,  \
        192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254,   \
        138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180

/* p[i] = p[i + 256]: the table repeated so that p[p[X] + Y] never needs a second "& 255". */
static const unsigned char perm[512] = {PERLIN_PERMUTATION, PERLIN_PERMUTATION};

/* fade(t) = 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at t = 0 and t = 1 */
static inline double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

static inline double lerp(double t, double a, double b) { return a + t * (b - a); }

/* The 12 gradients from the centre of a cube to its edge midpoints, (+-1, +-1, 0) and
 * permutations, padded to 16 with 4 of them repeated, indexed by hash & 15: exactly the vectors
 * Perlin's grad() selects with its branches, as a table so the hot path has no unpredictable
 * branch (his branches, as ?:, took 5x the time: the hash is random).  Each product is exact
 * (components are 0 or +-1), so the dot product rounds exactly as his u + v does.  A row is
 * padded to 4 doubles (32 bytes), so finding it is a shift, not a multiply by 24. */
static const double gradients[16][4] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}};

/* g . (x, y, z) for the gradient g picked by the low 4 bits of the hash */
static inline double grad(unsigned hash, double x, double y, double z)
{
    const double *g = gradients[hash & 15];
    return g[0] * x + g[1] * y + g[2] * z;
}

/* floor(x) mod 256 for an integer-valued fl, any magnitude: fl / 256 is exact (a power of two),
 * floor of it is exact, and fl - 256 floor(fl / 256) is an integer in [0, 255], so also exact.
 * Perlin's (int)floor(x) & 255 overflows an int past 2^31; this never does. */
static inline unsigned lattice_cell(double fl)
{
    double c = fl - 256.0 * floor(fl * (1.0 / 256.0));
    return (unsigned)c & 255;
}

/* Below this magnitude the lattice cell comes from an int conversion (2^30: far from INT_MAX) */
#define PERLIN_INT_SAFE 0x1p30

/* floor(x) for |x| < 2^30: truncate toward zero, then step down for a negative non-integer */
static inline int fast_floor(double x)
{
    int i = (int)x;
    return i - (x < (double)i);
}

double perlin_noise(double x, double y, double z)
{
    /* STEP(perlin): Perlin's improved noise (Perlin 2002), slides 45-46 (Solid textures): "compute
     * on the fly, e.g. Perlin noise": the lattice cell of (x, y, z), its 8 corners' hashed
     * gradients dotted with the offsets to them, blended by the fade curve (the helpers above;
     * perlin.h); a NaN or infinite coordinate gives 0 */
    /* STUB: (void)perm; (void)fade; (void)lerp; (void)grad; (void)lattice_cell;
     * (void)fast_floor; (void)x; (void)y; (void)z;
     * return 0.0; */
    unsigned X, Y, Z;
    if (fabs(x) < PERLIN_INT_SAFE && fabs(y) < PERLIN_INT_SAFE && fabs(z) < PERLIN_INT_SAFE) {
        /* the common case (NaN and infinities fail these comparisons and go below): floor by
         * truncation (exact in this range), the cell by & 255 (two's complement: floor(x) mod
         * 256 for negative floor(x) too) */
        int ix = fast_floor(x), iy = fast_floor(y), iz = fast_floor(z);
        X = (unsigned)ix & 255;
        Y = (unsigned)iy & 255;
        Z = (unsigned)iz & 255;
        x -= ix; /* the point's position inside its cell, [0, 1) */
        y -= iy;
        z -= iz;
    } else {
        if (!(isfinite(x) && isfinite(y) && isfinite(z))) return 0.0; /* no lattice cell: 0 */
        double fx = floor(x), fy = floor(y), fz = floor(z);
        X = lattice_cell(fx);
        Y = lattice_cell(fy);
        Z = lattice_cell(fz);
        x -= fx;
        y -= fy;
        z -= fz;
    }
    double u = fade(x), v = fade(y), w = fade(z);
    /* hash the 8 corners: A = p[X] + Y, AA = p[A] + Z, ... as in the reference (unsigned: each
     * is at most 255 + 255, and an unsigned index needs no sign extension before each load) */
    unsigned A = perm[X] + Y, AA = perm[A] + Z, AB = perm[A + 1] + Z;
    unsigned B = perm[X + 1] + Y, BA = perm[B] + Z, BB = perm[B + 1] + Z;
    /* trilinear blend (by the fade weights) of the 8 corner gradients dotted with the offsets */
    return lerp(w,
                lerp(v, lerp(u, grad(perm[AA], x, y, z), grad(perm[BA], x - 1, y, z)),
                     lerp(u, grad(perm[AB], x, y - 1, z), grad(perm[BB], x - 1, y - 1, z))),
                lerp(v,
                     lerp(u, grad(perm[AA + 1], x, y, z - 1), grad(perm[BA + 1], x - 1, y, z - 1)),
                     lerp(u, grad(perm[AB + 1], x, y - 1, z - 1),
                          grad(perm[BB + 1], x - 1, y - 1, z - 1))));
    /* END STEP(perlin) */
}

static int clamp_octaves(int octaves)
{
    if (octaves < 0) return 0;
    return octaves > PERLIN_MAX_OCTAVES ? PERLIN_MAX_OCTAVES : octaves;
}

double perlin_fbm(vec3 p, int octaves, double lacunarity, double gain)
{
    return perlin_fbm_filtered(p, 0.0, octaves, lacunarity, gain);
}

double perlin_turbulence(vec3 p, int octaves, double lacunarity, double gain)
{
    return perlin_turbulence_filtered(p, 0.0, octaves, lacunarity, gain);
}

/* Weight of an octave of lattice frequency f under a filter of width w:
 * a = 1 - smoothstep(1/2, 1, f w)  (see perlin.h for why these two edges). */
static inline double octave_weight(double f, double w)
{
    double t = (f * w - 0.5) * 2.0; /* 0 at f w = 1/2, 1 at f w = 1 */
    if (!(t > 0.0)) return 1.0;     /* also w <= 0 or NaN: unfiltered */
    if (t >= 1.0) return 0.0;
    return 1.0 - t * t * (3.0 - 2.0 * t);
}

/* The sum both filtered functions share: sum_i gain^i (a_i n_i + (1 - a_i) mean), where n_i is
 * noise (fbm) or |noise| (turbulence) at lacunarity^i p and mean is its average. */
static double octave_sum(vec3 p, double footprint, int octaves, double lacunarity, double gain,
                         int absolute, double mean)
{
    octaves = clamp_octaves(octaves);
    double sum = 0.0, amp = 1.0, freq = 1.0;
    for (int i = 0; i < octaves; i++) {
        double a = octave_weight(freq, footprint);
        if (a <= 0.0) {
            /* this octave and (lacunarity > 1) every finer one are filtered away entirely:
             * add their means, sum_{j >= i} gain^j mean, and stop */
            for (int j = i; j < octaves; j++, amp *= gain) sum += amp * mean;
            break;
        }
        double n = perlin_noise(p.x * freq, p.y * freq, p.z * freq);
        if (absolute) n = fabs(n);
        sum += amp * (a * n + (1.0 - a) * mean); /* a_i n_i + (1 - a_i) E[n_i] */
        amp *= gain;
        freq *= lacunarity;
    }
    return sum;
}

double perlin_fbm_filtered(vec3 p, double footprint, int octaves, double lacunarity, double gain)
{
    return octave_sum(p, footprint, octaves, lacunarity, gain, 0, 0.0);
}

double perlin_turbulence_filtered(vec3 p, double footprint, int octaves, double lacunarity,
                                  double gain)
{
    return octave_sum(p, footprint, octaves, lacunarity, gain, 1, PERLIN_MEAN_ABS);
}

double perlin_marble_veins(double phase)
{
    /* frequency * x or amplitude * turbulence overflowed (or was 0 * Inf): veins far finer than
     * the doubles can place, whose mean is 0; sin(+-Inf) and sin(NaN) would be NaN */
    if (!isfinite(phase)) return 0.0;
    return sin(phase);
}

double perlin_marble(vec3 p, double frequency, double amplitude, int octaves)
{
    double turb = perlin_turbulence(p, octaves, 2.0, 0.5);
    return 0.5 + 0.5 * perlin_marble_veins(frequency * p.x + amplitude * turb); /* marble */
}

double perlin_wood(vec3 p, double rings, double amplitude)
{
    double v = rings * sqrt(p.x * p.x + p.z * p.z) + amplitude * perlin_noise(p.x, p.y, p.z);
    double f = v - floor(v); /* ring fraction */
    /* v - floor(v) rounds up to 1.0 for v just below an integer (e.g. -1e-17): keep [0, 1);
     * NaN (from an infinite p) becomes 0 */
    if (!(f < 1.0)) f = f >= 1.0 ? 0x1.fffffffffffffp-1 : 0.0;
    return f;
}

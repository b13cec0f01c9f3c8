/* simd.h - four floats side by side (lanes), for tracing four rays at once (bvh_packet.h):
 * GCC's vector extensions, which GCC and Clang compile to SSE on x86-64 and to NEON on ARM,
 * plus the three operations they lack in C (min, max, a mask of lanes), from SSE where the
 * compiler has it and lane by lane elsewhere (ENVTEX_NO_SSE forces that, for its test).
 *
 *     f4 t = (f4_set(lo - o) * inv);            // four rays' slab distances at once
 *     int hit = f4_mask(tnear <= tfar);         // bit l set when lane l's comparison holds
 *
 * Each operation works lane by lane and rounds as the same float operation in C does, so lane l
 * holds, bit for bit, what a loop over the lanes would compute.  A comparison gives an i4 whose
 * lanes are -1 (true) or 0 (false).
 */
#ifndef ENVTEX_SIMD_H
#define ENVTEX_SIMD_H

#include <stdint.h>

#if defined(__SSE__) && !defined(ENVTEX_NO_SSE)
#include <xmmintrin.h>
#define SIMD_SSE 1
#else
#define SIMD_SSE 0
#endif

typedef float f4 __attribute__((vector_size(16)));
typedef int32_t i4 __attribute__((vector_size(16)));

static inline f4 f4_set(float x) { return (f4){x, x, x, x}; }

/* Lane by lane a < b ? a : b, so b where either is NaN. */
static inline f4 f4_min(f4 a, f4 b)
{
#if SIMD_SSE
    return _mm_min_ps(a, b);
#else
    for (int l = 0; l < 4; l++) a[l] = a[l] < b[l] ? a[l] : b[l];
    return a;
#endif
}

/* Lane by lane a > b ? a : b, so b where either is NaN. */
static inline f4 f4_max(f4 a, f4 b)
{
#if SIMD_SSE
    return _mm_max_ps(a, b);
#else
    for (int l = 0; l < 4; l++) a[l] = a[l] > b[l] ? a[l] : b[l];
    return a;
#endif
}

/* |a| lane by lane (the sign bit cleared, as fabsf). */
static inline f4 f4_abs(f4 a) { return (f4)((i4)a & 0x7fffffff); }

/* Bit l set when lane l of the comparison m is true. */
static inline int f4_mask(i4 m)
{
#if SIMD_SSE
    return _mm_movemask_ps((__m128)m);
#else
    return (m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8);
#endif
}

#endif

/* test_simd_generic.c - test_simd.c on simd.h's lane-by-lane code (what a processor without SSE
 * runs), so that both ways are checked on every machine. */
#define ENVTEX_NO_SSE 1
#include "test_simd.c"

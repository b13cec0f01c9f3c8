/* test_bvh_packet_generic.c - test_bvh_packet.c against the packet traversal compiled here
 * without SSE (simd.h lane by lane: what a processor without SSE runs), so that both ways are
 * checked on every machine.  This program's bvh_intersect_packet is the one it compiles. */
#define ENVTEX_NO_SSE 1
#include "../../../src/geometry/bvh_packet.c"
#include "test_bvh_packet.c"

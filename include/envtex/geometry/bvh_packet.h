/* bvh_packet.h - a camera's rays through neighbouring pixels traced together: up to BVH_PACKET
 * rays find the same closest hits as bvh_intersect finds one by one, bit for bit, in fewer
 * steps, because such rays cross the same nodes (docs/design-notes.md, "Packets of camera
 * rays").
 *
 *     ray r[BVH_PACKET];  int got[BVH_PACKET];  hit h[BVH_PACKET];
 *     for (int i = 0; i < n; i++) r[i] = camera_ray(&cam, x[i], y[i]);
 *     bvh_intersect_packet(&b, r, n, got, h);   // got[i] as bvh_intersect(&b, &r[i], &h[i])
 *
 * The rays go in groups of four, a ray a lane of simd.h's vectors, and the nodes are tested
 * for the whole packet at once by interval arithmetic over its directions.  That needs the
 * rays to share their origin, tmin, tmax and the sign of each direction component (none 0);
 * a packet that does not is traced one ray at a time, with the same results.  Queries
 * allocate nothing.
 */
#ifndef ENVTEX_BVH_PACKET_H
#define ENVTEX_BVH_PACKET_H

#include "envtex/geometry/bvh.h"

#define BVH_PACKET 64 /* rays in a packet at most: groups of four lanes */

/* For i in [0, n), 0 <= n <= BVH_PACKET: got[i] = bvh_intersect(b, &r[i], &h[i]), with h[i]
 * filled as bvh_intersect fills it (untouched on a miss). */
void bvh_intersect_packet(const bvh *b, const ray *r, int n, int *got, hit *h);

#endif

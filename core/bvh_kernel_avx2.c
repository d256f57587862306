/* The avx2 kernel, for CPUs with AVX2 (the platform checks; see rt_bvh_set_kernel): the
 * one-ray walk of bvh_walk.h and its leaves compiled for AVX2 (the same operations in
 * its encoding, which runs them faster: docs/performance.md; any-hit leaves four
 * triangles at a time), and the packet walk of bvh_packet.h in 256-bit vectors. */
#if defined(__SSE2__) && !defined(RT_REAL_FIXED) /* FLOAT_WALK's condition, before it is known */
#define LEAF_TARGET __attribute__((target("avx2")))
#define LEAF_QUADS
#endif
#include "bvh_float.h"

#if FLOAT_WALK
#define WALK_VEC 32
#define WALK_TARGET __attribute__((target("avx2")))
#define WALK_NAME rt_bvh_walk_avx2
#include "bvh_walk.h"

#define PACKET_VEC 32
#define PACKET_TARGET __attribute__((target("avx2")))
#define PACKET_WALK rt_bvh_packet_avx2
#include "bvh_packet.h"
#endif

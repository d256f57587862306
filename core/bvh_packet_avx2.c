/* The packet walk of bvh_packet.h in 256-bit vectors, for CPUs with AVX2 (the platform
 * checks; see rt_bvh_set_kernel). */
#include "bvh_float.h"

#if FLOAT_WALK
#define PACKET_VEC 32
#define PACKET_TARGET __attribute__((target("avx2")))
#define PACKET_WALK rt_bvh_packet_avx2
#include "bvh_packet.h"
#endif

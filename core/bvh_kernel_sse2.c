/* The sse2 kernel: the one-ray walk of bvh_walk.h and the packet walk of bvh_packet.h in
 * 128-bit vectors (SSE2, x86's baseline). */
#include "bvh_float.h"

#if FLOAT_WALK
#define WALK_VEC 16
#define WALK_TARGET
#define WALK_NAME rt_bvh_walk_sse2
#include "bvh_walk.h"

#define PACKET_VEC 16
#define PACKET_TARGET
#define PACKET_WALK rt_bvh_packet_sse2
#include "bvh_packet.h"
#endif

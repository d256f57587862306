/* The avx512 kernel, for CPUs with AVX2 and AVX-512 F and DQ (the platform checks; see
 * rt_bvh_set_kernel): the avx2 kernel's one-ray walk, and the packet walk of
 * bvh_packet.h with its boxes tested in 256-bit float vectors as the avx2 kernel's, but a
 * packet's eight rays held in one 512-bit double vector for the triangle tests, so that a
 * leaf's triangles are read once a packet instead of once per half of it. */
#include "bvh_float.h"

#if FLOAT_WALK
#define PACKET_VEC 32
#define PACKET_VEC_D 64
#define PACKET_TARGET __attribute__((target("avx2,avx512f,avx512dq")))
#define PACKET_WALK rt_bvh_packet_avx512
#include "bvh_packet.h"
#endif

/* A fingerprint of a built BVH: SHA-256 over everything the queries read of it, so two
 * builds that hash the same made the same tree, bit for bit. */
#ifndef RTP_BVH_HASH_H
#define RTP_BVH_HASH_H

#include "scene.h"

/* SHA-256 of the tree's shape (node count, depth, grid, extent), its nodes and its
 * primitive references, as lowercase hex (64 characters and a NUL). */
void rtp_bvh_hash(const rt_bvh *bvh, uint32_t prim_count, char hex[65]);

#endif

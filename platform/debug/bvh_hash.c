/* See bvh_hash.h. */
#include "debug/bvh_hash.h"
#include "sha256.h"
#include <stdio.h>

void rtp_bvh_hash(const rt_bvh *bvh, uint32_t prim_count, char hex[65])
{
    rt_sha256 h;
    rt_sha256_init(&h);
    /* Fields one by one: the struct's padding is not part of the tree. */
    int32_t grid = bvh->grid;
    rt_sha256_update(&h, &bvh->node_count, sizeof bvh->node_count);
    rt_sha256_update(&h, &bvh->depth, sizeof bvh->depth);
    rt_sha256_update(&h, &grid, sizeof grid);
    rt_sha256_update(&h, &bvh->extent, sizeof bvh->extent);
    /* rt_bvh_node has no padding: 6 x RT_BVH_WIDTH bounds and 2 x RT_BVH_WIDTH words of four bytes. */
    _Static_assert(sizeof(rt_bvh_node) == 6 * RT_BVH_WIDTH * sizeof(rt_bound) + 2 * RT_BVH_WIDTH * sizeof(uint32_t),
                   "rt_bvh_node is hashed as bytes");
    rt_sha256_update(&h, bvh->nodes, (size_t)bvh->node_count * sizeof(rt_bvh_node));
    rt_sha256_update(&h, bvh->prim_refs, (size_t)prim_count * sizeof(uint32_t));
    uint8_t digest[32];
    rt_sha256_final(&h, digest);
    for (int i = 0; i < 32; i++) snprintf(hex + 2 * i, 3, "%02x", digest[i]);
}

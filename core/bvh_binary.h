/* The binary tree the SAH build makes in scratch (bvh.c), before it is collapsed into
 * the wide tree the queries walk (bvh_collapse.c). Core-internal. */
#ifndef RT_BVH_BINARY_H
#define RT_BVH_BINARY_H

#include "bvh.h"

/* A binary node: its box as stored, and children nodes[first], nodes[first + 1]
 * (count 0) or references prim_refs[first .. first + count). The root is node 0; in the
 * levels split one at a time, the children of a node whose references split at index m
 * (into [.., m) and [m, ..)) are nodes 2m - 1 and 2m, so every node's place follows from
 * the tree alone and separate subtrees can be built at once without sharing a counter.
 * Inside a subtree built whole, of references [f, f + c), its nodes' descendants take
 * the 2c - 2 slots from 2f + 1 (which that scheme gives them, and no other node) pair by
 * pair in the order they are made, so that the collapse finds them together. */
typedef struct {
    rt_bound box[6];
    uint32_t first, count;
} rt_bin_node;

/* An inner node of at most RT_BIN_WIDE_ROOT_MAX references whose parent has more is a
 * wide root: the collapse does not open it into its parent's wide node. Its count is
 * RT_BIN_WIDE_ROOT (inner nodes' is otherwise 0), so that the job that built its
 * subtree can collapse it there and then (rt_bvh_collapse_block). The sizes give the
 * fewest wide nodes of those tried on the bench's meshes (docs/performance.md). */
#if RT_BVH_WIDTH == 8
#define RT_BIN_WIDE_ROOT_MAX 16384
#else
#define RT_BIN_WIDE_ROOT_MAX 8192
#endif
#define RT_BIN_WIDE_ROOT UINT32_MAX
/* The count of a wide root collapsed already: `first` is the slot of its block, whose
 * node count and depth are that slot's first and count, its wide nodes (numbered from
 * 0, its own) stored from the next slot on. */
#define RT_BIN_COLLAPSED (UINT32_MAX - 1)

/* Stores b rounded outwards on the tree's grid. */
void rt_bvh_store_box(rt_bound box[6], rt_aabb b, int grid);

/* Collapses the binary tree at bin (root node 0, `inner` inner nodes) into the wide
 * tree on bvh->grid: bvh->nodes (in the arena, 64-byte aligned), node_count, depth. The
 * blocks of wide roots collapsed already (at most `blocks` of them) are copied in by
 * jobs on the workers. */
rt_status rt_bvh_collapse(const rt_bin_node *bin, uint32_t inner, uint32_t blocks, rt_bvh *bvh, rt_arena *arena,
                          const rt_workers *workers);

/* Bytes of scratch one worker needs to collapse wide roots of up to `refs` references. */
size_t rt_bvh_block_scratch_size(uint32_t refs);
/* Collapses the wide root bin[root], over `count` references from `first`, in scratch
 * (rt_bvh_block_scratch_size(scratch_refs) bytes, 64-byte aligned) into a block that
 * it stores in the slots of the root's descendants (bvh_binary.h's numbering), which
 * are dead then, and marks the root RT_BIN_COLLAPSED. When the block does not fit
 * there, it changes nothing and the final collapse makes those nodes. */
void rt_bvh_collapse_block(rt_bin_node *bin, uint32_t root, uint32_t first, uint32_t count, int grid, void *scratch,
                           uint32_t scratch_refs);
/* The tree of a scene without primitives: a root whose slots are all empty. */
rt_status rt_bvh_empty(rt_bvh *bvh, rt_arena *arena);

#endif

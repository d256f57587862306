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

/* Stores b rounded outwards on the tree's grid. */
void rt_bvh_store_box(rt_bound box[6], rt_aabb b, int grid);

/* Collapses the binary tree at bin (root node 0, `inner` inner nodes) into the wide
 * tree on bvh->grid: bvh->nodes (in the arena, 64-byte aligned), node_count, depth. */
rt_status rt_bvh_collapse(const rt_bin_node *bin, uint32_t inner, rt_bvh *bvh, rt_arena *arena);
/* The tree of a scene without primitives: a root whose slots are all empty. */
rt_status rt_bvh_empty(rt_bvh *bvh, rt_arena *arena);

#endif

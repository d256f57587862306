/* Bounding volume hierarchy over a scene's primitives: a binned SAH build (bvh.c)
 * collapsed into a wide tree (RT_BVH_WIDTH children a node, bvh_collapse.c) that the scene queries walk
 * (scene_query.h). */
#ifndef RT_BVH_H
#define RT_BVH_H

#include "scene.h"
#include "workers.h"

/* Deepest binary tree the builder makes (the wide tree is at most as deep);
 * traversal stacks are sized by it. */
#define RT_BVH_MAX_DEPTH 64

/* The slots of a wide node, and every pair of them (a < b): the cases of the walks'
 * switches over one or two hit children. */
/* clang-format off */
#if RT_BVH_WIDTH == 8
#define RT_BVH_SLOTS(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7)
#define RT_BVH_SLOT_PAIRS(X) \
    X(0, 1) X(0, 2) X(0, 3) X(0, 4) X(0, 5) X(0, 6) X(0, 7) X(1, 2) X(1, 3) X(1, 4) X(1, 5) X(1, 6) X(1, 7) \
    X(2, 3) X(2, 4) X(2, 5) X(2, 6) X(2, 7) X(3, 4) X(3, 5) X(3, 6) X(3, 7) X(4, 5) X(4, 6) X(4, 7) \
    X(5, 6) X(5, 7) X(6, 7)
#else
#define RT_BVH_SLOTS(X) X(0) X(1) X(2) X(3)
#define RT_BVH_SLOT_PAIRS(X) X(0, 1) X(0, 2) X(0, 3) X(1, 2) X(1, 3) X(2, 3)
#endif
/* clang-format on */

/* How the build divides its work into jobs. Every plan gives the same tree, bit for bit:
 * a plan only decides which parts may run at once. */
typedef struct {
    /* Tasks of more references than this are split one level at a time, each split a job
     * of its own; smaller ones are built whole, one job each. */
    uint32_t split_above;
    uint32_t chunk; /* references per job where many references are bounded or binned */
} rt_bvh_plan;

rt_bvh_plan rt_bvh_default_plan(void);

/* Builds scene->bvh over scene->prim_count primitives, with the default plan, on the
 * workers (NULL: on this thread). Scratch comes from the arena too. */
rt_status rt_bvh_build(rt_scene *scene, rt_arena *arena, const rt_workers *workers);
rt_status rt_bvh_build_planned(rt_scene *scene, rt_arena *arena, const rt_workers *workers, rt_bvh_plan plan);

/* Child c's box as stored (holding the exact bounds it was built from). */
rt_aabb rt_bvh_child_box(const rt_bvh *bvh, const rt_bvh_node *node, int c);

/* The world-space bounds of primitive `prim`. */
rt_aabb rt_bvh_prim_bounds(const rt_scene *scene, uint32_t prim);

/* Whether this build of the core has kernel k (the CPU must have its instructions too). */
bool rt_bvh_kernel_compiled(rt_kernel k);
/* Sets the BVH's kernel to k if the core has it; returns whether it did. */
bool rt_bvh_set_kernel(rt_bvh *bvh, rt_kernel k);
/* Whether the BVH's kernel traces the stream queries in packets. */
bool rt_bvh_packets(const rt_bvh *bvh);

#endif

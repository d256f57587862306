/* The binary SAH tree (bvh_binary.h) collapsed into the wide tree of bvh.h. */
#include "bvh_binary.h"
#include "invariant.h"

void rt_bvh_store_box(rt_bound box[6], rt_aabb b, int grid)
{
    box[0] = rt_bound_below(b.lo.x, grid);
    box[1] = rt_bound_below(b.lo.y, grid);
    box[2] = rt_bound_below(b.lo.z, grid);
    box[3] = rt_bound_above(b.hi.x, grid);
    box[4] = rt_bound_above(b.hi.y, grid);
    box[5] = rt_bound_above(b.hi.z, grid);
}

static rt_aabb stored_box(rt_bound lo_x, rt_bound lo_y, rt_bound lo_z, rt_bound hi_x, rt_bound hi_y, rt_bound hi_z,
                          int g)
{
    rt_aabb r = {rt_v3(rt_bound_value(lo_x, g), rt_bound_value(lo_y, g), rt_bound_value(lo_z, g)),
                 rt_v3(rt_bound_value(hi_x, g), rt_bound_value(hi_y, g), rt_bound_value(hi_z, g))};
    return r;
}

rt_aabb rt_bvh_child_box(const rt_bvh *bvh, const rt_bvh_node *node, int c)
{
    return stored_box(node->box[0][c], node->box[1][c], node->box[2][c], node->box[3][c], node->box[4][c],
                      node->box[5][c], bvh->grid);
}

static rt_aabb bin_box(const rt_bin_node *n, int g)
{
    return stored_box(n->box[0], n->box[1], n->box[2], n->box[3], n->box[4], n->box[5], g);
}

/* Up to RT_BVH_WIDTH binary nodes that together cover binary node b's references: its
 * children, then repeatedly the largest-area inner one replaced by its own two. */
static int gather_children(const rt_bin_node *bin, uint32_t b, int grid, uint32_t out[RT_BVH_WIDTH])
{
    if (bin[b].count > 0) {
        out[0] = b; /* a leaf root: one leaf child */
        return 1;
    }
    int n = 2;
    out[0] = bin[b].first;
    out[1] = bin[b].first + 1;
    while (n < RT_BVH_WIDTH) {
        int widest = -1;
        rt_real widest_area = RT_ZERO;
        for (int c = 0; c < n; c++) {
            rt_real area = rt_aabb_half_area(bin_box(&bin[out[c]], grid));
            if (bin[out[c]].count == 0 && (widest < 0 || area > widest_area)) widest = c, widest_area = area;
        }
        if (widest < 0) break;
        /* The other inner children may be opened next, or become nodes: fetch their children at once. */
        for (int c = 0; c < n; c++)
            if (c != widest && bin[out[c]].count == 0) __builtin_prefetch(&bin[bin[out[c]].first]);
        uint32_t opened = out[widest];
        out[widest] = bin[opened].first;
        out[n++] = bin[opened].first + 1;
    }
    return n;
}

static void clear_slot(rt_bvh_node *node, int c, int grid)
{
    rt_bound empty[6];
    rt_bvh_store_box(empty, rt_aabb_empty(), grid);
    for (int k = 0; k < 6; k++) node->box[k][c] = empty[k];
    node->child[c] = 0;
    node->count[c] = RT_BVH_NO_CHILD;
}

typedef struct {
    uint32_t bin, wide, depth;
} collapse_task;

/* Each wide level pushes at most RT_BVH_WIDTH tasks, over at most RT_BVH_MAX_DEPTH levels. */
#define COLLAPSE_STACK (RT_BVH_MAX_DEPTH * RT_BVH_WIDTH + 1)

/* Wide nodes are allocated one by one as they are numbered: whole cache lines at 64-byte
 * alignment, so the arena places them end to end after node 0, and the tree takes its own
 * size, not the bound of one node per binary inner node. */
_Static_assert(sizeof(rt_bvh_node) % 64 == 0, "nodes allocated one by one lie end to end");

/* Wide nodes are numbered depth first from wide (node 0, allocated); returns their count,
 * or 0 when the arena is full. */
static uint32_t collapse(const rt_bin_node *bin, int grid, rt_arena *arena, rt_bvh_node *wide, collapse_task *stack,
                         uint32_t *depth)
{
    uint32_t top = 0, count = 1;
    stack[top++] = (collapse_task){0, 0, 1};
    *depth = 1;
    while (top > 0) {
        collapse_task t = stack[--top];
        rt_bvh_node *node = &wide[t.wide];
        uint32_t kids[RT_BVH_WIDTH];
        int n = gather_children(bin, t.bin, grid, kids);
        for (int c = RT_BVH_WIDTH - 1; c >= 0; c--) {
            if (c >= n) {
                clear_slot(node, c, grid);
                continue;
            }
            const rt_bin_node *kid = &bin[kids[c]];
            for (int k = 0; k < 6; k++) node->box[k][c] = kid->box[k];
            if (t.depth + 1 > *depth) *depth = t.depth + 1;
            node->count[c] = kid->count;
            if (kid->count > 0) {
                node->child[c] = kid->first;
                continue;
            }
            if (!rt_arena_alloc_aligned(arena, sizeof(rt_bvh_node), 64)) return 0;
            node->child[c] = count;
            /* Its children are read when it is popped: far apart in the binary tree's slots. */
            __builtin_prefetch(&bin[kid->first]);
            RT_ASSERT(top < COLLAPSE_STACK);
            stack[top++] = (collapse_task){kids[c], count++, t.depth + 1};
        }
    }
    return count;
}

rt_status rt_bvh_collapse(const rt_bin_node *bin, uint32_t inner, rt_bvh *bvh, rt_arena *arena)
{
    collapse_task *stack = RT_NEW_ARRAY(arena, collapse_task, COLLAPSE_STACK);
    bvh->nodes = stack ? rt_arena_alloc_aligned(arena, sizeof(rt_bvh_node), 64) : NULL; /* node 0 */
    if (!bvh->nodes) return RT_ERR_NOMEM;
    bvh->node_count = collapse(bin, bvh->grid, arena, bvh->nodes, stack, &bvh->depth);
    if (bvh->node_count == 0) return RT_ERR_NOMEM;
    /* At most one wide node per binary inner node, or one (checked in the asserts build). */
    (void)inner;
    RT_ASSERT(bvh->node_count <= inner + 1);
    return RT_OK;
}

rt_status rt_bvh_empty(rt_bvh *bvh, rt_arena *arena)
{
    bvh->grid = rt_bound_grid(RT_ONE);
    bvh->extent = RT_ZERO;
    bvh->nodes = rt_arena_alloc_aligned(arena, sizeof(rt_bvh_node), 64);
    if (!bvh->nodes) return RT_ERR_NOMEM;
    for (int c = 0; c < RT_BVH_WIDTH; c++) clear_slot(bvh->nodes, c, bvh->grid);
    bvh->node_count = 1;
    bvh->depth = 1;
    return RT_OK;
}

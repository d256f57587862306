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

/* Whether binary node n is a leaf (inner nodes' counts are 0, RT_BIN_WIDE_ROOT or
 * RT_BIN_COLLAPSED). */
static bool bin_leaf(const rt_bin_node *n) { return n->count != 0 && n->count < RT_BIN_COLLAPSED; }

/* Up to RT_BVH_WIDTH binary nodes that together cover binary node b's references: its
 * children, then repeatedly the largest-area inner one replaced by its own two; wide
 * roots are not opened. */
static int gather_children(const rt_bin_node *bin, uint32_t b, int grid, uint32_t out[RT_BVH_WIDTH])
{
    if (bin_leaf(&bin[b])) {
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

/* Wide nodes are allocated as they are numbered: whole cache lines at 64-byte alignment,
 * so the arena places them end to end after node 0, and the tree takes its own size, not
 * the bound of one node per binary inner node. */
_Static_assert(sizeof(rt_bvh_node) % 64 == 0, "nodes allocated one by one lie end to end");

/* Where the wide nodes go: from the arena (the tree), or into an array of cap (a block). */
typedef struct {
    rt_bvh_node *nodes;
    uint32_t count, cap;
    rt_arena *arena;
} wide_nodes;

/* Takes the next k nodes; false when the arena is full or the array would overflow. */
static bool take_nodes(wide_nodes *w, uint32_t k)
{
    if (w->arena ? !rt_arena_alloc_aligned(w->arena, (size_t)k * sizeof(rt_bvh_node), 64) : k > w->cap - w->count)
        return false;
    w->count += k;
    return true;
}

/* A wide root's block (RT_BIN_COLLAPSED) met by the final collapse, which gives it its
 * place: its node 0 at `wide`, the others as the nodes from `base` on, in their order,
 * which is the one the collapse would give them. Blocks are copied after the walk, in
 * jobs of their own (rt_bvh_collapse). */
typedef struct {
    uint32_t bin, wide, base;
} block_copy;

typedef struct {
    block_copy *items;
    uint32_t count, cap;
} block_list;

/* Takes the places of wide root t's block in w and lists it in `blocks` for its copy. */
static bool place_block(const rt_bin_node *bin, collapse_task t, wide_nodes *w, block_list *blocks, uint32_t *depth)
{
    uint32_t head = bin[t.bin].first, count = bin[head].first, base = w->count;
    if (blocks->count == blocks->cap || !take_nodes(w, count - 1)) return false;
    blocks->items[blocks->count++] = (block_copy){t.bin, t.wide, base};
    if (t.depth + bin[head].count - 1 > *depth) *depth = t.depth + bin[head].count - 1;
    return true;
}

/* Copies a placed block into the nodes of the tree. */
static void copy_block(const rt_bin_node *bin, block_copy b, rt_bvh_node *nodes)
{
    uint32_t head = bin[b.bin].first, count = bin[head].first;
    const unsigned char *from = (const unsigned char *)&bin[head + 1];
    for (uint32_t k = 0; k < count; k++) {
        rt_bvh_node *node = &nodes[k == 0 ? b.wide : b.base + k - 1];
        __builtin_memcpy(node, from + (size_t)k * sizeof(rt_bvh_node), sizeof(rt_bvh_node));
        for (int c = 0; c < RT_BVH_WIDTH; c++)
            if (node->count[c] == 0) node->child[c] += b.base - 1;
    }
}

/* Wide nodes are numbered depth first from w's node `wide` (taken), made from binary node
 * `root`, and the blocks met placed and listed in `blocks`; returns false when w or
 * `blocks` is full. */
static bool collapse(const rt_bin_node *bin, uint32_t root, int grid, wide_nodes *w, collapse_task *stack,
                     block_list *blocks, uint32_t *depth)
{
    uint32_t top = 0;
    stack[top++] = (collapse_task){root, w->count - 1, 1};
    *depth = 1;
    while (top > 0) {
        collapse_task t = stack[--top];
        if (bin[t.bin].count == RT_BIN_COLLAPSED) {
            if (!place_block(bin, t, w, blocks, depth)) return false;
            continue;
        }
        rt_bvh_node *node = &w->nodes[t.wide];
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
            if (bin_leaf(kid)) {
                node->count[c] = kid->count;
                node->child[c] = kid->first;
                continue;
            }
            if (!take_nodes(w, 1)) return false;
            node->count[c] = 0;
            node->child[c] = w->count - 1;
            /* Its children are read when it is popped: far apart in the binary tree's slots. */
            __builtin_prefetch(&bin[kid->first]);
            RT_ASSERT(top < COLLAPSE_STACK);
            stack[top++] = (collapse_task){kids[c], w->count - 1, t.depth + 1};
        }
    }
    return true;
}

typedef struct {
    const rt_bin_node *bin;
    const block_list *blocks;
    rt_bvh_node *nodes;
} copy_jobs;

static void copy_block_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    const copy_jobs *j = arg;
    copy_block(j->bin, j->blocks->items[index], j->nodes);
}

rt_status rt_bvh_collapse(const rt_bin_node *bin, uint32_t inner, uint32_t blocks, rt_bvh *bvh, rt_arena *arena,
                          const rt_workers *workers)
{
    collapse_task *stack = RT_NEW_ARRAY(arena, collapse_task, COLLAPSE_STACK);
    block_list list = {RT_NEW_ARRAY(arena, block_copy, blocks > 0 ? blocks : 1), 0, blocks};
    bvh->nodes = stack && list.items ? rt_arena_alloc_aligned(arena, sizeof(rt_bvh_node), 64) : NULL; /* node 0 */
    if (!bvh->nodes) return RT_ERR_NOMEM;
    wide_nodes w = {bvh->nodes, 1, 0, arena};
    if (!collapse(bin, 0, bvh->grid, &w, stack, &list, &bvh->depth)) return RT_ERR_NOMEM;
    bvh->node_count = w.count;
    copy_jobs jobs = {bin, &list, bvh->nodes};
    rt_workers_run(workers, copy_block_job, &jobs, list.count);
    /* At most one wide node per binary inner node, or one (checked in the asserts build). */
    (void)inner;
    RT_ASSERT(bvh->node_count <= inner + 1);
    return RT_OK;
}

/* The wide nodes that fit in the 2 count - 3 slots after a block's head (bvh_binary.h),
 * for a wide root of count (at least 2) references. */
static uint32_t block_room(uint32_t count) { return (2 * count - 3) * sizeof(rt_bin_node) / sizeof(rt_bvh_node); }

/* A block's scratch: its collapse's stack, then its nodes (64-byte aligned). */
#define BLOCK_STACK_BYTES ((COLLAPSE_STACK * sizeof(collapse_task) + 63) / 64 * 64)

size_t rt_bvh_block_scratch_size(uint32_t refs)
{
    return BLOCK_STACK_BYTES + (refs < 2 ? 0 : block_room(refs)) * sizeof(rt_bvh_node);
}

void rt_bvh_collapse_block(rt_bin_node *bin, uint32_t root, uint32_t first, uint32_t count, int grid, void *scratch,
                           uint32_t scratch_refs)
{
    uint32_t room = block_room(count < scratch_refs ? count : scratch_refs), depth;
    wide_nodes w = {(rt_bvh_node *)((unsigned char *)scratch + BLOCK_STACK_BYTES), 1, room, NULL};
    block_list none = {NULL, 0, 0}; /* a wide root holds no other */
    if (room < 1 || !collapse(bin, root, grid, &w, scratch, &none, &depth)) return;
    uint32_t head = 2 * first + 1;
    __builtin_memcpy(&bin[head + 1], w.nodes, (size_t)w.count * sizeof(rt_bvh_node));
    bin[head].first = w.count;
    bin[head].count = depth;
    bin[root].first = head;
    bin[root].count = RT_BIN_COLLAPSED;
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

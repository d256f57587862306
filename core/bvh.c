/* Binned-SAH BVH build, collapsed into a 4-wide tree; see bvh.h (queries: bvh_query.c). */
#include "bvh.h"

#define BIN_COUNT 16
/* Leaves hold LEAF_MIN references or fewer without asking, at most LEAF_MAX; in between
 * the SAH decides, pricing a node visit at TRAVERSAL_COST primitive tests. */
#define LEAF_MIN 4
#define LEAF_MAX 8
#define TRAVERSAL_COST RT_C(3.0)

static rt_aabb aabb_empty(void)
{
    rt_aabb b = {{RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX}, {rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX)}};
    return b;
}

static rt_aabb aabb_union(rt_aabb a, rt_aabb b)
{
    rt_aabb r = {rt_v3_min(a.lo, b.lo), rt_v3_max(a.hi, b.hi)};
    return r;
}

static rt_aabb aabb_add_point(rt_aabb a, rt_vec3 p)
{
    rt_aabb r = {rt_v3_min(a.lo, p), rt_v3_max(a.hi, p)};
    return r;
}

/* Half the surface area: all the SAH needs. */
static rt_real aabb_half_area(rt_aabb b)
{
    if (b.lo.x > b.hi.x) return RT_ZERO;
    rt_vec3 e = rt_v3_sub(b.hi, b.lo);
    return rt_add(rt_add(rt_mul(e.x, e.y), rt_mul(e.y, e.z)), rt_mul(e.z, e.x));
}

/* The largest absolute coordinate of a box's corners. */
static rt_real aabb_magnitude(rt_aabb b)
{
    rt_vec3 extent = rt_v3_max(rt_v3(rt_abs(b.lo.x), rt_abs(b.lo.y), rt_abs(b.lo.z)),
                               rt_v3(rt_abs(b.hi.x), rt_abs(b.hi.y), rt_abs(b.hi.z)));
    return rt_max(rt_max(extent.x, extent.y), extent.z);
}

/* Widens a box by 2^-20 of its magnitude (plus 2^-20 absolute) so that slab-test and
 * intersection rounding never cull a primitive's true hit: ample for double, and many
 * lsb for Q32.32. A wider box only costs a few extra tests. */
static rt_aabb aabb_pad(rt_aabb b)
{
    rt_real pad = rt_mul(rt_add(aabb_magnitude(b), RT_ONE), RT_C(0.00000095367431640625));
    rt_vec3 p = rt_v3(pad, pad, pad);
    rt_aabb r = {rt_v3_sub(b.lo, p), rt_v3_add(b.hi, p)};
    return r;
}

rt_aabb rt_prim_bounds(const rt_scene *scene, uint32_t prim)
{
    if (prim < scene->triangle_count) {
        const rt_triangle *tri = &scene->triangles[prim];
        rt_aabb b = aabb_empty();
        for (int k = 0; k < 3; k++) b = aabb_add_point(b, scene->positions[tri->v[k]]);
        return aabb_pad(b);
    }
    /* A quadric fills at most its object-space cube [-0.5, 0.5]^3. */
    const rt_object *obj = &scene->objects[scene->quadric_objects[prim - scene->triangle_count]];
    const rt_mat3 *m = &obj->to_world.linear;
    rt_vec3 half = rt_v3(rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[0][0]), rt_abs(m->m[0][1])), rt_abs(m->m[0][2]))),
                         rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[1][0]), rt_abs(m->m[1][1])), rt_abs(m->m[1][2]))),
                         rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[2][0]), rt_abs(m->m[2][1])), rt_abs(m->m[2][2]))));
    rt_aabb b = {rt_v3_sub(obj->to_world.translation, half), rt_v3_add(obj->to_world.translation, half)};
    return aabb_pad(b);
}

/* ---- Build ---- */

/* A primitive being sorted into the tree: its padded bounds travel with it, so each
 * node's passes read its references in order instead of gathering them. */
typedef struct {
    rt_aabb bounds;
    uint32_t prim;
} build_ref;

typedef struct {
    uint32_t node, first, count, depth;
    rt_aabb bounds, centroids; /* of the references, from the parent's bins and partition */
} build_task;

/* The box centre, as the binning sees the primitive. */
static rt_vec3 centroid_of(const build_ref *r) { return rt_v3_scale(rt_v3_add(r->bounds.lo, r->bounds.hi), RT_C(0.5)); }

static int bin_of(rt_real c, rt_real lo, rt_real scale)
{
    int32_t b = rt_floor_int(rt_mul(rt_sub(c, lo), scale));
    return b < 0 ? 0 : b >= BIN_COUNT ? BIN_COUNT - 1 : (int)b;
}

typedef struct {
    int axis, bin;          /* refs in bins <= bin go left */
    rt_real lo, scale;      /* the axis' binning */
    rt_aabb left, right;    /* the children's bounds, unions of their bins */
} split;

/* Finds the cheapest binned split of a task's references, binning all three axes in one
 * pass; false if a leaf is cheaper (and the task may be a leaf), or nothing splits. */
static bool choose_split(const build_ref *refs, const build_task *t, split *out)
{
    rt_aabb box[3][BIN_COUNT];
    uint32_t n_in[3][BIN_COUNT];
    rt_real lo[3], scale[3];
    bool active[3];
    for (int axis = 0; axis < 3; axis++) {
        lo[axis] = rt_v3_get(t->centroids.lo, axis);
        rt_real hi = rt_v3_get(t->centroids.hi, axis);
        active[axis] = hi > lo[axis];
        /* A flat axis bins everything into bin 0 (scale 0) and is never priced. */
        scale[axis] = active[axis] ? rt_div(rt_from_int(BIN_COUNT), rt_sub(hi, lo[axis])) : RT_ZERO;
        for (int b = 0; b < BIN_COUNT; b++) {
            box[axis][b] = aabb_empty();
            n_in[axis][b] = 0;
        }
    }
    for (uint32_t i = t->first; i < t->first + t->count; i++) {
        rt_vec3 c = centroid_of(&refs[i]);
        int bx = bin_of(c.x, lo[0], scale[0]), by = bin_of(c.y, lo[1], scale[1]), bz = bin_of(c.z, lo[2], scale[2]);
        box[0][bx] = aabb_union(box[0][bx], refs[i].bounds);
        box[1][by] = aabb_union(box[1][by], refs[i].bounds);
        box[2][bz] = aabb_union(box[2][bz], refs[i].bounds);
        n_in[0][bx]++;
        n_in[1][by]++;
        n_in[2][bz]++;
    }
    /* Costs relative to one primitive test over the task's area. */
    rt_real best_cost = t->count > LEAF_MAX ? RT_REAL_MAX : rt_mul(rt_from_int(t->count), aabb_half_area(t->bounds));
    rt_real visit = rt_mul(TRAVERSAL_COST, aabb_half_area(t->bounds));
    bool found = false;
    for (int axis = 0; axis < 3; axis++) {
        if (!active[axis]) continue;
        /* Sweep from the right to get suffix areas, then from the left to price each plane. */
        rt_real right_area[BIN_COUNT];
        uint32_t right_n[BIN_COUNT];
        rt_aabb acc = aabb_empty();
        uint32_t n = 0;
        for (int b = BIN_COUNT - 1; b > 0; b--) {
            acc = aabb_union(acc, box[axis][b]);
            n += n_in[axis][b];
            right_area[b] = aabb_half_area(acc);
            right_n[b] = n;
        }
        acc = aabb_empty();
        n = 0;
        for (int b = 0; b < BIN_COUNT - 1; b++) {
            acc = aabb_union(acc, box[axis][b]);
            n += n_in[axis][b];
            if (n == 0 || right_n[b + 1] == 0) continue;
            rt_real cost = rt_add(visit, rt_add(rt_mul(rt_from_int(n), aabb_half_area(acc)),
                                                rt_mul(rt_from_int(right_n[b + 1]), right_area[b + 1])));
            if (cost < best_cost) {
                best_cost = cost;
                found = true;
                out->axis = axis;
                out->bin = b;
            }
        }
    }
    if (!found) return false;
    out->lo = lo[out->axis];
    out->scale = scale[out->axis];
    out->left = out->right = aabb_empty();
    for (int b = 0; b < BIN_COUNT; b++) {
        rt_aabb *side = b <= out->bin ? &out->left : &out->right;
        *side = aabb_union(*side, box[out->axis][b]);
    }
    return true;
}

/* Moves the references of bins <= s->bin to the front and returns their count; the
 * children's centroid bounds are gathered on the way. */
static uint32_t partition(build_ref *refs, uint32_t first, uint32_t count, const split *s, rt_aabb *left_c,
                          rt_aabb *right_c)
{
    *left_c = *right_c = aabb_empty();
    uint32_t i = first, j = first + count;
    while (i < j) {
        rt_vec3 c = centroid_of(&refs[i]);
        if (bin_of(rt_v3_get(c, s->axis), s->lo, s->scale) <= s->bin) {
            *left_c = aabb_add_point(*left_c, c);
            i++;
        } else {
            *right_c = aabb_add_point(*right_c, c);
            j--;
            build_ref swap = refs[i];
            refs[i] = refs[j];
            refs[j] = swap;
        }
    }
    return i - first;
}

/* A node of the binary tree the SAH builds, in scratch, before it is collapsed into the
 * 4-wide tree: its box as stored, and children nodes[first], nodes[first + 1] (count 0)
 * or references prim_refs[first .. first + count). */
typedef struct {
    rt_bound box[6];
    uint32_t first, count;
} bin_node;

static void store_box(rt_bound box[6], rt_aabb b, int grid)
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

static rt_aabb bin_box(const bin_node *n, int g)
{
    return stored_box(n->box[0], n->box[1], n->box[2], n->box[3], n->box[4], n->box[5], g);
}

/* Builds the binary SAH tree over n > 0 references into bin (room for 2n - 1 nodes);
 * returns its node count. refs end up in leaf order. */
static uint32_t build_binary(const rt_scene *scene, build_ref *refs, uint32_t n, bin_node *bin, build_task *stack,
                             int *grid)
{
    build_task root = {0, 0, n, 1, aabb_empty(), aabb_empty()};
    for (uint32_t i = 0; i < n; i++) {
        refs[i].bounds = rt_prim_bounds(scene, i);
        refs[i].prim = i;
        root.bounds = aabb_union(root.bounds, refs[i].bounds);
        root.centroids = aabb_add_point(root.centroids, centroid_of(&refs[i]));
    }
    *grid = rt_bound_grid(aabb_magnitude(root.bounds));
    uint32_t count = 1, top = 0;
    stack[top++] = root;
    while (top > 0) {
        build_task task = stack[--top];
        bin_node *node = &bin[task.node];
        store_box(node->box, task.bounds, *grid);
        node->first = task.first;
        node->count = task.count;
        split s;
        if (task.count <= LEAF_MIN || task.depth >= RT_BVH_MAX_DEPTH || !choose_split(refs, &task, &s)) continue;
        rt_aabb left_c, right_c;
        uint32_t left_n = partition(refs, task.first, task.count, &s, &left_c, &right_c);
        uint32_t left = count;
        count += 2;
        node->first = left;
        node->count = 0;
        /* Push right first so the left subtree is built next (depth-first, bounded stack). */
        stack[top++] = (build_task){left + 1, task.first + left_n, task.count - left_n, task.depth + 1, s.right, right_c};
        stack[top++] = (build_task){left, task.first, left_n, task.depth + 1, s.left, left_c};
    }
    return count;
}

/* Up to RT_BVH_WIDTH binary nodes that together cover binary node b's references: its
 * children, then repeatedly the largest-area inner one replaced by its own two. */
static int gather_children(const bin_node *bin, uint32_t b, int grid, uint32_t out[RT_BVH_WIDTH])
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
            rt_real area = aabb_half_area(bin_box(&bin[out[c]], grid));
            if (bin[out[c]].count == 0 && (widest < 0 || area > widest_area)) widest = c, widest_area = area;
        }
        if (widest < 0) break;
        uint32_t opened = out[widest];
        out[widest] = bin[opened].first;
        out[n++] = bin[opened].first + 1;
    }
    return n;
}

static void clear_slot(rt_bvh_node *node, int c, int grid)
{
    rt_bound empty[6];
    store_box(empty, aabb_empty(), grid);
    for (int k = 0; k < 6; k++) node->box[k][c] = empty[k];
    node->child[c] = 0;
    node->count[c] = RT_BVH_NO_CHILD;
}

/* Collapses the binary tree into wide nodes at `wide` (room for one per binary inner
 * node, and one); returns the wide node count. Nodes are numbered depth first. */
typedef struct {
    uint32_t bin, wide, depth;
} collapse_task;

/* Each wide level pushes at most RT_BVH_WIDTH tasks, over at most RT_BVH_MAX_DEPTH levels. */
#define COLLAPSE_STACK (RT_BVH_MAX_DEPTH * RT_BVH_WIDTH + 1)

static uint32_t collapse(const bin_node *bin, int grid, rt_bvh_node *wide, collapse_task *stack, uint32_t *depth)
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
            const bin_node *kid = &bin[kids[c]];
            for (int k = 0; k < 6; k++) node->box[k][c] = kid->box[k];
            if (t.depth + 1 > *depth) *depth = t.depth + 1;
            node->count[c] = kid->count;
            if (kid->count > 0) {
                node->child[c] = kid->first;
                continue;
            }
            node->child[c] = count;
            stack[top++] = (collapse_task){kids[c], count++, t.depth + 1};
        }
    }
    return count;
}

/* The wide nodes start on a 64-byte boundary: each is two whole cache lines. */
static rt_bvh_node *alloc_nodes(rt_arena *arena, size_t count)
{
    return rt_arena_alloc_aligned(arena, count * sizeof(rt_bvh_node), 64);
}

/* The binary tree and the wide one are made in scratch above the arena's mark; then the
 * arena is reset and the wide nodes are copied down to the mark, at their final size. */
rt_status rt_bvh_build(rt_scene *scene, rt_arena *arena)
{
    uint32_t n = scene->prim_count;
    rt_bvh *bvh = &scene->bvh;
    bvh->prim_refs = RT_NEW_ARRAY(arena, uint32_t, n > 0 ? n : 1);
    if (!bvh->prim_refs) return RT_ERR_NOMEM;
    size_t mark = rt_arena_mark(arena);
    uint32_t bin_count = 1;
    bvh->grid = rt_bound_grid(RT_ONE);
    /* Every node and reference is written before it is read: no zeroing. */
    bin_node *bin = rt_arena_alloc(arena, (n > 0 ? 2 * (size_t)n - 1 : 1) * sizeof(bin_node));
    build_ref *refs = n > 0 ? rt_arena_alloc(arena, (size_t)n * sizeof(build_ref)) : NULL;
    build_task *stack = RT_NEW_ARRAY(arena, build_task, RT_BVH_MAX_DEPTH + 2);
    if (!bin || (n > 0 && !refs) || !stack) return RT_ERR_NOMEM;
    if (n > 0) bin_count = build_binary(scene, refs, n, bin, stack, &bvh->grid);
    for (uint32_t i = 0; i < n; i++) bvh->prim_refs[i] = refs[i].prim;
    /* At most one wide node per binary inner node, or one. */
    rt_bvh_node *wide = alloc_nodes(arena, bin_count / 2 + 1);
    collapse_task *tasks = RT_NEW_ARRAY(arena, collapse_task, COLLAPSE_STACK);
    if (!wide || !tasks) return RT_ERR_NOMEM;
    uint32_t depth = 1;
    if (n > 0) {
        bvh->node_count = collapse(bin, bvh->grid, wide, tasks, &depth);
    } else { /* no primitives: a root without children */
        bvh->node_count = 1;
        for (int c = 0; c < RT_BVH_WIDTH; c++) clear_slot(wide, c, bvh->grid);
    }
    bvh->depth = depth;
    rt_arena_reset(arena, mark);
    bvh->nodes = alloc_nodes(arena, bvh->node_count);
    /* Below the scratch copy, which starts past the binary tree: a forward copy never
     * overwrites a node it has yet to read. */
    for (uint32_t i = 0; i < bvh->node_count; i++) bvh->nodes[i] = wide[i];
    return RT_OK;
}

/* Binned-SAH BVH build and traversal; see bvh.h. */
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

static bool quadric_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit);

/* Inline in the BVH's leaf loop, where a triangle test is most of the work; kx, ky, kz
 * are rs's axis permutation (see rt_intersect_triangle_axes). */
__attribute__((always_inline)) static inline bool prim_intersect(const rt_scene *scene, uint32_t prim,
                                                                 const rt_ray_setup *rs, rt_prim_hit *hit, int kx,
                                                                 int ky, int kz)
{
    if (prim >= scene->triangle_count) return quadric_intersect(scene, prim, rs, hit);
    const rt_triangle *tri = &scene->triangles[prim];
    return rt_intersect_triangle_axes(rs, scene->positions[tri->v[0]], scene->positions[tri->v[1]],
                                      scene->positions[tri->v[2]], hit, kx, ky, kz);
}

bool rt_prim_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit)
{
    return prim_intersect(scene, prim, rs, hit, rs->kx, rs->ky, rs->kz);
}

static bool quadric_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit)
{
    const rt_object *obj = &scene->objects[scene->quadric_objects[prim - scene->triangle_count]];
    rt_vec3 o = rt_affine_point(&obj->to_object, rs->ray.origin);
    rt_vec3 d = rt_affine_vector(&obj->to_object, rs->ray.direction);
    /* Solve with a unit object-space direction and scale t back: the short direction of a
     * scaled-up object would leave Q32.32 only a few bits in d.d. */
    rt_real len = rt_v3_length(d);
    if (!(len > RT_ZERO)) return false;
    rt_vec3 unit = rt_v3_scale(d, rt_div(RT_ONE, len));
    rt_real t_min = rt_mul(rs->ray.t_min, len), t_max = rt_mul(rs->ray.t_max, len);
    bool found = obj->kind == RT_SHAPE_SPHERE ? rt_intersect_sphere(o, unit, t_min, t_max, hit)
                                              : rt_intersect_cylinder(o, unit, t_min, t_max, hit);
    if (!found) return false;
    hit->t = rt_div(hit->t, len);
    return hit->t > rs->ray.t_min && hit->t < rs->ray.t_max;
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
    if (n > 0) {
        bin_count = build_binary(scene, refs, n, bin, stack, &bvh->grid);
    } else { /* an empty leaf: the root gets no children */
        store_box(bin[0].box, aabb_empty(), bvh->grid);
        bin[0].first = bin[0].count = 0;
    }
    for (uint32_t i = 0; i < n; i++) bvh->prim_refs[i] = refs[i].prim;
    /* At most one wide node per binary inner node, or one. */
    rt_bvh_node *wide = alloc_nodes(arena, bin_count / 2 + 1);
    collapse_task *tasks = RT_NEW_ARRAY(arena, collapse_task, COLLAPSE_STACK);
    if (!wide || !tasks) return RT_ERR_NOMEM;
    uint32_t depth;
    bvh->node_count = n > 0 ? collapse(bin, bvh->grid, wide, tasks, &depth) : 1;
    if (n == 0) {
        depth = 1;
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

/* ---- Queries ---- */

/* The double build tests a node's four children two at a time with SSE2 (x86-64's
 * baseline); the fixed build and other targets test them one by one. The SSE2
 * operations are the compilers' own builtins (the core includes no intrinsics header). */
#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
#define SLAB_SSE2 1
typedef double v2df __attribute__((vector_size(16)));
typedef float v4sf __attribute__((vector_size(16), aligned(4), may_alias));
typedef uint32_t v4su __attribute__((vector_size(16), aligned(4), may_alias));

/* Lanes 0, 1 (lo) or 2, 3 (hi) of four floats, as doubles: one cvtps2pd either way. */
static inline v2df v2df_from_lo(v4sf a)
{
#ifdef __clang__
    return __builtin_convertvector(__builtin_shufflevector(a, a, 0, 1), v2df);
#else
    return __builtin_ia32_cvtps2pd(a);
#endif
}
static inline v2df v2df_from_hi(v4sf a)
{
#ifdef __clang__
    return __builtin_convertvector(__builtin_shufflevector(a, a, 2, 3), v2df);
#else
    return __builtin_ia32_cvtps2pd(__builtin_ia32_movhlps(a, a));
#endif
}
#else
#define SLAB_SSE2 0
#endif

#ifdef RT_REAL_FIXED
/* The fixed build's box test in plain 64-bit integers. Culling only has to be
 * conservative (a box is never missed where the exact test hits it; the boxes are
 * padded beyond any rounding of a hit's t), so instead of rounded, saturated Q32.32
 * products it bounds each plane's distance from below (near planes) or above (far
 * planes) in a per-ray unit of distance: with the plane b and o_lo = floor(origin) in
 * the tree's grid units, d = b - o_lo, and m = floor(inv * 2^e) (|m| <= 2^29 on the
 * steepest axis), the distance in units is d' m' with d' in (d - 1, d] and m' in
 * [m, m + 1), so within |m| + 1 + |d| of d m. With |o_lo| < 2^32 every product stays
 * below 2^62; rays beyond that take the general test. */
typedef struct {
    int64_t o_lo[3], m[3], m_err[3]; /* m_err = |m| + 1 */
    int to_units;                    /* a Q32.32 value times 2^to_units is in units */
    bool usable;
} fixed_slab;

/* floor(x / 2^s) for 0 <= s <= 63, by the magnitude (no signed right shift). */
static int64_t floor_shift(int64_t x, int s)
{
    uint64_t mag = rt_fx_mag(x), q = mag >> s;
    bool rest = (mag & ((UINT64_C(1) << s) - 1)) != 0;
    return x < 0 ? -(int64_t)(q + rest) : (int64_t)q;
}

/* x * 2^s for s >= 0, saturated to +-INT64_MAX. */
static int64_t saturating_scale(int64_t x, int s)
{
    int64_t most = INT64_MAX >> s;
    return x > most ? INT64_MAX : x < -most ? -INT64_MAX : x * ((int64_t)1 << s);
}

/* x * 2^s rounded down (up = false) or up, saturated; -63 <= s <= 62. */
static int64_t scale_bound(int64_t x, int s, bool up)
{
    if (s >= 0) return saturating_scale(x, s);
    return up ? -floor_shift(-x, -s) : floor_shift(x, -s);
}

/* The number of bits of v (0 for 0). */
static int bit_length(uint64_t v)
{
    int n = 0;
    for (int step = 32; step > 0; step /= 2)
        if (v >> step) {
            v >>= step;
            n += step;
        }
    return n + (v != 0);
}

static fixed_slab fixed_slab_prepare(rt_vec3 origin, rt_vec3 inv, int grid)
{
    fixed_slab f;
    rt_real o[3] = {origin.x, origin.y, origin.z}, iv[3] = {inv.x, inv.y, inv.z};
    int steepest = 0;
    f.usable = true;
    for (int k = 0; k < 3; k++) {
        int bits = bit_length(rt_fx_mag(iv[k]));
        if (bits > steepest) steepest = bits;
        f.o_lo[k] = floor_shift(o[k], grid);
        if (rt_fx_mag(f.o_lo[k]) >= UINT64_C(1) << 32) f.usable = false;
    }
    /* e = 29 - steepest leaves m 29 bits on the steepest axis. A distance is d' g inv
     * with the grid unit g = 2^(grid - 32) and inv = inv_q 2^-32 (inv_q the Q32.32 count),
     * so the unit is 2^(grid - 64 - e), and a Q32.32 t (t_q 2^-32) is t_q 2^(e + 32 - grid)
     * units. */
    int e = 29 - steepest;
    f.to_units = e + 32 - grid;
    for (int k = 0; k < 3; k++) {
        f.m[k] = e >= 0 ? iv[k] * ((int64_t)1 << e) : floor_shift(iv[k], -e);
        f.m_err[k] = (int64_t)rt_fx_mag(f.m[k]) + 1;
    }
    return f;
}

/* Lower (near = true) or upper bound of one plane's distance, in units. */
static inline int64_t fixed_plane(const fixed_slab *f, int k, rt_bound b, bool near)
{
    int64_t d = (int64_t)b - f->o_lo[k];
    int64_t err = f->m_err[k] + (int64_t)rt_fx_mag(d);
    return near ? d * f->m[k] - err : d * f->m[k] + err;
}
#endif

/* The slab test of rt_intersect_aabb on a child's stored box, with the per-axis branches
 * decided once per ray: for a non-zero direction component the near plane is lo when it
 * is positive and hi when negative (the products are monotonic in the plane, so this is
 * the swap the general test makes), and without NaN the three axes can be clamped before
 * the one comparison. Rays with a zero component, a non-finite reciprocal or origin keep
 * the general test, whose zero-direction and NaN cases differ. */
typedef struct {
    rt_vec3 origin, inv;
    rt_real t_min;
    int near[3], far[3]; /* each axis' near and far plane: a row of rt_bvh_node.box */
    int grid;
    bool general;
    const rt_ray_setup *rs;
    const rt_bvh *bvh;
#if SLAB_SSE2
    v2df origin2[3], inv2[3], t_min2; /* each value in both lanes */
#endif
#ifdef RT_REAL_FIXED
    fixed_slab fx;
#endif
} slab_ray;

static slab_ray slab_prepare(const rt_ray_setup *rs, const rt_bvh *bvh)
{
    rt_vec3 d = rs->ray.direction, o = rs->ray.origin, inv = rs->inv_direction;
    slab_ray r;
    r.origin = o;
    r.inv = inv;
    r.t_min = rs->ray.t_min;
    r.rs = rs;
    r.bvh = bvh;
    r.grid = bvh->grid;
    for (int k = 0; k < 3; k++) {
        bool neg = rt_v3_get(d, k) < RT_ZERO;
        r.near[k] = neg ? 3 + k : k;
        r.far[k] = neg ? k : 3 + k;
#if SLAB_SSE2
        r.origin2[k] = (v2df){rt_v3_get(o, k), rt_v3_get(o, k)};
        r.inv2[k] = (v2df){rt_v3_get(inv, k), rt_v3_get(inv, k)};
#endif
    }
#if SLAB_SSE2
    r.t_min2 = (v2df){r.t_min, r.t_min};
#endif
    r.general = d.x == RT_ZERO || d.y == RT_ZERO || d.z == RT_ZERO || !rt_is_finite(inv.x) || !rt_is_finite(inv.y) ||
                !rt_is_finite(inv.z) || !rt_is_finite(o.x) || !rt_is_finite(o.y) || !rt_is_finite(o.z);
#ifdef RT_REAL_FIXED
    r.fx = fixed_slab_prepare(o, inv, bvh->grid);
    r.general = r.general || !r.fx.usable;
#endif
    return r;
}

/* Child c of `node`: entered before t_max, at *t_enter? */
static inline bool slab_hit(const slab_ray *r, const rt_bvh_node *node, int c, rt_real t_max, rt_real *t_enter)
{
    if (r->general) {
        rt_aabb box = rt_bvh_child_box(r->bvh, node, c);
        return rt_intersect_aabb(r->rs, &box, t_max, t_enter);
    }
    const rt_bound(*b)[RT_BVH_WIDTH] = node->box;
    int g = r->grid;
    rt_real x0 = rt_mul(rt_sub(rt_bound_value(b[r->near[0]][c], g), r->origin.x), r->inv.x);
    rt_real x1 = rt_mul(rt_sub(rt_bound_value(b[r->far[0]][c], g), r->origin.x), r->inv.x);
    rt_real y0 = rt_mul(rt_sub(rt_bound_value(b[r->near[1]][c], g), r->origin.y), r->inv.y);
    rt_real y1 = rt_mul(rt_sub(rt_bound_value(b[r->far[1]][c], g), r->origin.y), r->inv.y);
    rt_real z0 = rt_mul(rt_sub(rt_bound_value(b[r->near[2]][c], g), r->origin.z), r->inv.z);
    rt_real z1 = rt_mul(rt_sub(rt_bound_value(b[r->far[2]][c], g), r->origin.z), r->inv.z);
    rt_real t0 = rt_max(rt_max(rt_max(r->t_min, x0), y0), z0);
    rt_real t1 = rt_min(rt_min(rt_min(t_max, x1), y1), z1);
    *t_enter = t0;
    return !(t0 > t1);
}

#if SLAB_SSE2
typedef struct {
    v2df t0_01, t0_23, t1_01, t1_23; /* entry and exit distances of children 0, 1 and 2, 3 */
} slab4;

/* One axis of slab_hit for all four children, two per register: the same IEEE
 * operations in the same order, so the same distances (maxpd and minpd are rt_max and
 * rt_min: a > b ? a : b and a < b ? a : b). */
__attribute__((always_inline)) static inline void slab_axis_sse2(const slab_ray *r, const rt_bvh_node *node, int k,
                                                                 slab4 *s)
{
    v4sf near = *(const v4sf *)node->box[r->near[k]], far = *(const v4sf *)node->box[r->far[k]];
    v2df o = r->origin2[k], inv = r->inv2[k];
    s->t0_01 = __builtin_ia32_maxpd(s->t0_01, (v2df_from_lo(near) - o) * inv);
    s->t0_23 = __builtin_ia32_maxpd(s->t0_23, (v2df_from_hi(near) - o) * inv);
    s->t1_01 = __builtin_ia32_minpd(s->t1_01, (v2df_from_lo(far) - o) * inv);
    s->t1_23 = __builtin_ia32_minpd(s->t1_23, (v2df_from_hi(far) - o) * inv);
}

/* slab_hit on all four children at once. */
__attribute__((always_inline)) static inline unsigned slab_hit_sse2(const slab_ray *r, const rt_bvh_node *node,
                                                                    rt_real t_max, rt_real t_enter[RT_BVH_WIDTH])
{
    v2df limit = {t_max, t_max};
    slab4 s = {r->t_min2, r->t_min2, limit, limit};
    slab_axis_sse2(r, node, 0, &s);
    slab_axis_sse2(r, node, 1, &s);
    slab_axis_sse2(r, node, 2, &s);
    t_enter[0] = s.t0_01[0];
    t_enter[1] = s.t0_01[1];
    t_enter[2] = s.t0_23[0];
    t_enter[3] = s.t0_23[1];
    unsigned hits = (unsigned)(__builtin_ia32_movmskpd(__builtin_ia32_cmplepd(s.t0_01, s.t1_01)) |
                               __builtin_ia32_movmskpd(__builtin_ia32_cmplepd(s.t0_23, s.t1_23)) << 2);
    v4su unused = *(const v4su *)node->count == RT_BVH_NO_CHILD;
    return hits & ~(unsigned)__builtin_ia32_movmskps((v4sf)unused);
}
#endif

#ifdef RT_REAL_FIXED
/* All four children with fixed_plane's bounds: a superset of the exact test's hits, and
 * entry distances at or below the exact ones. */
__attribute__((always_inline)) static inline unsigned slab_hit_fixed(const slab_ray *r, const rt_bvh_node *node,
                                                                     rt_real t_max, rt_real t_enter[RT_BVH_WIDTH])
{
    const fixed_slab *f = &r->fx;
    int64_t t_min_u = scale_bound(r->t_min, f->to_units, false), limit_u = scale_bound(t_max, f->to_units, true);
    unsigned hits = 0;
    for (int c = 0; c < RT_BVH_WIDTH; c++) {
        if (node->count[c] == RT_BVH_NO_CHILD) continue;
        int64_t t0 = t_min_u, t1 = limit_u;
        for (int k = 0; k < 3; k++) {
            t0 = rt_max(t0, fixed_plane(f, k, node->box[r->near[k]][c], true));
            t1 = rt_min(t1, fixed_plane(f, k, node->box[r->far[k]][c], false));
        }
        if (t0 > t1) continue;
        hits |= 1u << c;
        t_enter[c] = scale_bound(t0, -f->to_units, false);
    }
    return hits;
}
#endif

/* Tests every child of `node`: bit c of the result is set when child c is entered
 * before t_max, at t_enter[c]. Unused slots never are. */
__attribute__((always_inline)) static inline unsigned slab_hit_children(const slab_ray *r, const rt_bvh_node *node,
                                                                        rt_real t_max, rt_real t_enter[RT_BVH_WIDTH])
{
#if SLAB_SSE2
    if (!r->general) return slab_hit_sse2(r, node, t_max, t_enter);
#endif
#ifdef RT_REAL_FIXED
    if (!r->general) return slab_hit_fixed(r, node, t_max, t_enter);
#endif
    unsigned hits = 0;
    for (int c = 0; c < RT_BVH_WIDTH; c++)
        if (node->count[c] != RT_BVH_NO_CHILD && slab_hit(r, node, c, t_max, &t_enter[c])) hits |= 1u << c;
    return hits;
}

/* Keeps prim's hit in *best if it is nearer, or as near and a lower reference. */
__attribute__((always_inline)) static inline void consider(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs,
                                                           rt_scene_hit *best, bool *found, int kx, int ky, int kz)
{
    rt_prim_hit h;
    if (!prim_intersect(scene, prim, rs, &h, kx, ky, kz)) return;
    if (*found && (h.t > best->hit.t || (h.t == best->hit.t && prim > best->prim))) return;
    best->hit = h;
    best->prim = prim;
    *found = true;
}

__attribute__((always_inline)) static inline bool leaf_loop(const rt_scene *scene, uint32_t first, uint32_t count,
                                                            const rt_ray_setup *rs, bool any, rt_scene_hit *best,
                                                            bool *found, int kx, int ky, int kz)
{
    const uint32_t *refs = scene->bvh.prim_refs;
    for (uint32_t i = first; i < first + count; i++) {
        consider(scene, refs[i], rs, best, found, kx, ky, kz);
        if (any && *found) break;
    }
    return *found;
}

/* The references prim_refs[first .. first + count), out of line so that the traversal
 * loop keeps its registers, with one copy of the loop per axis permutation; with `any`,
 * stops at the first hit. Returns *found. */
__attribute__((noinline)) static bool visit_leaf(const rt_scene *scene, uint32_t first, uint32_t count,
                                                 const rt_ray_setup *rs, bool any, rt_scene_hit *best, bool *found)
{
    bool swapped = rs->kx != (rs->kz + 1) % 3; /* see rt_ray_prepare */
    switch (rs->kz * 2 + swapped) {
    case 0: return leaf_loop(scene, first, count, rs, any, best, found, 1, 2, 0);
    case 1: return leaf_loop(scene, first, count, rs, any, best, found, 2, 1, 0);
    case 2: return leaf_loop(scene, first, count, rs, any, best, found, 2, 0, 1);
    case 3: return leaf_loop(scene, first, count, rs, any, best, found, 0, 2, 1);
    case 4: return leaf_loop(scene, first, count, rs, any, best, found, 0, 1, 2);
    default: return leaf_loop(scene, first, count, rs, any, best, found, 1, 0, 2);
    }
}

static bool nearest_brute(const rt_scene *scene, const rt_ray_setup *rs, rt_scene_hit *out)
{
    bool found = false;
    for (uint32_t p = 0; p < scene->prim_count; p++) consider(scene, p, rs, out, &found, rs->kx, rs->ky, rs->kz);
    return found;
}

/* A child waiting to be visited: a node (count 0) or a leaf's references, and the
 * distance at which the ray enters its box. */
typedef struct {
    uint32_t child, count;
    rt_real t_enter;
} stack_entry;

/* Each wide level pushes at most RT_BVH_WIDTH - 1 children, after the root. */
#define QUERY_STACK (RT_BVH_MAX_DEPTH * (RT_BVH_WIDTH - 1) + 1)

static inline stack_entry child_entry(const rt_bvh_node *node, int c, rt_real t_enter)
{
    return (stack_entry){node->child[c], node->count[c], t_enter};
}

/* Of hit children a < b, returns the nearer (a on a tie) and pushes the other. */
__attribute__((always_inline)) static inline stack_entry nearer_of(const rt_bvh_node *node, int a, int b,
                                                                   const rt_real t[RT_BVH_WIDTH], stack_entry *stack,
                                                                   uint32_t *top)
{
    if (t[b] < t[a]) {
        stack[(*top)++] = child_entry(node, a, t[a]);
        return child_entry(node, b, t[b]);
    }
    stack[(*top)++] = child_entry(node, b, t[b]);
    return child_entry(node, a, t[a]);
}

/* Returns the nearest of the children in `hits`, pushing the others farthest first.
 * One or two hits are told apart by branches, each with its slots as constants, not
 * computed: a predicted branch lets the next node's load start before this node's test
 * is done. */
__attribute__((always_inline)) static inline stack_entry descend(const rt_bvh_node *node, unsigned hits,
                                                                 const rt_real t[RT_BVH_WIDTH], stack_entry *stack,
                                                                 uint32_t *top)
{
    switch (hits) {
    case 1: return child_entry(node, 0, t[0]);
    case 2: return child_entry(node, 1, t[1]);
    case 4: return child_entry(node, 2, t[2]);
    case 8: return child_entry(node, 3, t[3]);
    case 3: return nearer_of(node, 0, 1, t, stack, top);
    case 5: return nearer_of(node, 0, 2, t, stack, top);
    case 6: return nearer_of(node, 1, 2, t, stack, top);
    case 9: return nearer_of(node, 0, 3, t, stack, top);
    case 10: return nearer_of(node, 1, 3, t, stack, top);
    case 12: return nearer_of(node, 2, 3, t, stack, top);
    default: break;
    }
    int order[RT_BVH_WIDTH], n = 0; /* the hit children by entry distance, ties by slot */
    for (int c = 0; c < RT_BVH_WIDTH; c++) {
        if (!(hits >> c & 1u)) continue;
        int i = n++;
        for (; i > 0 && t[order[i - 1]] > t[c]; i--) order[i] = order[i - 1];
        order[i] = c;
    }
    for (int i = n - 1; i > 0; i--) stack[(*top)++] = child_entry(node, order[i], t[order[i]]);
    return child_entry(node, order[0], t[order[0]]);
}

/* Boxes are tested against the best t itself (not below it), and a popped child is
 * skipped only when it is entered beyond the best t, so ties to a lower reference survive.
 * With `any`, the first hit found ends the search (rt_scene_any). */
static bool nearest_bvh(const rt_scene *scene, const rt_ray_setup *rs, bool any, rt_scene_hit *out)
{
    const rt_bvh_node *nodes = scene->bvh.nodes;
    slab_ray sr = slab_prepare(rs, &scene->bvh);
    bool found = false;
    stack_entry stack[QUERY_STACK];
    uint32_t top = 0;
    if (scene->prim_count == 0) return false;
    stack[top++] = (stack_entry){0, 0, rs->ray.t_min}; /* the root node */
    while (top > 0) {
        stack_entry e = stack[--top];
        if (found && e.t_enter > out->hit.t) continue;
        /* Descend into the nearest child directly; the others wait on the stack. */
        while (e.count == 0) {
            const rt_bvh_node *node = &nodes[e.child];
            rt_real limit = found ? out->hit.t : rs->ray.t_max, t[RT_BVH_WIDTH];
            unsigned hits = slab_hit_children(&sr, node, limit, t);
            if (!hits) break;
            e = descend(node, hits, t, stack, &top);
        }
        if (e.count == 0) continue;
        if (visit_leaf(scene, e.child, e.count, rs, any, out, &found) && any) return true;
    }
    return found;
}

bool rt_scene_nearest(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh, rt_scene_hit *out)
{
    return use_bvh ? nearest_bvh(scene, rs, false, out) : nearest_brute(scene, rs, out);
}

bool rt_scene_any(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh)
{
    rt_scene_hit first;
    if (use_bvh) return nearest_bvh(scene, rs, true, &first);
    rt_prim_hit h;
    for (uint32_t p = 0; p < scene->prim_count; p++)
        if (rt_prim_intersect(scene, p, rs, &h)) return true;
    return false;
}

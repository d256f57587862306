/* Binned-SAH BVH build on the caller's workers, collapsed into a wide tree
 * (bvh_collapse.c); see bvh.h (queries: scene_query.c). */
#include "bvh.h"
#include "bvh_bin.h"
#include "bvh_binary.h"
#include "invariant.h"

/* Leaves hold LEAF_MIN references or fewer without asking, at most LEAF_MAX; in between
 * the SAH decides, pricing a node visit at TRAVERSAL_COST primitive tests. */
#define LEAF_MIN 4
#define LEAF_MAX 8
#define TRAVERSAL_COST RT_C(3.0)

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
static rt_real aabb_padding(rt_aabb b)
{
    return rt_mul(rt_add(aabb_magnitude(b), RT_ONE), RT_C(0.00000095367431640625));
}

static rt_aabb aabb_widen(rt_aabb b, rt_real pad)
{
    rt_vec3 p = rt_v3(pad, pad, pad);
    rt_aabb r = {rt_v3_sub(b.lo, p), rt_v3_add(b.hi, p)};
    return r;
}

static rt_aabb aabb_pad(rt_aabb b) { return aabb_widen(b, aabb_padding(b)); }

/* A quadric fills at most its object-space cube [-0.5, 0.5]^3. */
static rt_aabb quadric_bounds(const rt_scene *scene, uint32_t prim)
{
    const rt_object *obj = &scene->objects[scene->quadric_objects[prim - scene->triangle_count]];
    const rt_mat3 *m = &obj->to_world.linear;
    rt_vec3 half = rt_v3(rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[0][0]), rt_abs(m->m[0][1])), rt_abs(m->m[0][2]))),
                         rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[1][0]), rt_abs(m->m[1][1])), rt_abs(m->m[1][2]))),
                         rt_mul(RT_C(0.5), rt_add(rt_add(rt_abs(m->m[2][0]), rt_abs(m->m[2][1])), rt_abs(m->m[2][2]))));
    rt_aabb b = {rt_v3_sub(obj->to_world.translation, half), rt_v3_add(obj->to_world.translation, half)};
#ifdef RT_REAL_FIXED
    /* In Q32.32 the rounded inverse transform leaves a large quadric's hit off by up to
     * about 2^-31 of its scale squared (tests/test_precision.c measures 0.15 at a scale of
     * 16,000), beyond the padding above for scales over about 128: there the padding is
     * 2^-26 of its largest half extent squared, some seven times that error. */
    rt_real h = rt_max(rt_max(half.x, half.y), half.z);
    return aabb_widen(b, rt_max(aabb_padding(b), rt_mul(h, rt_mul(h, RT_C(0x1p-26)))));
#else
    return aabb_pad(b);
#endif
}

/* Inline in the build's first pass, which bounds every primitive: a triangle's bounds
 * there, a quadric's out of line. */
__attribute__((always_inline)) static inline rt_aabb prim_bounds(const rt_scene *scene, uint32_t prim)
{
    if (prim >= scene->triangle_count) return quadric_bounds(scene, prim);
    const rt_triangle *tri = &scene->triangles[prim];
    rt_aabb b = rt_aabb_empty();
    for (int k = 0; k < 3; k++) b = aabb_add_point(b, scene->positions[tri->v[k]]);
    return aabb_pad(b);
}

rt_aabb rt_bvh_prim_bounds(const rt_scene *scene, uint32_t prim) { return prim_bounds(scene, prim); }

/* ---- Build ---- */

/* A primitive being sorted into the tree is a build_ref (bvh_bin.h): its box travels with
 * it, so each node's passes read its references in order instead of gathering them. */

typedef struct {
    uint32_t node, first, count, depth, parent_count;
    rt_aabb bounds, centroids; /* of the references, from the parent's bins and partition */
} build_task;

/* Whether task, if it splits, is a wide root (bvh_binary.h). */
static bool is_wide_root(const build_task *task)
{
    return task->count <= RT_BIN_WIDE_ROOT_MAX && task->parent_count > RT_BIN_WIDE_ROOT_MAX;
}

/* The references binned so far, per axis and bin: the union of their bounds and their
 * count. A union with an empty box changes no bit, so the sweeps leave empty bins (count
 * 0) out. */
typedef struct {
    bin_box box[3][BIN_COUNT];
    uint32_t count[3][BIN_COUNT];
} bins;

/* Bins refs[first .. first + count) into b. */
static void bin_refs(bins *b, const binning *g, const build_ref *refs, uint32_t first, uint32_t count)
{
    for (int axis = 0; axis < 3; axis++)
        for (int k = 0; k < BIN_COUNT; k++) {
            b->box[axis][k] = bin_box_empty();
            b->count[axis][k] = 0;
        }
    for (uint32_t i = first; i < first + count; i++) {
        bin_box box = ref_box(&refs[i]);
        int k[3];
        box_bins(g, box, k);
        bin_box_grow(&b->box[0][k[0]], box);
        bin_box_grow(&b->box[1][k[1]], box);
        bin_box_grow(&b->box[2][k[2]], box);
        b->count[0][k[0]]++;
        b->count[1][k[1]]++;
        b->count[2][k[2]]++;
    }
}

/* Adds the bins of the references that follow those of `into`. A union of min and max
 * keeps, on ties, the later operand, as the one-by-one pass does, so bins merged in
 * reference order equal the bins of one pass over all of them. */
static void merge_bins(bins *into, const bins *later)
{
    for (int axis = 0; axis < 3; axis++) {
        for (int k = 0; k < BIN_COUNT; k++) {
            bin_box_grow(&into->box[axis][k], later->box[axis][k]);
            into->count[axis][k] += later->count[axis][k];
        }
    }
}

typedef struct {
    int axis, bin;       /* refs in bins <= bin go left */
    binning binning;     /* the task's */
    rt_aabb left, right; /* the children's bounds, unions of their bins */
} split;

/* The cheapest split plane between bins of a task's references; false if a leaf is
 * cheaper (and the task may be a leaf), or nothing splits. */
static bool price_split(const build_task *t, const binning *g, const bins *b, split *out)
{
    /* Costs relative to one primitive test over the task's area. */
    rt_real best_cost = t->count > LEAF_MAX ? RT_REAL_MAX : rt_mul(rt_from_int(t->count), rt_aabb_half_area(t->bounds));
    rt_real visit = rt_mul(TRAVERSAL_COST, rt_aabb_half_area(t->bounds));
    bool found = false;
    for (int axis = 0; axis < 3; axis++) {
        if (!g->active[axis]) continue;
        const uint32_t *used = b->count[axis];
        /* Sweep from the right to get suffix areas, then from the left to price each plane.
         * A plane after an empty bin costs what the plane before it costs and never wins
         * (a cheaper cost must be strictly cheaper), so only planes after used bins,
         * with a used bin beyond them, are priced. */
        rt_real right_area[BIN_COUNT];
        uint32_t right_n[BIN_COUNT];
        bin_box acc = bin_box_empty();
        uint32_t n = 0;
        for (int k = BIN_COUNT - 1; k > 0; k--) {
            if (!used[k]) continue;
            bin_box_grow(&acc, b->box[axis][k]);
            n += b->count[axis][k];
            right_area[k] = bin_box_half_area(acc);
            right_n[k] = n;
        }
        acc = bin_box_empty();
        n = 0;
        for (int k = 0, plane = -1; k < BIN_COUNT; k++) {
            if (!used[k]) continue;
            /* The plane after the previous used bin: refs up to it left, from bin k right. */
            if (plane >= 0) {
                rt_real cost = rt_add(visit, rt_add(rt_mul(rt_from_int(n), bin_box_half_area(acc)),
                                                    rt_mul(rt_from_int(right_n[k]), right_area[k])));
                if (cost < best_cost) {
                    best_cost = cost;
                    found = true;
                    out->axis = axis;
                    out->bin = plane;
                }
            }
            bin_box_grow(&acc, b->box[axis][k]);
            n += b->count[axis][k];
            plane = k;
        }
    }
    if (!found) return false;
    out->binning = *g;
    bin_box left = bin_box_empty(), right = bin_box_empty();
    for (int k = 0; k < BIN_COUNT; k++) {
        if (!b->count[out->axis][k]) continue;
        bin_box_grow(k <= out->bin ? &left : &right, b->box[out->axis][k]);
    }
    out->left = bin_box_aabb(left);
    out->right = bin_box_aabb(right);
    return true;
}

/* Moves the references of bins <= s->bin to the front and returns their count; the
 * children's centroid bounds are gathered on the way. */
static uint32_t partition(build_ref *refs, uint32_t first, uint32_t count, const split *s, rt_aabb *left_c,
                          rt_aabb *right_c)
{
    centre_bounds left = centre_bounds_empty(), right = centre_bounds_empty();
    uint32_t i = first, j = first + count;
    while (i < j) {
        centre c = box_centre(ref_box(&refs[i]));
        if (centre_bin(&s->binning, c, s->axis) <= s->bin) {
            centre_grow(&left, c);
            i++;
        } else {
            centre_grow(&right, c);
            j--;
            build_ref swap = refs[i];
            refs[i] = refs[j];
            refs[j] = swap;
        }
    }
    *left_c = centre_bounds_aabb(left);
    *right_c = centre_bounds_aabb(right);
    return i - first;
}

/* Some of a top task's references, binned by one job. */
typedef struct {
    uint32_t task, first, count;
    bins bins;
} bin_chunk;

/* One build: the tree's scratch and its work of the moment, shared with the jobs. */
typedef struct {
    const rt_scene *scene;
    const rt_workers *workers;
    rt_bvh_plan plan;
    build_ref *refs;
    rt_bin_node *nodes;
    size_t nodes_size;   /* bytes: 2n - 1 slots */
    uint32_t *prim_refs; /* the tree's, written from refs as each part of it is made */
    rt_real extent;
    int grid;
    /* The references' bounds and centroid bounds, per chunk of plan.chunk. */
    rt_aabb *chunk_bounds, *chunk_centroids;
    /* A level of the top of the tree: its tasks, whether each split, and the children
     * made, two per task; for a level binned in chunks, the tasks' binnings, the chunks
     * and the splits found. */
    build_task *level;
    bool *level_splits;
    build_task *children;
    binning *level_binning;
    bin_chunk *chunks;
    split *level_split;
    /* The subtrees built whole, the inner nodes each made, and a stack per worker; and
     * scratch per worker to collapse wide roots of up to block_refs references (NULL:
     * the final collapse makes every wide node). */
    build_task *subtrees;
    uint32_t subtree_count;
    uint32_t *subtree_inner;
    build_task *stacks;
    unsigned char *block_scratch;
    size_t block_scratch_size;
    uint32_t block_refs;
    /* The tasks of the level being partitioned in chunks, and after them the jobs that
     * touch the binary tree's scratch ahead (touch_job), while the root is partitioned. */
    uint32_t level_count, touch_jobs;
} build;

/* A subtree's stack: each split pushes two tasks and pops one, once per level. */
#define SUBTREE_STACK (RT_BVH_MAX_DEPTH + 2)

/* Writes the primitives of refs[first .. first + count), in their final order, to the
 * tree's list. */
static void store_prims(const build *b, uint32_t first, uint32_t count)
{
    for (uint32_t i = first; i < first + count; i++) b->prim_refs[i] = b->refs[i].prim;
}

/* Stores task's node: a leaf, or, given its split s, an inner node whose two children
 * (written to kids) get their references by partition, and as nodes the pair of slots
 * at *next_pair (which advances past them) or, with next_pair NULL, the pair the split's
 * position gives (bvh_binary.h). */
static void make_node(const build *b, const build_task *task, const split *s, uint32_t *next_pair, build_task kids[2])
{
    rt_bin_node *node = &b->nodes[task->node];
    rt_bvh_store_box(node->box, task->bounds, b->grid);
    node->first = task->first;
    node->count = task->count;
    if (!s) {
        store_prims(b, task->first, task->count); /* a leaf's, final now */
        return;
    }
    rt_aabb left_c, right_c;
    /* A split plane has references on both sides (price_split), so 0 < left_n < count. */
    uint32_t left_n = partition(b->refs, task->first, task->count, s, &left_c, &right_c);
    RT_ASSERT(0 < left_n && left_n < task->count);
    uint32_t left = 2 * (task->first + left_n) - 1;
    if (next_pair) {
        left = *next_pair;
        *next_pair += 2;
    }
    node->first = left;
    node->count = is_wide_root(task) ? RT_BIN_WIDE_ROOT : 0;
    kids[0] = (build_task){left, task->first, left_n, task->depth + 1, task->count, s->left, left_c};
    kids[1] = (build_task){left + 1, task->first + left_n, task->count - left_n, task->depth + 1, task->count, s->right,
                           right_c};
}

/* Bins and prices task and stores its node (make_node, with next_pair); returns whether
 * it split, into kids. */
static bool split_task(const build *b, const build_task *task, uint32_t *next_pair, build_task kids[2])
{
    split s;
    bool splits = false;
    if (task->count > LEAF_MIN && task->depth < RT_BVH_MAX_DEPTH) {
        binning g = binning_make(task->centroids);
        bins all;
        bin_refs(&all, &g, b->refs, task->first, task->count);
        splits = price_split(task, &g, &all, &s);
    }
    make_node(b, task, splits ? &s : NULL, next_pair, kids);
    return splits;
}

/* Builds the subtree of root depth first on one worker; returns its inner node count. */
static uint32_t build_subtree(const build *b, build_task root, build_task *stack)
{
    uint32_t inner = 0, top = 0, next_pair = 2 * root.first + 1;
    stack[top++] = root;
    while (top > 0) {
        build_task task = stack[--top], kids[2];
        if (!split_task(b, &task, &next_pair, kids)) continue;
        inner++;
        /* Right first, so the left subtree is built next (a bounded stack). */
        RT_ASSERT(top + 2 <= SUBTREE_STACK);
        stack[top++] = kids[1];
        stack[top++] = kids[0];
    }
    return inner;
}

static uint32_t min_u32(uint32_t a, uint32_t b) { return a < b ? a : b; }

static void bound_refs_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    build *b = arg;
    uint32_t first = index * b->plan.chunk, end = first + min_u32(b->plan.chunk, b->scene->prim_count - first);
    bin_box bounds = bin_box_empty();
    centre_bounds centroids = centre_bounds_empty();
    const rt_scene *scene = b->scene;
    for (uint32_t i = first; i < end; i++) {
        bin_box box = ref_store(&b->refs[i], prim_bounds(scene, i), i);
        bin_box_grow(&bounds, box);
        centre_grow(&centroids, box_centre(box));
    }
    b->chunk_bounds[index] = bin_box_aabb(bounds);
    b->chunk_centroids[index] = centre_bounds_aabb(centroids);
}

static void split_task_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    build *b = arg;
    b->level_splits[index] = split_task(b, &b->level[index], NULL, &b->children[2 * index]);
}

static void bin_chunk_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    build *b = arg;
    bin_chunk *c = &b->chunks[index];
    bin_refs(&c->bins, &b->level_binning[c->task], b->refs, c->first, c->count);
}

/* The binary tree's scratch is first written all over by the top levels' nodes and the
 * subtrees, each first write into a page a page fault (docs/performance.md, "Page
 * faults"). While one worker partitions the root, the others write a byte every
 * TOUCH_STRIDE of it ahead: with huge pages (2 MiB) that faults every page the build
 * would, with small ones a few. The slots touched are written again before they are read. */
#define TOUCH_STRIDE ((size_t)2 << 20)
#define TOUCH_JOB_BYTES (4 * TOUCH_STRIDE)

static void touch_job(const build *b, uint32_t index)
{
    volatile unsigned char *scratch = (volatile unsigned char *)b->nodes;
    size_t first = index * TOUCH_JOB_BYTES;
    /* Not the root's slot (offset 0), which the partition's job writes meanwhile. */
    for (size_t at = first > 0 ? first : TOUCH_STRIDE; at < first + TOUCH_JOB_BYTES && at < b->nodes_size;
         at += TOUCH_STRIDE)
        scratch[at] = 0;
}

static void partition_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    build *b = arg;
    if (index >= b->level_count) {
        touch_job(b, index - b->level_count);
        return;
    }
    make_node(b, &b->level[index], b->level_splits[index] ? &b->level_split[index] : NULL, NULL,
              &b->children[2 * index]);
}

static void subtree_job(void *arg, uint32_t index, uint32_t worker)
{
    build *b = arg;
    const build_task *root = &b->subtrees[index];
    b->subtree_inner[index] = build_subtree(b, *root, &b->stacks[(size_t)worker * SUBTREE_STACK]);
    /* A wide root's wide nodes are made while its binary nodes are in this core's caches. */
    if (b->block_scratch && b->nodes[root->node].count == RT_BIN_WIDE_ROOT)
        rt_bvh_collapse_block(b->nodes, root->node, root->first, root->count, b->grid,
                              b->block_scratch + worker * b->block_scratch_size, b->block_refs);
}

/* Whether the top phase splits task, level by level, rather than one job building it whole. */
static bool is_top(const build *b, const build_task *task)
{
    return task->count > b->plan.split_above && task->count > LEAF_MIN && task->depth < RT_BVH_MAX_DEPTH;
}

/* Splits a level of top tasks fewer than the workers: bins them in chunks over all the
 * workers, prices the merged bins, and partitions each task in its own job. */
static void split_level_in_chunks(build *b, uint32_t count)
{
    uint32_t chunks = 0;
    for (uint32_t t = 0; t < count; t++) {
        b->level_binning[t] = binning_make(b->level[t].centroids);
        uint32_t end = b->level[t].first + b->level[t].count;
        for (uint32_t first = b->level[t].first; first < end;) {
            bin_chunk *c = &b->chunks[chunks++];
            c->task = t;
            c->first = first;
            c->count = min_u32(b->plan.chunk, end - first);
            first += c->count;
        }
    }
    rt_workers_run(b->workers, bin_chunk_job, b, chunks);
    for (uint32_t t = 0, c = 0; t < count; t++) {
        bins *all = &b->chunks[c++].bins;
        while (c < chunks && b->chunks[c].task == t) merge_bins(all, &b->chunks[c++].bins);
        b->level_splits[t] = price_split(&b->level[t], &b->level_binning[t], all, &b->level_split[t]);
    }
    b->level_count = count;
    rt_workers_run(b->workers, partition_job, b, count + b->touch_jobs);
    b->touch_jobs = 0;
}

/* Whether task a is handed out before b: the larger first, then by first reference. */
static bool runs_before(const build_task *a, const build_task *b)
{
    return a->count > b->count || (a->count == b->count && a->first < b->first);
}

/* Orders a level's tasks largest first, so that jobs handed out in index order finish
 * together; the tree does not depend on the order (nodes' slots follow from the split). */
static void order_largest_first(build_task *level, uint32_t count)
{
    for (uint32_t i = 1; i < count; i++) {
        build_task t = level[i];
        uint32_t j = i;
        for (; j > 0 && runs_before(&t, &level[j - 1]); j--) level[j] = level[j - 1];
        level[j] = t;
    }
}

/* Splits one level of top tasks (b->level[0 .. count)). With at least as many tasks as
 * workers, one job bins, prices and partitions each task, so that the partition finds
 * the references in the caches of the core that binned them; fewer are binned in chunks
 * over all the workers. The bins, and so the tree, are the same either way. The
 * children that are top tasks again become the next level (returned count), the others
 * join the subtrees. */
static uint32_t split_level(build *b, uint32_t count, uint32_t *subtrees, uint32_t *inner)
{
    if (count < rt_workers_count(b->workers)) {
        split_level_in_chunks(b, count);
    } else {
        order_largest_first(b->level, count);
        rt_workers_run(b->workers, split_task_job, b, count);
    }
    uint32_t next = 0;
    for (uint32_t t = 0; t < count; t++) {
        if (!b->level_splits[t]) continue;
        (*inner)++;
        for (int k = 0; k < 2; k++) {
            const build_task *kid = &b->children[2 * t + k];
            if (is_top(b, kid))
                b->level[next++] = *kid;
            else
                b->subtrees[(*subtrees)++] = *kid;
        }
    }
    return next;
}

rt_bvh_plan rt_bvh_default_plan(void)
{
    /* About 50 top tasks and 50 subtrees for a million references (twice as many with
     * nodes of four children); a chunk is bounded in about a third of a millisecond,
     * binned in about a tenth. Subtrees of at most RT_BIN_WIDE_ROOT_MAX references are
     * wide roots, collapsed in their jobs. */
    rt_bvh_plan p = {RT_BIN_WIDE_ROOT_MAX, 16384};
    return p;
}

/* Allocates the arrays of the top phase (when the root is larger than split_above) and
 * of the subtrees, for n references. Their sizes are bounds: a level's top tasks are
 * disjoint and larger than split_above, there are at most RT_BVH_MAX_DEPTH levels, and
 * the subtrees, being disjoint, are at most n. */
static bool alloc_phases(build *b, rt_arena *arena, uint32_t n)
{
    size_t subtrees = 1;
    if (n > b->plan.split_above) {
        size_t level = n / ((size_t)b->plan.split_above + 1) + 1;
        b->level = rt_arena_alloc(arena, level * sizeof *b->level);
        b->level_binning = rt_arena_alloc(arena, level * sizeof *b->level_binning);
        b->level_split = rt_arena_alloc(arena, level * sizeof *b->level_split);
        b->level_splits = rt_arena_alloc(arena, level * sizeof *b->level_splits);
        b->children = rt_arena_alloc(arena, 2 * level * sizeof *b->children);
        b->chunks = rt_arena_alloc(arena, (n / b->plan.chunk + level) * sizeof *b->chunks);
        if (!b->level || !b->level_binning || !b->level_split || !b->level_splits || !b->children || !b->chunks)
            return false;
        subtrees = 2 * RT_BVH_MAX_DEPTH * level + 1;
        if (subtrees > n) subtrees = n;
    }
    b->subtrees = rt_arena_alloc(arena, subtrees * sizeof *b->subtrees);
    b->subtree_inner = rt_arena_alloc(arena, subtrees * sizeof *b->subtree_inner);
    return b->subtrees && b->subtree_inner;
}

/* Scratch for the subtrees' jobs to collapse their roots, if any may be wide roots, for
 * every worker that may run them (one job runs on worker 0). Optional: without it (a small
 * arena), the final collapse makes every wide node. */
static void alloc_block_scratch(build *b, rt_arena *arena, uint32_t subtrees)
{
    b->block_refs = 0;
    for (uint32_t s = 0; s < subtrees; s++) {
        const build_task *t = &b->subtrees[s];
        if (t->count > LEAF_MIN && is_wide_root(t)) b->block_refs = t->count > b->block_refs ? t->count : b->block_refs;
    }
    if (b->block_refs == 0) return;
    b->block_scratch_size = rt_bvh_block_scratch_size(b->block_refs);
    size_t workers = subtrees > 1 ? rt_workers_count(b->workers) : 1;
    b->block_scratch = rt_arena_alloc_aligned(arena, workers * b->block_scratch_size, 64);
}

/* Builds the binary tree over n > 0 references into b->nodes; returns its inner node count. */
static uint32_t build_binary(build *b, rt_arena *arena, uint32_t n)
{
    uint32_t chunks = (n - 1) / b->plan.chunk + 1;
    rt_workers_run(b->workers, bound_refs_job, b, chunks);
    build_task root = {0, 0, n, 1, UINT32_MAX, rt_aabb_empty(), rt_aabb_empty()};
    for (uint32_t c = 0; c < chunks; c++) {
        root.bounds = aabb_union(root.bounds, b->chunk_bounds[c]);
        root.centroids = aabb_union(root.centroids, b->chunk_centroids[c]);
    }
    b->extent = aabb_magnitude(root.bounds);
    b->grid = rt_bound_grid(b->extent);
    uint32_t inner = 0, subtrees = 0, level = 0;
    if (is_top(b, &root)) {
        b->level[level++] = root;
        if (rt_workers_count(b->workers) > 1) b->touch_jobs = (uint32_t)((b->nodes_size - 1) / TOUCH_JOB_BYTES + 1);
    } else
        b->subtrees[subtrees++] = root;
    while (level > 0) level = split_level(b, level, &subtrees, &inner);
    alloc_block_scratch(b, arena, subtrees);
    rt_workers_run(b->workers, subtree_job, b, subtrees);
    for (uint32_t s = 0; s < subtrees; s++) inner += b->subtree_inner[s];
    b->subtree_count = subtrees;
    return inner;
}

/* The wide tree's move down from scratch, in jobs of MOVE_CHUNK nodes (256 KiB). */
#define MOVE_CHUNK 1024
typedef struct {
    const rt_bvh_node *from;
    rt_bvh_node *to;
    uint32_t count;
} node_move;

static void move_nodes_job(void *arg, uint32_t index, uint32_t worker)
{
    (void)worker;
    const node_move *m = arg;
    uint32_t first = index * MOVE_CHUNK;
    __builtin_memcpy(m->to + first, m->from + first, min_u32(MOVE_CHUNK, m->count - first) * sizeof(rt_bvh_node));
}

/* The binary tree and the wide one are made in scratch above the arena's mark; then the
 * arena is reset and the wide nodes are copied down to the mark, at their final size. */
rt_status rt_bvh_build_planned(rt_scene *scene, rt_arena *arena, const rt_workers *workers, rt_bvh_plan plan)
{
    uint32_t n = scene->prim_count;
    rt_bvh *bvh = &scene->bvh;
    bvh->kernel = rt_bvh_kernel_compiled(RT_KERNEL_SSE2) ? RT_KERNEL_SSE2 : RT_KERNEL_PORTABLE;
    bvh->prim_refs = RT_NEW_ARRAY(arena, uint32_t, (size_t)n + RT_BVH_REF_PAD);
    if (!bvh->prim_refs) return RT_ERR_NOMEM;
    for (uint32_t k = 0; k < RT_BVH_REF_PAD; k++) bvh->prim_refs[n + k] = 0;
    if (n == 0) return rt_bvh_empty(bvh, arena);
    if (plan.split_above < 1) plan.split_above = 1;
    if (plan.chunk < 1) plan.chunk = 1;
    size_t mark = rt_arena_mark(arena);
    build b = {.scene = scene, .workers = workers, .plan = plan, .prim_refs = bvh->prim_refs};
    size_t chunks = (n - 1) / plan.chunk + 1;
    /* Every node and reference is written before it is read: no zeroing. */
    b.nodes_size = (2 * (size_t)n - 1) * sizeof *b.nodes;
    b.nodes = rt_arena_alloc(arena, b.nodes_size);
    size_t past_nodes = rt_arena_mark(arena);
    b.refs = rt_arena_alloc(arena, (size_t)n * sizeof *b.refs);
    b.chunk_bounds = rt_arena_alloc(arena, chunks * sizeof *b.chunk_bounds);
    b.chunk_centroids = rt_arena_alloc(arena, chunks * sizeof *b.chunk_centroids);
    b.stacks = rt_arena_alloc(arena, (size_t)rt_workers_count(workers) * SUBTREE_STACK * sizeof *b.stacks);
    if (!b.nodes || !b.refs || !b.chunk_bounds || !b.chunk_centroids || !b.stacks || !alloc_phases(&b, arena, n))
        return RT_ERR_NOMEM;
    uint32_t inner = build_binary(&b, arena, n);
    bvh->grid = b.grid;
    bvh->extent = b.extent;
    /* Only the binary tree is read from here on: the wide tree is made over the references
     * and the rest of the scratch, memory already touched. */
    rt_arena_reset(arena, past_nodes);
    /* Each block collapsed already is a subtree's. */
    rt_status st = rt_bvh_collapse(b.nodes, inner, b.subtree_count, bvh, arena, workers);
    if (st != RT_OK) return st;
    node_move move = {bvh->nodes, NULL, bvh->node_count};
    rt_arena_reset(arena, mark);
    move.to = rt_arena_alloc_aligned(arena, bvh->node_count * sizeof(rt_bvh_node), 64);
    bvh->nodes = move.to;
    /* Down from the scratch copy, which starts past the binary tree: in parallel when the
     * two do not overlap, as for a large tree; a small one is less than a node past. */
    if (move.to + move.count <= move.from)
        rt_workers_run(workers, move_nodes_job, &move, (move.count - 1) / MOVE_CHUNK + 1);
    else
        __builtin_memmove(move.to, move.from, move.count * sizeof(rt_bvh_node));
    return RT_OK;
}

rt_status rt_bvh_build(rt_scene *scene, rt_arena *arena, const rt_workers *workers)
{
    return rt_bvh_build_planned(scene, arena, workers, rt_bvh_default_plan());
}

bool rt_bvh_set_kernel(rt_bvh *bvh, rt_kernel k)
{
    if (!rt_bvh_kernel_compiled(k)) return false;
    bvh->kernel = k;
    return true;
}

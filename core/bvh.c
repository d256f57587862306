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

static void store_box(rt_bvh_node *node, rt_aabb b, int grid)
{
    node->box[0] = rt_bound_below(b.lo.x, grid);
    node->box[1] = rt_bound_below(b.lo.y, grid);
    node->box[2] = rt_bound_below(b.lo.z, grid);
    node->box[3] = rt_bound_above(b.hi.x, grid);
    node->box[4] = rt_bound_above(b.hi.y, grid);
    node->box[5] = rt_bound_above(b.hi.z, grid);
}

rt_aabb rt_bvh_node_box(const rt_bvh *bvh, const rt_bvh_node *node)
{
    const rt_bound *b = node->box;
    int g = bvh->grid;
    rt_aabb r = {rt_v3(rt_bound_value(b[0], g), rt_bound_value(b[1], g), rt_bound_value(b[2], g)),
                 rt_v3(rt_bound_value(b[3], g), rt_bound_value(b[4], g), rt_bound_value(b[5], g))};
    return r;
}

/* Siblings are nodes (2k + 1, 2k + 2): the array starts one node before a 64-byte
 * boundary so that each pair a traversal step reads shares one cache line. */
_Static_assert(2 * sizeof(rt_bvh_node) == 64, "a sibling pair fills one cache line");
static rt_bvh_node *alloc_nodes(rt_arena *arena, size_t count)
{
    uint8_t *line = rt_arena_alloc_aligned(arena, (count + 1) * sizeof(rt_bvh_node), 64);
    return line ? (rt_bvh_node *)(line + 64 - sizeof(rt_bvh_node)) : NULL;
}

/* Nodes are made in scratch for the worst case (2n - 1) at the arena's mark, then the
 * arena is reset and only the nodes made are kept there, in place. */
rt_status rt_bvh_build(rt_scene *scene, rt_arena *arena)
{
    uint32_t n = scene->prim_count;
    rt_bvh *bvh = &scene->bvh;
    bvh->prim_refs = RT_NEW_ARRAY(arena, uint32_t, n > 0 ? n : 1);
    if (!bvh->prim_refs) return RT_ERR_NOMEM;
    size_t mark = rt_arena_mark(arena);
    /* Every node and reference is written before it is read: no zeroing. */
    bvh->nodes = alloc_nodes(arena, n > 0 ? 2 * (size_t)n - 1 : 1);
    build_ref *refs = n > 0 ? rt_arena_alloc(arena, (size_t)n * sizeof(build_ref)) : NULL;
    build_task *stack = RT_NEW_ARRAY(arena, build_task, RT_BVH_MAX_DEPTH + 2);
    if (!bvh->nodes || (n > 0 && !refs) || !stack) return RT_ERR_NOMEM;
    build_task root = {0, 0, n, 1, aabb_empty(), aabb_empty()};
    for (uint32_t i = 0; i < n; i++) {
        refs[i].bounds = rt_prim_bounds(scene, i);
        refs[i].prim = i;
        root.bounds = aabb_union(root.bounds, refs[i].bounds);
        root.centroids = aabb_add_point(root.centroids, centroid_of(&refs[i]));
    }
    bvh->grid = rt_bound_grid(aabb_magnitude(root.bounds));
    bvh->node_count = 1;
    bvh->depth = 1;
    store_box(&bvh->nodes[0], aabb_empty(), bvh->grid);
    bvh->nodes[0].first = 0;
    bvh->nodes[0].count = 0;
    uint32_t top = 0;
    if (n > 0) stack[top++] = root;
    while (top > 0) {
        build_task task = stack[--top];
        rt_bvh_node *node = &bvh->nodes[task.node];
        store_box(node, task.bounds, bvh->grid);
        node->first = task.first;
        node->count = task.count;
        if (task.depth > bvh->depth) bvh->depth = task.depth;
        split s;
        if (task.count <= LEAF_MIN || task.depth >= RT_BVH_MAX_DEPTH || !choose_split(refs, &task, &s)) continue;
        rt_aabb left_c, right_c;
        uint32_t left_n = partition(refs, task.first, task.count, &s, &left_c, &right_c);
        uint32_t left = bvh->node_count;
        bvh->node_count += 2;
        node->first = left;
        node->count = 0;
        /* Push right first so the left subtree is built next (depth-first, bounded stack). */
        stack[top++] = (build_task){left + 1, task.first + left_n, task.count - left_n, task.depth + 1, s.right, right_c};
        stack[top++] = (build_task){left, task.first, left_n, task.depth + 1, s.left, left_c};
    }
    for (uint32_t i = 0; i < n; i++) bvh->prim_refs[i] = refs[i].prim;
    rt_arena_reset(arena, mark);
    bvh->nodes = alloc_nodes(arena, bvh->node_count); /* the same address */
    return RT_OK;
}

/* ---- Queries ---- */

/* The double build tests a node's two children at once with SSE2 (x86-64's baseline). */
#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
#define SLAB_SSE2 1
#include <emmintrin.h>
#else
#define SLAB_SSE2 0
#endif

/* The slab test of rt_intersect_aabb on a node's stored box, with the per-axis branches
 * decided once per ray: for a non-zero direction component the near plane is lo when it
 * is positive and hi when negative (the products are monotonic in the plane, so this is
 * the swap the general test makes), and without NaN the three axes can be clamped before
 * the one comparison. Rays with a zero component, a non-finite reciprocal or origin keep
 * the general test, whose zero-direction and NaN cases differ. */
typedef struct {
    rt_vec3 origin, inv;
    rt_real t_min;
    int near[3], far[3]; /* each axis' near and far plane in rt_bvh_node.box */
    int grid;
    bool general;
    const rt_ray_setup *rs;
    const rt_bvh *bvh;
#if SLAB_SSE2
    __m128d origin2[3], inv2[3], t_min2; /* each value in both lanes */
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
        r.origin2[k] = _mm_set1_pd(rt_v3_get(o, k));
        r.inv2[k] = _mm_set1_pd(rt_v3_get(inv, k));
#endif
    }
#if SLAB_SSE2
    r.t_min2 = _mm_set1_pd(r.t_min);
#endif
    r.general = d.x == RT_ZERO || d.y == RT_ZERO || d.z == RT_ZERO || !rt_is_finite(inv.x) || !rt_is_finite(inv.y) ||
                !rt_is_finite(inv.z) || !rt_is_finite(o.x) || !rt_is_finite(o.y) || !rt_is_finite(o.z);
    return r;
}

__attribute__((always_inline)) static inline bool slab_hit(const slab_ray *r, const rt_bvh_node *node, rt_real t_max, rt_real *t_enter)
{
    if (r->general) {
        rt_aabb box = rt_bvh_node_box(r->bvh, node);
        return rt_intersect_aabb(r->rs, &box, t_max, t_enter);
    }
    const rt_bound *b = node->box;
    rt_real x0 = rt_mul(rt_sub(rt_bound_value(b[r->near[0]], r->grid), r->origin.x), r->inv.x);
    rt_real x1 = rt_mul(rt_sub(rt_bound_value(b[r->far[0]], r->grid), r->origin.x), r->inv.x);
    rt_real y0 = rt_mul(rt_sub(rt_bound_value(b[r->near[1]], r->grid), r->origin.y), r->inv.y);
    rt_real y1 = rt_mul(rt_sub(rt_bound_value(b[r->far[1]], r->grid), r->origin.y), r->inv.y);
    rt_real z0 = rt_mul(rt_sub(rt_bound_value(b[r->near[2]], r->grid), r->origin.z), r->inv.z);
    rt_real z1 = rt_mul(rt_sub(rt_bound_value(b[r->far[2]], r->grid), r->origin.z), r->inv.z);
    rt_real t0 = rt_max(rt_max(rt_max(r->t_min, x0), y0), z0);
    rt_real t1 = rt_min(rt_min(rt_min(t_max, x1), y1), z1);
    *t_enter = t0;
    return !(t0 > t1);
}

#if SLAB_SSE2
/* slab_hit on both children at once, two doubles per SSE2 register. IEEE arithmetic is
 * the same packed or scalar; minpd/maxpd are rt_min/rt_max (a < b ? a : b), and the
 * smaller of a slab's two plane distances is the near plane's (the products are
 * monotonic), the same value slab_hit reads. */
__attribute__((always_inline)) static inline unsigned slab_hit_pair_sse2(const slab_ray *r, const rt_bvh_node *pair,
                                                                         rt_real t_max, rt_real t_enter[2])
{
    __m128 a = _mm_loadu_ps(&pair[0].box[0]), b = _mm_loadu_ps(&pair[1].box[0]); /* lo x y z, hi x */
    /* hi y z, then `first` and `count` read as floats: those two lanes are never converted. */
    __m128 a_hi = _mm_loadu_ps(&pair[0].box[4]), b_hi = _mm_loadu_ps(&pair[1].box[4]);
    __m128 lxy = _mm_unpacklo_ps(a, b), lzhx = _mm_unpackhi_ps(a, b), hyz = _mm_unpacklo_ps(a_hi, b_hi);
    const __m128d *o = r->origin2, *inv = r->inv2;
    __m128d x0 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(lxy), o[0]), inv[0]);
    __m128d y0 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(lxy, lxy)), o[1]), inv[1]);
    __m128d z0 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(lzhx), o[2]), inv[2]);
    __m128d x1 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(lzhx, lzhx)), o[0]), inv[0]);
    __m128d y1 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(hyz), o[1]), inv[1]);
    __m128d z1 = _mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(hyz, hyz)), o[2]), inv[2]);
    __m128d t0 = _mm_max_pd(_mm_max_pd(_mm_max_pd(r->t_min2, _mm_min_pd(x0, x1)), _mm_min_pd(y0, y1)), _mm_min_pd(z0, z1));
    __m128d t1 = _mm_min_pd(_mm_min_pd(_mm_min_pd(_mm_set1_pd(t_max), _mm_max_pd(x0, x1)), _mm_max_pd(y0, y1)),
                            _mm_max_pd(z0, z1));
    _mm_storeu_pd(t_enter, t0);
    return (unsigned)_mm_movemask_pd(_mm_cmple_pd(t0, t1));
}
#endif

/* Tests both children of an inner node (pair = &nodes[first]): bit k of the result is
 * set when pair[k] is entered before t_max, at t_enter[k]. */
__attribute__((always_inline)) static inline unsigned slab_hit_pair(const slab_ray *r, const rt_bvh_node *pair,
                                                                    rt_real t_max, rt_real t_enter[2])
{
#if SLAB_SSE2
    if (!r->general) return slab_hit_pair_sse2(r, pair, t_max, t_enter);
#endif
    return (unsigned)slab_hit(r, &pair[0], t_max, &t_enter[0]) | (unsigned)slab_hit(r, &pair[1], t_max, &t_enter[1]) << 1;
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

__attribute__((always_inline)) static inline bool leaf_loop(const rt_scene *scene, const rt_bvh_node *leaf,
                                                            const rt_ray_setup *rs, bool any, rt_scene_hit *best,
                                                            bool *found, int kx, int ky, int kz)
{
    const uint32_t *refs = scene->bvh.prim_refs;
    for (uint32_t i = leaf->first; i < leaf->first + leaf->count; i++) {
        consider(scene, refs[i], rs, best, found, kx, ky, kz);
        if (any && *found) break;
    }
    return *found;
}

/* A leaf's primitives, out of line so that the traversal loop keeps its registers, with
 * one copy of the loop per axis permutation; with `any`, stops at the first hit.
 * Returns *found. */
__attribute__((noinline)) static bool visit_leaf(const rt_scene *scene, const rt_bvh_node *leaf, const rt_ray_setup *rs,
                                                 bool any, rt_scene_hit *best, bool *found)
{
    bool swapped = rs->kx != (rs->kz + 1) % 3; /* see rt_ray_prepare */
    switch (rs->kz * 2 + swapped) {
    case 0: return leaf_loop(scene, leaf, rs, any, best, found, 1, 2, 0);
    case 1: return leaf_loop(scene, leaf, rs, any, best, found, 2, 1, 0);
    case 2: return leaf_loop(scene, leaf, rs, any, best, found, 2, 0, 1);
    case 3: return leaf_loop(scene, leaf, rs, any, best, found, 0, 2, 1);
    case 4: return leaf_loop(scene, leaf, rs, any, best, found, 0, 1, 2);
    default: return leaf_loop(scene, leaf, rs, any, best, found, 1, 0, 2);
    }
}

static bool nearest_brute(const rt_scene *scene, const rt_ray_setup *rs, rt_scene_hit *out)
{
    bool found = false;
    for (uint32_t p = 0; p < scene->prim_count; p++) consider(scene, p, rs, out, &found, rs->kx, rs->ky, rs->kz);
    return found;
}

typedef struct {
    uint32_t node;
    rt_real t_enter;
} stack_entry;

/* Boxes are tested against the best t itself (not below it), and a popped node is
 * skipped only when it is entered beyond the best t, so ties to a lower reference survive.
 * With `any`, the first hit found ends the search (rt_scene_any). */
static bool nearest_bvh(const rt_scene *scene, const rt_ray_setup *rs, bool any, rt_scene_hit *out)
{
    const rt_bvh_node *nodes = scene->bvh.nodes;
    slab_ray sr = slab_prepare(rs, &scene->bvh);
    bool found = false;
    stack_entry stack[RT_BVH_MAX_DEPTH + 2];
    uint32_t top = 0;
    rt_real t_root;
    if (scene->prim_count == 0 || !slab_hit(&sr, &nodes[0], rs->ray.t_max, &t_root)) return false;
    stack[top++] = (stack_entry){0, t_root};
    while (top > 0) {
        stack_entry e = stack[--top];
        if (found && e.t_enter > out->hit.t) continue;
        const rt_bvh_node *node = &nodes[e.node];
        /* Descend into the nearer child directly; the farther one waits on the stack. */
        while (node->count == 0) {
            rt_real limit = found ? out->hit.t : rs->ray.t_max, t[2];
            uint32_t first = node->first;
            unsigned hits = slab_hit_pair(&sr, &nodes[first], limit, t);
            /* Branches, not selects: a predicted branch lets the next node's load start
             * before this test is done (traversal waits on memory more than on arithmetic). */
            if (hits == 1) {
                node = &nodes[first];
            } else if (hits == 2) {
                node = &nodes[first + 1];
            } else if (hits == 3 && t[0] <= t[1]) {
                stack[top++] = (stack_entry){first + 1, t[1]};
                node = &nodes[first];
            } else if (hits == 3) {
                stack[top++] = (stack_entry){first, t[0]};
                node = &nodes[first + 1];
            } else {
                node = NULL;
                break;
            }
        }
        if (!node) continue;
        if (visit_leaf(scene, node, rs, any, out, &found) && any) return true;
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

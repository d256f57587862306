/* Scene queries: nearest and any hit along a ray, with the tie rule of scene_query.h: the
 * float walk (bvh_walk.h) for the rays it takes, the general walk here for the others. */
#include "scene_query.h"
#include "bvh_slab.h"
#include "invariant.h"

#include "bvh_float.h"
#include "bvh_leaf.h"

static bool nearest_brute(const rt_scene *scene, const rt_ray_setup *rs, rt_scene_hit *out)
{
    bool found = false;
    for (uint32_t p = 0; p < scene->prim_count; p++) consider(scene, p, rs, out, &found, rs->kx, rs->ky, rs->kz, false);
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

/* clang-format off */
#define ONE_HIT(a) case 1u << a: return child_entry(node, a, t[a]);
#define TWO_HITS(a, b) case 1u << a | 1u << b: return nearer_of(node, a, b, t, stack, top);
/* clang-format on */

/* Returns the nearest of the children in `hits`, pushing the others farthest first.
 * One or two hits are told apart by branches, each with its slots as constants, not
 * computed: a predicted branch lets the next node's load start before this node's test
 * is done. */
__attribute__((always_inline)) static inline stack_entry descend(const rt_bvh_node *node, unsigned hits,
                                                                 const rt_real t[RT_BVH_WIDTH], stack_entry *stack,
                                                                 uint32_t *top)
{
    switch (hits) {
        RT_BVH_SLOTS(ONE_HIT)
        RT_BVH_SLOT_PAIRS(TWO_HITS)
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
 * Distances are compared as slab_key's keys (limit: t_max's, then the best t's).
 * With `any`, the first hit found ends the search (rt_scene_any). */
static bool nearest_bvh(const rt_scene *scene, const rt_ray_setup *rs, bool any, rt_scene_hit *out)
{
    const rt_bvh_node *nodes = scene->bvh.nodes;
    slab_ray sr = slab_prepare(rs, &scene->bvh);
    bool found = false;
    stack_entry stack[QUERY_STACK];
    uint32_t top = 0;
    rt_real limit = slab_key(&sr, rs->ray.t_max);
    if (scene->prim_count == 0) return false;
    stack[top++] = (stack_entry){0, 0, slab_key(&sr, rs->ray.t_min)}; /* the root node */
    while (top > 0) {
        stack_entry e = stack[--top];
        if (found && e.t_enter > limit) continue;
        /* Descend into the nearest child directly; the others wait on the stack. */
        while (e.count == 0) {
            const rt_bvh_node *node = &nodes[e.child];
            rt_real t[RT_BVH_WIDTH];
            unsigned hits = slab_hit_children(&sr, node, limit, t);
            if (!hits) break;
            RT_ASSERT(top + RT_BVH_WIDTH - 1 <= QUERY_STACK);
            e = descend(node, hits, t, stack, &top);
        }
        if (e.count == 0) continue;
        if (visit_leaf(scene, e.child, e.count, rs, any, out, &found)) {
            if (any) return true;
            limit = slab_key(&sr, out->hit.t);
        }
    }
    return found;
}

bool rt_scene_prim_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit)
{
    return prim_intersect(scene, prim, rs, hit, rs->kx, rs->ky, rs->kz);
}

/* The BVH walk for the ray: the float one where it can take the ray. */
static bool walk(const rt_scene *scene, const rt_ray_setup *rs, bool any, rt_scene_hit *out)
{
#if FLOAT_WALK
    float_slab f;
    if (scene->bvh.kernel != RT_KERNEL_PORTABLE && scene->prim_count > 0 &&
        float_slab_prepare(rs, scene->bvh.extent, &f))
        return scene->bvh.kernel == RT_KERNEL_SSE2 ? rt_bvh_walk_sse2(scene, rs, &f, any, out)
                                                   : rt_bvh_walk_avx2(scene, rs, &f, any, out);
#endif
    return nearest_bvh(scene, rs, any, out);
}

bool rt_scene_nearest(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh, rt_scene_hit *out)
{
    return use_bvh ? walk(scene, rs, false, out) : nearest_brute(scene, rs, out);
}

bool rt_scene_any(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh)
{
    rt_scene_hit first;
    if (use_bvh) return walk(scene, rs, true, &first);
    rt_prim_hit h;
    for (uint32_t p = 0; p < scene->prim_count; p++)
        if (rt_scene_prim_intersect(scene, p, rs, &h)) return true;
    return false;
}

uint32_t rt_scene_triangle_object(const rt_scene *scene, uint32_t triangle)
{
    /* The last mesh object whose first triangle is at or before it. */
    uint32_t lo = 0, hi = scene->mesh_object_count;
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (scene->objects[scene->mesh_objects[mid]].first_triangle <= triangle)
            lo = mid;
        else
            hi = mid;
    }
    return scene->mesh_objects[lo];
}

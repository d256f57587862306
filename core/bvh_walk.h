/* The one-ray float walk (the double build on x86): each node's four children tested in
 * one 128-bit register against the ray's conservative float bounds (bvh_float.h), the
 * nearest hit child descended into directly, the walk's state kept in registers.
 *
 * A template: the including file defines WALK_TARGET (a function attribute, possibly
 * empty) and WALK_NAME (the name of the entry point), after including bvh_float.h. The
 * same operations in another instruction set's encoding give the same bits (no
 * contraction: -ffp-contract=off). */

/* A child waiting to be visited: a node (count 0) or a leaf's references, and a lower
 * bound of the distance at which the ray enters its box. */
typedef struct {
    uint32_t child, count;
    float t;
} float_entry;

static inline float_entry float_child(const rt_bvh_node *node, int c, const float *t)
{
    return (float_entry){node->child[c], node->count[c], t[c]};
}

/* Of hit children a < b, returns the nearer (a on a tie) and pushes the other. */
__attribute__((always_inline)) static inline float_entry float_nearer(const rt_bvh_node *node, int a, int b,
                                                                      const float *t, float_entry *stack, uint32_t *top)
{
    if (t[b] < t[a]) {
        stack[(*top)++] = float_child(node, a, t);
        return float_child(node, b, t);
    }
    stack[(*top)++] = float_child(node, b, t);
    return float_child(node, a, t);
}

/* Returns the nearest of the children in `hits`, pushing the others farthest first.
 * One or two hits are told apart by branches, each with its slots as constants, not
 * computed: a predicted branch lets the next node's load start before this node's test
 * is done. */
__attribute__((always_inline)) static inline float_entry float_descend(const rt_bvh_node *node, unsigned hits,
                                                                       const float *t, float_entry *stack,
                                                                       uint32_t *top)
{
    switch (hits) {
    case 1: return float_child(node, 0, t);
    case 2: return float_child(node, 1, t);
    case 4: return float_child(node, 2, t);
    case 8: return float_child(node, 3, t);
    case 3: return float_nearer(node, 0, 1, t, stack, top);
    case 5: return float_nearer(node, 0, 2, t, stack, top);
    case 6: return float_nearer(node, 1, 2, t, stack, top);
    case 9: return float_nearer(node, 0, 3, t, stack, top);
    case 10: return float_nearer(node, 1, 3, t, stack, top);
    case 12: return float_nearer(node, 2, 3, t, stack, top);
    default: break;
    }
    int order[RT_BVH_WIDTH], n = 0; /* the hit children by entry distance, ties by slot */
    for (int c = 0; c < RT_BVH_WIDTH; c++) {
        if (!(hits >> c & 1u)) continue;
        int i = n++;
        for (; i > 0 && t[order[i - 1]] > t[c]; i--) order[i] = order[i - 1];
        order[i] = c;
    }
    for (int i = n - 1; i > 0; i--) stack[(*top)++] = float_child(node, order[i], t);
    return float_child(node, order[0], t);
}

/* Each wide level pushes at most RT_BVH_WIDTH - 1 children. */
#define FLOAT_STACK (RT_BVH_MAX_DEPTH * (RT_BVH_WIDTH - 1) + 1)

/* The nearest hit (or with `any`, the first found) as rt_scene_nearest defines it. Boxes
 * are tested against the best t rounded up, and a popped child is skipped only when it
 * is entered beyond that, so ties to a lower reference survive. An unused slot's box is
 * empty (lo = FLT_MAX, hi = -FLT_MAX: entered beyond where it is left), so no slot needs
 * a check of its count. */
WALK_TARGET __attribute__((always_inline)) static inline bool float_walk(const rt_scene *scene, const rt_ray_setup *rs,
                                                                         const float_slab *f, bool any,
                                                                         rt_scene_hit *out)
{
    const rt_bvh_node *nodes = scene->bvh.nodes;
    rt_vec3 d = rs->ray.direction;
    /* Byte offsets of each axis' near and far rows in rt_bvh_node.box (lo x y z, hi x y z). */
    const size_t row = sizeof nodes->box[0];
    size_t nx = d.x < 0 ? 3 * row : 0, ny = d.y < 0 ? 4 * row : row, nz = d.z < 0 ? 5 * row : 2 * row;
    size_t fx = d.x < 0 ? 0 : 3 * row, fy = d.y < 0 ? row : 4 * row, fz = d.z < 0 ? 2 * row : 5 * row;
    v4f onx = v4f_all(f->o_near[0]), ony = v4f_all(f->o_near[1]), onz = v4f_all(f->o_near[2]);
    v4f ofx = v4f_all(f->o_far[0]), ofy = v4f_all(f->o_far[1]), ofz = v4f_all(f->o_far[2]);
    v4f inx = v4f_all(f->inv_near[0]), iny = v4f_all(f->inv_near[1]), inz = v4f_all(f->inv_near[2]);
    v4f ifx = v4f_all(f->inv_far[0]), ify = v4f_all(f->inv_far[1]), ifz = v4f_all(f->inv_far[2]);
    v4f t_min = v4f_all(f->t_min), limit = v4f_all(f->t_max);
    float best = f->t_max;
    float_entry stack[FLOAT_STACK], e = {0, 0, 0.0f}; /* the root node */
    uint32_t top = 0;
    bool found = false;
    for (;;) {
        /* Descend into the nearest child directly; the others wait on the stack. */
        while (e.count == 0) {
            const rt_bvh_node *node = &nodes[e.child];
            const char *b = (const char *)node->box;
            v4f t0 = __builtin_ia32_maxps(t_min, (*(const v4f *)(b + nx) - onx) * inx);
            v4f t1 = __builtin_ia32_minps(limit, (*(const v4f *)(b + fx) - ofx) * ifx);
            t0 = __builtin_ia32_maxps(t0, (*(const v4f *)(b + ny) - ony) * iny);
            t1 = __builtin_ia32_minps(t1, (*(const v4f *)(b + fy) - ofy) * ify);
            t0 = __builtin_ia32_maxps(t0, (*(const v4f *)(b + nz) - onz) * inz);
            t1 = __builtin_ia32_minps(t1, (*(const v4f *)(b + fz) - ofz) * ifz);
            unsigned hits = (unsigned)__builtin_ia32_movmskps(__builtin_ia32_cmpleps(t0, t1));
            if (!hits) goto pop;
            float t[RT_BVH_WIDTH];
            *(v4f *)t = t0;
            RT_ASSERT(top + RT_BVH_WIDTH - 1 <= FLOAT_STACK);
            e = float_descend(node, hits, t, stack, &top);
        }
        if (visit_leaf(scene, e.child, e.count, rs, any, out, &found)) {
            if (any) return true;
            best = float_outward(out->hit.t, true);
            limit = v4f_all(best);
        }
    pop:
        do {
            if (top == 0) return found;
            e = stack[--top];
        } while (e.t > best);
    }
}

/* The walk with `any` a constant in each branch, so each query gets its own code. */
WALK_TARGET bool WALK_NAME(const rt_scene *scene, const rt_ray_setup *rs, const float_slab *f, bool any,
                           rt_scene_hit *out)
{
    return any ? float_walk(scene, rs, f, true, out) : float_walk(scene, rs, f, false, out);
}

/* The one-ray float walk (the double build on x86): each node's eight children tested,
 * a register of floats at a time, against the ray's conservative float bounds
 * (bvh_float.h), the nearest hit child descended into directly, the walk's state kept in
 * registers.
 *
 * A template: the including file defines WALK_VEC (vector bytes: 16 for SSE2, 32 for
 * AVX2), WALK_TARGET (a function attribute, possibly empty) and WALK_NAME (the name of
 * the entry point), after including bvh_float.h. The same operations in another
 * instruction set's encoding give the same bits (no contraction: -ffp-contract=off). */

#define WALK_LANES (WALK_VEC / 4)              /* floats per vector */
#define WALK_PARTS (RT_BVH_WIDTH / WALK_LANES) /* vectors per row of a node's boxes */
typedef float walk_v __attribute__((vector_size(WALK_VEC), aligned(4), may_alias));
#if WALK_VEC == 32
#define WALK_ALL(x) ((walk_v){x, x, x, x, x, x, x, x})
#define WALK_MAX __builtin_ia32_maxps256
#define WALK_MIN __builtin_ia32_minps256
#define WALK_MASK_LE(a, b) ((unsigned)__builtin_ia32_movmskps256(__builtin_ia32_cmpps256(a, b, 2))) /* _CMP_LE_OS */
#else
#define WALK_ALL(x) ((walk_v){x, x, x, x})
#define WALK_MAX __builtin_ia32_maxps
#define WALK_MIN __builtin_ia32_minps
#define WALK_MASK_LE(a, b) ((unsigned)__builtin_ia32_movmskps(__builtin_ia32_cmpleps(a, b)))
#endif

/* In float_walk: the node's children whose boxes start at byte `at` of each row, a
 * vector of them: their entry distances (bounded from below) into `near`, and which
 * ones the ray enters into `hits`. A statement: in a loop over the parts, gcc spilled
 * the ray's vectors to the stack (docs/performance.md). */
#define WALK_TEST(at, near, hits)                                              \
    do {                                                                       \
        const char *b = (const char *)node->box + (at);                        \
        near = WALK_MAX(t_min, (*(const walk_v *)(b + nx) - onx) * inx);       \
        walk_v far = WALK_MIN(limit, (*(const walk_v *)(b + fx) - ofx) * ifx); \
        near = WALK_MAX(near, (*(const walk_v *)(b + ny) - ony) * iny);        \
        far = WALK_MIN(far, (*(const walk_v *)(b + fy) - ofy) * ify);          \
        near = WALK_MAX(near, (*(const walk_v *)(b + nz) - onz) * inz);        \
        far = WALK_MIN(far, (*(const walk_v *)(b + fz) - ofz) * ifz);          \
        hits = WALK_MASK_LE(near, far);                                        \
    } while (0)

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

/* clang-format off */
#define FLOAT_ONE_HIT(a) case 1u << a: return float_child(node, a, t);
#define FLOAT_TWO_HITS(a, b) case 1u << a | 1u << b: return float_nearer(node, a, b, t, stack, top);
/* clang-format on */

/* Returns the nearest of the children in `hits`, pushing the others farthest first.
 * One or two hits are told apart by branches, each with its slots as constants, not
 * computed: a predicted branch lets the next node's load start before this node's test
 * is done. */
__attribute__((always_inline)) static inline float_entry float_descend(const rt_bvh_node *node, unsigned hits,
                                                                       const float *t, float_entry *stack,
                                                                       uint32_t *top)
{
    switch (hits) {
        RT_BVH_SLOTS(FLOAT_ONE_HIT)
        RT_BVH_SLOT_PAIRS(FLOAT_TWO_HITS)
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
    walk_v onx = WALK_ALL(f->o_near[0]), ony = WALK_ALL(f->o_near[1]), onz = WALK_ALL(f->o_near[2]);
    walk_v ofx = WALK_ALL(f->o_far[0]), ofy = WALK_ALL(f->o_far[1]), ofz = WALK_ALL(f->o_far[2]);
    walk_v inx = WALK_ALL(f->inv_near[0]), iny = WALK_ALL(f->inv_near[1]), inz = WALK_ALL(f->inv_near[2]);
    walk_v ifx = WALK_ALL(f->inv_far[0]), ify = WALK_ALL(f->inv_far[1]), ifz = WALK_ALL(f->inv_far[2]);
    walk_v t_min = WALK_ALL(f->t_min), limit = WALK_ALL(f->t_max);
    float best = f->t_max;
    float_entry stack[FLOAT_STACK], e = {0, 0, 0.0f}; /* the root node */
    uint32_t top = 0;
    bool found = false;
    for (;;) {
        /* Descend into the nearest child directly; the others wait on the stack. */
        while (e.count == 0) {
            const rt_bvh_node *node = &nodes[e.child];
            float t[RT_BVH_WIDTH];
#if WALK_PARTS == 1
            walk_v t0;
            unsigned hits;
            WALK_TEST(0, t0, hits);
            if (!hits) goto pop;
            *(walk_v *)t = t0;
#else
            walk_v t0, t4;
            unsigned lo, hi;
            WALK_TEST(0, t0, lo);
            WALK_TEST(WALK_VEC, t4, hi);
            unsigned hits = lo | hi << WALK_LANES;
            if (!hits) goto pop;
            *(walk_v *)t = t0;
            *(walk_v *)(t + WALK_LANES) = t4;
#endif
            RT_ASSERT(top + RT_BVH_WIDTH - 1 <= FLOAT_STACK);
            e = float_descend(node, hits, t, stack, &top);
        }
        if (visit_leaf(scene, e.child, e.count, rs, any, out, &found)) {
            if (any) return true;
            best = float_outward(out->hit.t, true);
            limit = WALK_ALL(best);
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

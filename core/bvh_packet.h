/* A packet of up to RT_PACKET rays walked through the BVH together (the double build on
 * x86). Each node's children are tested for all the packet's rays at once, one ray per
 * lane, with each ray's conservative float bounds (bvh_float.h); each triangle of a leaf
 * gets the watertight test (rt_intersect_triangle_axes) for all the rays at once, one
 * ray per double lane, with exactly the scalar test's operations in the same order, and
 * its hits go through the tie rule one ray at a time. So every ray gets exactly what
 * rt_scene_nearest (or rt_scene_any) gives it alone. The rays of a packet share their
 * direction's octant and axis permutation (bvh_stream.c groups them).
 *
 * A template: the including file defines PACKET_VEC (vector bytes: 16 for SSE2, 32 for
 * AVX2), PACKET_TARGET (a function attribute, possibly empty) and PACKET_WALK (the name
 * of the entry point), after including bvh_float.h; and may define PACKET_VEC_D, the
 * bytes of the double vectors that hold the rays for the triangle tests (64: AVX-512,
 * the whole packet in one vector; PACKET_VEC otherwise). */

#ifndef PACKET_VEC_D
#define PACKET_VEC_D PACKET_VEC
#endif
#define PACKET_LANES_F (PACKET_VEC / 4)        /* floats per vector */
#define PACKET_LANES_D (PACKET_VEC_D / 8)      /* doubles per vector */
#define PACKET_NF (RT_PACKET / PACKET_LANES_F) /* float vectors per packet quantity */
#define PACKET_ND (RT_PACKET / PACKET_LANES_D) /* double vectors per packet quantity */

typedef float pk_f __attribute__((vector_size(PACKET_VEC)));
typedef int32_t pk_i __attribute__((vector_size(PACKET_VEC)));
typedef double pk_d __attribute__((vector_size(PACKET_VEC_D)));
typedef int64_t pk_l __attribute__((vector_size(PACKET_VEC_D)));

#if PACKET_VEC == 32
#define PK_MAXF __builtin_ia32_maxps256
#define PK_MINF __builtin_ia32_minps256
#define PK_MASKF(x) ((unsigned)__builtin_ia32_movmskps256((pk_f)(x)))
#define PK_ALLF(x) ((pk_f){x, x, x, x, x, x, x, x})
#if PACKET_VEC_D == 64
typedef long long pk_ll __attribute__((vector_size(64))); /* the type AVX-512's builtins take */
#define PK_MASKD(x) ((unsigned)__builtin_ia32_cvtq2mask512((pk_ll)(x)))
#define PK_ALLD(x) ((pk_d){x, x, x, x, x, x, x, x})
#else
#define PK_MASKD(x) ((unsigned)__builtin_ia32_movmskpd256((pk_d)(x)))
#define PK_ALLD(x) ((pk_d){x, x, x, x})
#endif
#else
#define PK_MAXF __builtin_ia32_maxps
#define PK_MINF __builtin_ia32_minps
#define PK_MASKF(x) ((unsigned)__builtin_ia32_movmskps((pk_f)(x)))
#define PK_MASKD(x) ((unsigned)__builtin_ia32_movmskpd((pk_d)(x)))
#define PK_ALLF(x) ((pk_f){x, x, x, x})
#define PK_ALLD(x) ((pk_d){x, x})
#endif
/* The triangle tests' comparisons of double vectors, as pk_m lane masks: a vector of
 * all-ones and zero lanes, or with AVX-512 the bits of a compare straight into a mask
 * register, by the predicates of C's <, <= and > (signalling) and == (quiet). PK_BITS
 * gives a mask's bits. */
#if PACKET_VEC_D == 64
typedef unsigned pk_m;
#define PK_CMPD(a, b, predicate) ((unsigned)__builtin_ia32_cmppd512_mask(a, b, predicate, (unsigned char)0xff, 4))
#define PK_LTD(a, b) PK_CMPD(a, b, 0x01)
#define PK_LED(a, b) PK_CMPD(a, b, 0x02)
#define PK_GTD(a, b) PK_CMPD(a, b, 0x0e)
#define PK_EQD(a, b) PK_CMPD(a, b, 0x00)
#define PK_BITS(m) ((m)&0xffu)
#else
typedef pk_l pk_m;
#define PK_LTD(a, b) ((a) < (b))
#define PK_LED(a, b) ((a) <= (b))
#define PK_GTD(a, b) ((a) > (b))
#define PK_EQD(a, b) ((a) == (b))
#define PK_BITS(m) PK_MASKD(m)
#endif
#ifdef __clang__
#define PK_SHUFFLE(a, ...) __builtin_shufflevector(a, a, __VA_ARGS__)
#else
#define PK_SHUFFLE(a, ...) __builtin_shuffle(a, (pk_i){__VA_ARGS__})
#endif

/* The packet: each quantity as PACKET_NF float (or PACKET_ND double) vectors, lane l of
 * the packet in lane l % lanes of vector l / lanes. */
typedef struct {
    pk_f o_near[3][PACKET_NF], o_far[3][PACKET_NF], inv_near[3][PACKET_NF], inv_far[3][PACKET_NF];
    pk_f t_min_f[PACKET_NF], best[PACKET_NF]; /* best: the t each ray's boxes are tested against */
    pk_d origin[3][PACKET_ND], sx[PACKET_ND], sy[PACKET_ND], sz[PACKET_ND], t_min[PACKET_ND], t_max[PACKET_ND];
    size_t near[3], far[3]; /* byte offsets of each axis' near and far row of rt_bvh_node.box */
    int order;              /* the rays' axis order (rt_ray_setup.order) */
} pk_packet;

/* A child waiting to be visited by the rays in `mask`, each entering its box at or after t. */
typedef struct {
    uint32_t child, count, mask;
    pk_f t[PACKET_NF];
} pk_entry;

/* Tests child c of `node` for the packet's rays: returns the lanes that enter its box,
 * with their entry distances (bounded from below) in t, +infinity in the other lanes. */
__attribute__((always_inline)) static inline PACKET_TARGET unsigned pk_child(const pk_packet *p,
                                                                             const rt_bvh_node *node, int c,
                                                                             pk_f t[PACKET_NF])
{
    const char *b = (const char *)node->box;
    const pk_i inf = (pk_i)PK_ALLF(__builtin_inff());
    pk_f nx = PK_ALLF(((const float *)(b + p->near[0]))[c]), ny = PK_ALLF(((const float *)(b + p->near[1]))[c]);
    pk_f nz = PK_ALLF(((const float *)(b + p->near[2]))[c]), fx = PK_ALLF(((const float *)(b + p->far[0]))[c]);
    pk_f fy = PK_ALLF(((const float *)(b + p->far[1]))[c]), fz = PK_ALLF(((const float *)(b + p->far[2]))[c]);
    unsigned hits = 0;
    for (int v = 0; v < PACKET_NF; v++) {
        pk_f t0 = PK_MAXF(p->t_min_f[v], (nx - p->o_near[0][v]) * p->inv_near[0][v]);
        pk_f t1 = PK_MINF(p->best[v], (fx - p->o_far[0][v]) * p->inv_far[0][v]);
        t0 = PK_MAXF(t0, (ny - p->o_near[1][v]) * p->inv_near[1][v]);
        t1 = PK_MINF(t1, (fy - p->o_far[1][v]) * p->inv_far[1][v]);
        t0 = PK_MAXF(t0, (nz - p->o_near[2][v]) * p->inv_near[2][v]);
        t1 = PK_MINF(t1, (fz - p->o_far[2][v]) * p->inv_far[2][v]);
        pk_i in = t0 <= t1;
        t[v] = (pk_f)(((pk_i)t0 & in) | (inf & ~in));
        hits |= PK_MASKF(in) << (v * PACKET_LANES_F);
    }
    return hits;
}

/* The smallest (or with `largest`, the largest) of v's lanes, in every lane: v folded
 * onto itself with its halves, quarters (and eighths) swapped. */
__attribute__((always_inline)) static inline PACKET_TARGET pk_f pk_across(pk_f v, bool largest)
{
#define PK_FOLD(w) (v = largest ? PK_MAXF(v, w) : PK_MINF(v, w))
#if PACKET_VEC == 32
    PK_FOLD(PK_SHUFFLE(v, 4, 5, 6, 7, 0, 1, 2, 3));
    PK_FOLD(PK_SHUFFLE(v, 2, 3, 0, 1, 6, 7, 4, 5));
    return PK_FOLD(PK_SHUFFLE(v, 1, 0, 3, 2, 5, 4, 7, 6));
#else
    PK_FOLD(PK_SHUFFLE(v, 2, 3, 0, 1));
    return PK_FOLD(PK_SHUFFLE(v, 1, 0, 3, 2));
#endif
#undef PK_FOLD
}

/* The smallest of a child's entry distances (pk_child's t): the order of children. */
__attribute__((always_inline)) static inline PACKET_TARGET float pk_first(const pk_f t[PACKET_NF])
{
    pk_f v = t[0];
    for (int w = 1; w < PACKET_NF; w++) v = PK_MINF(v, t[w]);
    return pk_across(v, false)[0];
}

/* rt_magnitude lane by lane: the sign bit cleared. */
__attribute__((always_inline)) static inline PACKET_TARGET pk_d pk_magnitude(pk_d a)
{
    return (pk_d)((pk_l)a & ~(pk_l)PK_ALLD(-0.0));
}

/* The watertight test of one triangle (vertices a, b, c) for the rays in `lanes` (bit i:
 * lane i) of double vector v, each lane by rt_intersect_triangle_axes's operations;
 * every hit goes through the tie rule of `loses_to` for its ray. Returns the lanes of v
 * whose nearest hit changed. */
__attribute__((always_inline)) static inline PACKET_TARGET unsigned pk_triangle(const pk_packet *p, int v,
                                                                                unsigned lanes, uint32_t prim,
                                                                                const rt_vec3 *va, const rt_vec3 *vb,
                                                                                const rt_vec3 *vc, rt_scene_hit *out,
                                                                                bool *found, int kx, int ky, int kz)
{
    const rt_real a[3] = {va->x, va->y, va->z}, b[3] = {vb->x, vb->y, vb->z}, c[3] = {vc->x, vc->y, vc->z};
    const pk_d zero = PK_ALLD(0.0);
    unsigned improved = 0;
    pk_d az = PK_ALLD(a[kz]) - p->origin[kz][v], bz = PK_ALLD(b[kz]) - p->origin[kz][v];
    pk_d cz = PK_ALLD(c[kz]) - p->origin[kz][v];
    pk_d ax = (PK_ALLD(a[kx]) - p->origin[kx][v]) - p->sx[v] * az;
    pk_d ay = (PK_ALLD(a[ky]) - p->origin[ky][v]) - p->sy[v] * az;
    pk_d bx = (PK_ALLD(b[kx]) - p->origin[kx][v]) - p->sx[v] * bz;
    pk_d by = (PK_ALLD(b[ky]) - p->origin[ky][v]) - p->sy[v] * bz;
    pk_d cx = (PK_ALLD(c[kx]) - p->origin[kx][v]) - p->sx[v] * cz;
    pk_d cy = (PK_ALLD(c[ky]) - p->origin[ky][v]) - p->sy[v] * cz;
    pk_d u = cx * by - cy * bx, vv = ax * cy - ay * cx, w = bx * ay - by * ax;
    pk_m outside =
        (PK_LTD(u, zero) | PK_LTD(vv, zero) | PK_LTD(w, zero)) & (PK_GTD(u, zero) | PK_GTD(vv, zero) | PK_GTD(w, zero));
    lanes &= ~PK_BITS(outside);
    if (!lanes) return 0;
    pk_d det = (u + vv) + w;
    pk_d extent_x = (pk_magnitude(ax) + pk_magnitude(bx)) + pk_magnitude(cx),
         extent_y = (pk_magnitude(ay) + pk_magnitude(by)) + pk_magnitude(cy);
    pk_d t = ((u * (p->sz[v] * az) + vv * (p->sz[v] * bz)) + w * (p->sz[v] * cz)) / det;
    pk_m edge_on = PK_LED(pk_magnitude(det), (extent_x * extent_y) * PK_ALLD(1e-12));
    pk_m inside = PK_GTD(t, p->t_min[v]) & PK_LTD(t, p->t_max[v]) & PK_EQD(t - t, zero);
    lanes &= PK_BITS(inside & ~edge_on);
    if (!lanes) return 0;
    pk_d b1 = vv / det, b2 = w / det;
    for (; lanes; lanes &= lanes - 1) {
        int i = __builtin_ctz(lanes), l = v * PACKET_LANES_D + i;
        rt_scene_hit *best = &out[l];
        if (loses_to(best, found[l], t[i], prim)) continue;
        best->hit.t = t[i];
        best->hit.b1 = b1[i];
        best->hit.b2 = b2[i];
        best->hit.part = RT_PART_SURFACE;
        best->prim = prim;
        found[l] = true;
        improved |= 1u << i;
    }
    return improved;
}

/* The references of a leaf for the rays in mask; returns the lanes whose nearest hit
 * changed. With `any`, a lane stops at its first hit. Each double vector of rays goes
 * through the whole leaf in turn, so a vector with no ray in mask is passed over once,
 * not at every reference (and the avx2 kernel spills less); each ray meets the
 * references in the same order either way. */
__attribute__((always_inline)) static inline PACKET_TARGET unsigned pk_leaf_loop(
    const rt_scene *scene, const pk_packet *p, const rt_ray_setup *const *rs, uint32_t first, uint32_t count,
    unsigned mask, bool any, rt_scene_hit *out, bool *found, int kx, int ky, int kz)
{
    const uint32_t *refs = scene->bvh.prim_refs;
    unsigned improved = 0;
    for (int v = 0; v < PACKET_ND; v++) {
        unsigned lanes = mask >> (v * PACKET_LANES_D) & ((1u << PACKET_LANES_D) - 1);
        for (uint32_t i = first; i < first + count && lanes; i++) {
            uint32_t prim = refs[i];
            unsigned got = 0;
            if (prim < scene->triangle_count) {
                const rt_triangle *tri = &scene->triangles[prim];
                got = pk_triangle(p, v, lanes, prim, &scene->positions[tri->v[0]], &scene->positions[tri->v[1]],
                                  &scene->positions[tri->v[2]], out, found, kx, ky, kz);
            } else {
                for (unsigned m = lanes; m; m &= m - 1) {
                    int lane = __builtin_ctz(m), l = v * PACKET_LANES_D + lane;
                    if (consider(scene, prim, rs[l], &out[l], &found[l], kx, ky, kz, false)) got |= 1u << lane;
                }
            }
            improved |= got << (v * PACKET_LANES_D);
            if (any) lanes &= ~got;
        }
    }
    return improved;
}

__attribute__((noinline)) static PACKET_TARGET unsigned pk_leaf(const rt_scene *scene, const pk_packet *p,
                                                                const rt_ray_setup *const *rs, uint32_t first,
                                                                uint32_t count, unsigned mask, bool any,
                                                                rt_scene_hit *out, bool *found)
{
    switch (p->order) {
    case 0: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 1, 2, 0);
    case 1: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 2, 1, 0);
    case 2: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 2, 0, 1);
    case 3: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 0, 2, 1);
    case 4: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 0, 1, 2);
    default: return pk_leaf_loop(scene, p, rs, first, count, mask, any, out, found, 1, 0, 2);
    }
}

/* The float vector of packet lanes [w * PACKET_LANES_F, (w + 1) * PACKET_LANES_F) of a
 * quantity held in double vectors x: each lane rounded to float as a cast does. */
#if PACKET_LANES_D == PACKET_LANES_F
__attribute__((always_inline)) static inline PACKET_TARGET pk_f pk_floats(const pk_d x[PACKET_ND], int w)
{
    return __builtin_convertvector(x[w], pk_f);
}
#else
typedef float pk_half __attribute__((vector_size(PACKET_VEC / 2))); /* a double vector's lanes as floats */

__attribute__((always_inline)) static inline PACKET_TARGET pk_f pk_floats(const pk_d x[PACKET_ND], int w)
{
    pk_half lo = __builtin_convertvector(x[2 * w], pk_half), hi = __builtin_convertvector(x[2 * w + 1], pk_half);
#if PACKET_VEC == 32
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3);
#endif
}
#endif

/* The lanes of double vector v from a field of the lanes' rays r. */
#if PACKET_VEC_D == 64
#define PK_GATHER(r, field)                                                                                          \
    ((pk_d){(r)[0]->field, (r)[1]->field, (r)[2]->field, (r)[3]->field, (r)[4]->field, (r)[5]->field, (r)[6]->field, \
            (r)[7]->field})
#elif PACKET_VEC == 32
#define PK_GATHER(r, field) ((pk_d){(r)[0]->field, (r)[1]->field, (r)[2]->field, (r)[3]->field})
#else
#define PK_GATHER(r, field) ((pk_d){(r)[0]->field, (r)[1]->field})
#endif

/* Fills the packet from the n <= RT_PACKET rays (one octant and permutation); lanes from
 * n on repeat ray 0. Returns the lanes the float bounds can take (float_slab_prepare,
 * with its roundings, lane by lane). */
static PACKET_TARGET unsigned pk_fill(pk_packet *p, const rt_ray_setup *const *rs, uint32_t n, rt_real extent)
{
    pk_d inv[3][PACKET_ND], near[3][PACKET_ND], far[3][PACKET_ND], shrink[3][PACKET_ND], grow[3][PACKET_ND];
    pk_d t_lo[PACKET_ND], t_hi[PACKET_ND];
    const pk_d small = PK_ALLD(0x1p-100), large = PK_ALLD(0x1p100), reach = PK_ALLD(0x1p120), ext = PK_ALLD(extent);
    const pk_d step = PK_ALLD(0x1p-23), tiny = PK_ALLD(0x1p-126), zero = PK_ALLD(0.0);
    unsigned usable = 0;
    for (int v = 0; v < PACKET_ND; v++) {
        const rt_ray_setup *r[PACKET_LANES_D];
        for (int i = 0; i < PACKET_LANES_D; i++) {
            uint32_t l = (uint32_t)(v * PACKET_LANES_D + i);
            r[i] = rs[l < n ? l : 0];
        }
        p->origin[0][v] = PK_GATHER(r, ray.origin.x), p->origin[1][v] = PK_GATHER(r, ray.origin.y);
        p->origin[2][v] = PK_GATHER(r, ray.origin.z);
        inv[0][v] = PK_GATHER(r, inv_direction.x), inv[1][v] = PK_GATHER(r, inv_direction.y);
        inv[2][v] = PK_GATHER(r, inv_direction.z);
        p->sx[v] = PK_GATHER(r, sx), p->sy[v] = PK_GATHER(r, sy), p->sz[v] = PK_GATHER(r, sz);
        p->t_min[v] = PK_GATHER(r, ray.t_min), p->t_max[v] = PK_GATHER(r, ray.t_max);
        pk_l ok = (p->t_min[v] >= small) & (p->t_min[v] <= large);
        for (int k = 0; k < 3; k++) {
            pk_d o = p->origin[k][v], mag = pk_magnitude(inv[k][v]), o_mag = pk_magnitude(o);
            ok &= (mag >= small) & (mag <= large) & (o_mag <= large) & ((ext + o_mag) * mag <= reach);
            pk_d pad = o_mag * step + tiny, up = o + pad, down = o - pad;
            pk_l pos = inv[k][v] > zero;
            near[k][v] = (pk_d)(((pk_l)up & pos) | ((pk_l)down & ~pos));
            far[k][v] = (pk_d)(((pk_l)down & pos) | ((pk_l)up & ~pos));
            shrink[k][v] = inv[k][v] * PK_ALLD(1.0 - 0x1p-21), grow[k][v] = inv[k][v] * PK_ALLD(1.0 + 0x1p-21);
        }
        t_lo[v] = p->t_min[v] - (pk_magnitude(p->t_min[v]) * step + tiny);
        t_hi[v] = p->t_max[v] + (pk_magnitude(p->t_max[v]) * step + tiny);
        usable |= PK_MASKD(ok) << (v * PACKET_LANES_D);
    }
    for (int w = 0; w < PACKET_NF; w++) {
        for (int k = 0; k < 3; k++) {
            p->o_near[k][w] = pk_floats(near[k], w), p->o_far[k][w] = pk_floats(far[k], w);
            p->inv_near[k][w] = pk_floats(shrink[k], w), p->inv_far[k][w] = pk_floats(grow[k], w);
        }
        p->t_min_f[w] = pk_floats(t_lo, w), p->best[w] = pk_floats(t_hi, w);
    }
    rt_vec3 d = rs[0]->ray.direction;
    const size_t row = sizeof((const rt_bvh_node *)0)->box[0];
    p->near[0] = d.x < 0 ? 3 * row : 0, p->near[1] = d.y < 0 ? 4 * row : row, p->near[2] = d.z < 0 ? 5 * row : 2 * row;
    p->far[0] = d.x < 0 ? 0 : 3 * row, p->far[1] = d.y < 0 ? row : 4 * row, p->far[2] = d.z < 0 ? 2 * row : 5 * row;
    p->order = rs[0]->order;
    return usable & (n >= 32 ? ~0u : (1u << n) - 1);
}

#if PACKET_VEC == 32 && RT_BVH_WIDTH == 8 && PACKET_NF == 1
#define PK_FRUSTUM 1
typedef float pk_row __attribute__((vector_size(32), aligned(4), may_alias)); /* a row of a node's boxes */

/* A packet's frustum: for each axis the extremes over its lanes of the near and far
 * origin bounds (the one that gives the smallest near and largest far distance) and of
 * the reciprocals, each in every lane, so that one test of a node's eight boxes bounds
 * every lane's entry from below and exit from above (pk_frustum_test). */
typedef struct {
    pk_f o_near[3], o_far[3], near_lo[3], near_hi[3], far_lo[3], far_hi[3], t_min;
} pk_frustum;

/* The smallest (or with `largest`, the largest) of x's lanes in `lanes`, in every lane. */
__attribute__((always_inline)) static inline PACKET_TARGET pk_f pk_extreme(pk_f x, unsigned lanes, bool largest)
{
    const pk_i bit = {1, 2, 4, 8, 16, 32, 64, 128};
    pk_i in = (bit & (int)lanes) != 0;
    pk_f fill = PK_ALLF(largest ? -__builtin_inff() : __builtin_inff());
    return pk_across((pk_f)(((pk_i)x & in) | ((pk_i)fill & ~in)), largest);
}

/* The frustum of the packet's lanes in `lanes` (not 0), whose bounds pk_fill made. A
 * lane's near distance on an axis is (b - o) i with its o and i; (b - O) rounds at or
 * below every lane's b - o when O is the extreme o on that side (rounding is monotonic),
 * and the product with either extreme reciprocal bounds the product with any between. */
static PACKET_TARGET void pk_frustum_make(pk_frustum *f, const pk_packet *p, unsigned lanes)
{
    for (int k = 0; k < 3; k++) {
        bool up = p->near[k] < p->far[k]; /* the direction is positive on axis k */
        f->o_near[k] = pk_extreme(p->o_near[k][0], lanes, up);
        f->o_far[k] = pk_extreme(p->o_far[k][0], lanes, !up);
        f->near_lo[k] = pk_extreme(p->inv_near[k][0], lanes, false);
        f->near_hi[k] = pk_extreme(p->inv_near[k][0], lanes, true);
        f->far_lo[k] = pk_extreme(p->inv_far[k][0], lanes, false);
        f->far_hi[k] = pk_extreme(p->inv_far[k][0], lanes, true);
    }
    f->t_min = pk_extreme(p->t_min_f[0], lanes, false);
}

/* Whether the n rays share their origin (a camera's rays): their frustum is narrow. */
static bool pk_one_origin(const rt_ray_setup *const *rs, uint32_t n)
{
    rt_vec3 o = rs[0]->ray.origin;
    for (uint32_t i = 1; i < n; i++) {
        rt_vec3 q = rs[i]->ray.origin;
        if (q.x != o.x || q.y != o.y || q.z != o.z) return false;
    }
    return true;
}

/* The node's children that some lane may enter before `far` (the largest of the lanes'
 * best): a superset of every lane's own hits. Their entry distances, bounded from below
 * for every lane, go to *near. */
__attribute__((always_inline)) static inline PACKET_TARGET unsigned pk_frustum_test(const pk_frustum *f,
                                                                                    const pk_packet *p,
                                                                                    const rt_bvh_node *node, pk_f far,
                                                                                    pk_f *near)
{
    const char *b = (const char *)node->box;
    pk_f t = f->t_min;
    for (int k = 0; k < 3; k++) {
        pk_f a = *(const pk_row *)(b + p->near[k]) - f->o_near[k];
        pk_f z = *(const pk_row *)(b + p->far[k]) - f->o_far[k];
        t = PK_MAXF(t, PK_MINF(a * f->near_lo[k], a * f->near_hi[k]));
        far = PK_MINF(far, PK_MAXF(z * f->far_lo[k], z * f->far_hi[k]));
    }
    *near = t;
    return PK_MASKF(t <= far);
}

/* The frustum of rays that end where they share a point (a point light's shadow rays,
 * each from its own hit point): its apex a box around their far ends o + t_max d, the
 * directions reversed, distances s = t_max - t measured from the apex. Bounds every
 * lane's exact double test (docs/box-tests.md, "Shadow rays' frustum"). */
typedef struct {
    pk_f o_near[3], o_far[3], inv_lo[3], inv_hi[3];
} pk_end_frustum;

/* Rays whose ends lie within this fraction of the longest segment share one end. */
#define PK_END_SPREAD 0x1p-10

/* Makes the frustum of the rays in `lanes` (not 0) from their far ends, and in *reach the
 * longest segment rounded up; false when they do not share an end, or when its distances
 * could leave the float range. */
static PACKET_TARGET bool pk_end_frustum_make(pk_end_frustum *f, const pk_packet *p, const rt_ray_setup *const *rs,
                                              unsigned lanes, rt_real extent, pk_f *reach_f)
{
    const double inf = __builtin_inf();
    double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf}, reach = 0, inv = 0;
    for (unsigned m = lanes; m; m &= m - 1) {
        const rt_ray_setup *q = rs[__builtin_ctz(m)];
        const rt_ray *r = &q->ray;
        const double o[3] = {r->origin.x, r->origin.y, r->origin.z};
        const double d[3] = {r->direction.x, r->direction.y, r->direction.z};
        for (int k = 0; k < 3; k++) {
            /* The far end, padded beyond its own rounding and the double test's (2^-50.4). */
            double td = r->t_max * d[k], end = o[k] + td, pad = (rt_magnitude(o[k]) + rt_magnitude(td)) * 0x1p-48;
            lo[k] = rt_min(lo[k], end - pad);
            hi[k] = rt_max(hi[k], end + pad);
            inv = rt_max(inv, rt_magnitude(rt_v3_get(q->inv_direction, k)));
        }
        reach = rt_max(reach, r->t_max - r->t_min);
    }
    double spread = 0, apex = 0;
    for (int k = 0; k < 3; k++) {
        spread = rt_max(spread, hi[k] - lo[k]);
        apex = rt_max(apex, rt_max(rt_magnitude(lo[k]), rt_magnitude(hi[k])));
    }
    /* (A ray without an end, t_max = RT_REAL_MAX, fails the first test or its NaNs the others.) */
    if (!(reach <= 0x1p100 && spread <= reach * PK_END_SPREAD && (extent + apex) * inv <= 0x1p119)) return false;
    *reach_f = PK_ALLF(float_outward(reach, true));
    for (int k = 0; k < 3; k++) {
        /* Reversed, a positive direction is negative: the near distance (p - a) r is least
         * at the apex's lowest a, the far one largest at its highest. */
        bool up = p->near[k] < p->far[k];
        float a_lo = float_outward(lo[k], false), a_hi = float_outward(hi[k], true);
        f->o_near[k] = PK_ALLF(up ? a_lo : a_hi);
        f->o_far[k] = PK_ALLF(up ? a_hi : a_lo);
        /* The lanes' float reciprocals bracket 1 / d; negated, and widened by 2^-20 beyond
         * the test's roundings. */
        pk_f r0 = -p->inv_near[k][0], r1 = -p->inv_far[k][0];
        pk_f r_lo = pk_extreme(PK_MINF(r0, r1), lanes, false), r_hi = pk_extreme(PK_MAXF(r0, r1), lanes, true);
        f->inv_lo[k] = r_lo * PK_ALLF(up ? 1.0f + 0x1p-20f : 1.0f - 0x1p-20f);
        f->inv_hi[k] = r_hi * PK_ALLF(up ? 1.0f - 0x1p-20f : 1.0f + 0x1p-20f);
    }
    return true;
}

/* The node's children that some lane's segment may cross (reach: from make): a superset
 * of every lane's own hits. Their exit distances from the apex (bounded from above) go to
 * *exit. A reversed direction's near planes are the forward far ones. */
__attribute__((always_inline)) static inline PACKET_TARGET unsigned pk_end_frustum_test(const pk_end_frustum *f,
                                                                                        const pk_packet *p,
                                                                                        const rt_bvh_node *node,
                                                                                        pk_f reach, pk_f *exit)
{
    const char *b = (const char *)node->box;
    pk_f t = PK_ALLF(0.0f), far = reach;
    for (int k = 0; k < 3; k++) {
        pk_f a = *(const pk_row *)(b + p->far[k]) - f->o_near[k];
        pk_f z = *(const pk_row *)(b + p->near[k]) - f->o_far[k];
        t = PK_MAXF(t, PK_MINF(a * f->inv_lo[k], a * f->inv_hi[k]));
        far = PK_MINF(far, PK_MAXF(z * f->inv_lo[k], z * f->inv_hi[k]));
    }
    *exit = far;
    /* 2^-100 of slack for the products that underflow (their error is absolute). */
    return PK_MASKF(t <= far + PK_ALLF(0x1p-100f));
}
#else
#define PK_FRUSTUM 0
#endif

/* Asks for an inner node's cache lines ahead of its visit: a pushed child waits on the
 * stack while its nearer siblings are walked. */
__attribute__((always_inline)) static inline void pk_prefetch_node(const rt_bvh_node *node)
{
#pragma GCC unroll 8
    for (size_t at = 0; at < sizeof *node; at += 64) __builtin_prefetch((const char *)node + at);
}

/* Each wide level pushes at most RT_BVH_WIDTH - 1 children. */
#define PK_STACK (RT_BVH_MAX_DEPTH * (RT_BVH_WIDTH - 1) + 1)

/* rt_scene_nearest (any: rt_scene_any) for each of the n <= RT_PACKET rays rs[i] (one
 * octant and permutation) into out[i] and found[i] (false on entry), for the rays the
 * float bounds can take; returns those. */
PACKET_TARGET unsigned PACKET_WALK(const rt_scene *scene, const rt_ray_setup *const *rs, uint32_t n, bool any,
                                   rt_scene_hit *out, bool *found)
{
    pk_packet p;
    unsigned alive = pk_fill(&p, rs, n, scene->bvh.extent), taken = alive;
    const rt_bvh_node *nodes = scene->bvh.nodes;
    pk_entry stack[PK_STACK];
    uint32_t top = 0, child = 0, count = 0, mask = alive;
    if (!alive) return 0;
#if PK_FRUSTUM
    pk_frustum f;             /* of rays from one origin (a tile's camera rays) */
    pk_end_frustum g;         /* of rays to one end (a point light's shadow rays) */
    pk_f far = PK_ALLF(0.0f); /* where the frustum ends: the lanes' largest best, or reach */
    bool frustum = pk_one_origin(rs, n), to_end = false;
    if (frustum) {
        pk_frustum_make(&f, &p, alive);
        far = pk_extreme(p.best[0], alive, true);
    } else if (any) {
        to_end = pk_end_frustum_make(&g, &p, rs, alive, scene->bvh.extent, &far);
    }
#endif
    for (;;) {
        while (count == 0) {
            const rt_bvh_node *node = &nodes[child];
            pk_f t[RT_BVH_WIDTH][PACKET_NF];
            unsigned hits[RT_BVH_WIDTH];
            int order[RT_BVH_WIDTH], n_hit = 0; /* the hit children, nearest first */
            float first[RT_BVH_WIDTH];
#if PK_FRUSTUM
            if (frustum) {
                pk_f near;
                /* An unused slot's box is empty: no test enters it (docs/box-tests.md). */
                for (unsigned in = pk_frustum_test(&f, &p, node, far, &near); in; in &= in - 1) {
                    int c = __builtin_ctz(in);
                    if (node->count[c] > 0) { /* a leaf: its lanes, each by its own test */
                        hits[c] = pk_child(&p, node, c, t[c]) & mask;
                        if (!hits[c]) continue;
                    } else {
                        hits[c] = mask;
                        t[c][0] = PK_ALLF(near[c]);
                    }
                    first[c] = near[c];
                    order[n_hit++] = c;
                }
            } else if (to_end) {
                pk_f exit;
                /* Each child the frustum lets through gets its lanes' own test; the one
                 * that leaves the frustum last, nearest the rays' origins, goes first. */
                for (unsigned in = pk_end_frustum_test(&g, &p, node, far, &exit); in; in &= in - 1) {
                    int c = __builtin_ctz(in);
                    hits[c] = pk_child(&p, node, c, t[c]) & mask;
                    if (!hits[c]) continue;
                    first[c] = -exit[c];
                    order[n_hit++] = c;
                }
            } else
#endif
            {
                /* Slots are filled from 0: the first unused one ends the node. */
                for (int c = 0; c < RT_BVH_WIDTH && node->count[c] != RT_BVH_NO_CHILD; c++) {
                    hits[c] = pk_child(&p, node, c, t[c]) & mask;
                    if (hits[c]) order[n_hit++] = c;
                }
                if (n_hit > 1)
                    for (int i = 0; i < n_hit; i++) first[order[i]] = pk_first(t[order[i]]);
            }
            if (!n_hit) goto pop;
            if (n_hit > 1) {
                for (int i = 1; i < n_hit; i++) {
                    int c = order[i], j = i;
                    for (; j > 0 && first[order[j - 1]] > first[c]; j--) order[j] = order[j - 1];
                    order[j] = c;
                }
            }
            for (int i = n_hit - 1; i > 0; i--) {
                pk_entry *e = &stack[top++];
                int c = order[i];
                e->child = node->child[c], e->count = node->count[c], e->mask = hits[c];
                for (int v = 0; v < PACKET_NF; v++) e->t[v] = t[c][v];
                if (e->count == 0) pk_prefetch_node(&nodes[e->child]);
            }
            child = node->child[order[0]], count = node->count[order[0]], mask = hits[order[0]];
        }
        {
            unsigned improved = pk_leaf(scene, &p, rs, child, count, mask, any, out, found);
            if (any) {
                alive &= ~improved;
                if (!alive) return taken;
            } else {
                for (unsigned m = improved; m; m &= m - 1) {
                    int l = __builtin_ctz(m);
                    p.best[l / PACKET_LANES_F][l % PACKET_LANES_F] = float_outward(out[l].hit.t, true);
                }
#if PK_FRUSTUM
                if (frustum && improved) far = pk_extreme(p.best[0], alive, true);
#endif
            }
        }
    pop:
        for (;;) {
            if (top == 0) return taken;
            pk_entry *e = &stack[--top];
            unsigned live = 0;
            for (int v = 0; v < PACKET_NF; v++) live |= PK_MASKF(e->t[v] <= p.best[v]) << (v * PACKET_LANES_F);
            mask = e->mask & live & alive;
            if (!mask) continue;
            child = e->child, count = e->count;
            break;
        }
    }
}

/* A BVH leaf visited by one ray: the exact test of each of its references, keeping the
 * nearest hit with the tie rule of bvh.h. In the double build the triangles are tested
 * two at a time (vector_size(16) doubles: SSE2, NEON; four at a time in the avx2
 * kernel's any-hit queries) with exactly the scalar test's operations, a triangle per
 * lane (bvh_leaf_lanes.h), and the lanes give their crossings' t and barycentrics.
 * Included by scene_query.c and each kernel's walks (bvh_kernel_*.c), which may compile
 * visit_leaf for their instruction set (LEAF_TARGET). */
#ifndef RT_BVH_LEAF_H
#define RT_BVH_LEAF_H

#include "bvh.h"
#include "scene_query.h"

#ifndef LEAF_TARGET
#define LEAF_TARGET
#endif

/* Where a quadric's test starts on the ray, as a ray parameter: 0, or in the fixed build,
 * for an origin more than 256 from the quadric's centre on some axis, the point of the ray
 * nearest the centre. The inverse transform's entries are rounded to 2^-33, so an
 * object-space origin's error grows with its distance; far out it exceeded the BVH's
 * padding (finding 16 in docs/robustness.md). From the nearest point it stays within the
 * object's size. The double build's entries are off by 2^-53 of themselves: an origin
 * would have to be some 2^30 object sizes away. */
static rt_real quadric_start(const rt_object *obj, const rt_ray *ray)
{
#ifdef RT_REAL_FIXED
    rt_vec3 to_centre = rt_v3_sub(obj->to_world.translation, ray->origin);
    const rt_real near = RT_C(256.0);
    if (rt_abs(to_centre.x) <= near && rt_abs(to_centre.y) <= near && rt_abs(to_centre.z) <= near) return RT_ZERO;
    rt_real dd = rt_v3_dot(ray->direction, ray->direction);
    if (!(dd > RT_ZERO)) return RT_ZERO;
    rt_real start = rt_div(rt_v3_dot(to_centre, ray->direction), dd);
    return rt_is_finite(start) ? start : RT_ZERO;
#else
    (void)obj;
    (void)ray;
    return RT_ZERO;
#endif
}

static bool quadric_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit)
{
    const rt_object *obj = &scene->objects[scene->quadric_objects[prim - scene->triangle_count]];
    rt_vec3 o = rt_object_point(obj, rs->ray.origin);
    rt_vec3 d = rt_object_vector(obj, rs->ray.direction);
    bool sphere = obj->kind == RT_SHAPE_SPHERE;
    if (rt_line_clears_ball(o, d, sphere ? RT_C(0.25) : RT_C(0.5))) return false;
    rt_real start = quadric_start(obj, &rs->ray), t_min = rs->ray.t_min, t_max = rs->ray.t_max;
    if (start != RT_ZERO) {
        o = rt_object_point(obj, rt_v3_madd(rs->ray.origin, rs->ray.direction, start));
        t_min = rt_sub(t_min, start);
        t_max = rt_sub(t_max, start);
    }
    /* Solve with a unit object-space direction and scale t back: the short direction of a
     * scaled-up object would leave Q32.32 only a few bits in d.d. */
    rt_real len = rt_v3_length(d);
    if (!(len > RT_ZERO)) return false;
    rt_vec3 unit = rt_v3_scale(d, rt_div(RT_ONE, len));
    t_min = rt_mul(t_min, len);
    t_max = rt_mul(t_max, len);
    bool found =
        sphere ? rt_intersect_sphere(o, unit, t_min, t_max, hit) : rt_intersect_cylinder(o, unit, t_min, t_max, hit);
    if (!found) return false;
    hit->t = rt_div(hit->t, len);
    if (start != RT_ZERO) hit->t = rt_add(start, hit->t);
    return hit->t > rs->ray.t_min && hit->t < rs->ray.t_max;
}

/* Triangle prim's crossing by the ray, up to t (rt_triangle_cross); kx, ky, kz are rs's
 * axis permutation, `bounded` whether rt_triangle_unsaturated holds. */
__attribute__((always_inline)) static inline bool triangle_cross(const rt_scene *scene, uint32_t prim,
                                                                 const rt_ray_setup *rs, rt_triangle_crossing *x,
                                                                 int kx, int ky, int kz, bool bounded)
{
    const rt_triangle *tri = &scene->triangles[prim];
    return rt_triangle_cross(rs, scene->positions[tri->v[0]], scene->positions[tri->v[1]], scene->positions[tri->v[2]],
                             x, kx, ky, kz, bounded);
}

/* Inline in the BVH's leaf loop, where a triangle test is most of the work; kx, ky, kz
 * are rs's axis permutation (see rt_triangle_cross). */
__attribute__((always_inline)) static inline bool prim_intersect(const rt_scene *scene, uint32_t prim,
                                                                 const rt_ray_setup *rs, rt_prim_hit *hit, int kx,
                                                                 int ky, int kz)
{
    if (prim >= scene->triangle_count) return quadric_intersect(scene, prim, rs, hit);
    rt_triangle_crossing x;
    if (!triangle_cross(scene, prim, rs, &x, kx, ky, kz, false)) return false;
    rt_triangle_hit(&x, hit);
    return true;
}

/* Whether a hit at t on prim loses to *best: farther, or as near and a higher reference. */
static inline bool loses_to(const rt_scene_hit *best, bool found, rt_real t, uint32_t prim)
{
    return found && (t > best->hit.t || (t == best->hit.t && prim > best->prim));
}

/* Keeps triangle prim's crossing x in *best if it is nearer, or as near and a lower
 * reference; returns whether it did. Its barycentrics are computed only for a hit it keeps. */
__attribute__((always_inline)) static inline bool keep_crossing(uint32_t prim, rt_triangle_crossing x,
                                                                rt_scene_hit *best, bool *found)
{
    if (loses_to(best, *found, x.t, prim)) return false;
    rt_triangle_hit(&x, &best->hit);
    best->prim = prim;
    *found = true;
    return true;
}

/* Keeps prim's hit in *best by the same rule; returns whether it did. `bounded`: as for
 * triangle_cross. */
__attribute__((always_inline)) static inline bool consider(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs,
                                                           rt_scene_hit *best, bool *found, int kx, int ky, int kz,
                                                           bool bounded)
{
    if (prim < scene->triangle_count) {
        rt_triangle_crossing x;
        return triangle_cross(scene, prim, rs, &x, kx, ky, kz, bounded) && keep_crossing(prim, x, best, found);
    }
    rt_prim_hit h;
    if (!quadric_intersect(scene, prim, rs, &h) || loses_to(best, *found, h.t, prim)) return false;
    best->hit = h;
    best->prim = prim;
    *found = true;
    return true;
}

#if !defined(RT_REAL_FIXED) && defined(__GNUC__)
#define EDGE_PAIRS 1
typedef double pair_d __attribute__((vector_size(16)));
typedef double pair_d_load __attribute__((vector_size(16), aligned(8), may_alias));
typedef int64_t pair_i __attribute__((vector_size(16)));
#ifdef __clang__
#define PAIR_SHUFFLE(a, b, i, j) __builtin_shufflevector(a, b, i, j)
#else
#define PAIR_SHUFFLE(a, b, i, j) __builtin_shuffle(a, b, (pair_i){i, j})
#endif

/* Vertex v of triangles refs[0], refs[1] relative to the origin o, a coordinate per
 * vector: out[k] holds coordinate k of both. */
__attribute__((always_inline)) static inline LEAF_TARGET void lanes_vertex2(const rt_scene *scene, const uint32_t *refs,
                                                                            int v, rt_vec3 o, pair_d out[3])
{
    const rt_vec3 *p = scene->positions;
    const rt_triangle *t = scene->triangles;
    const rt_vec3 *a = &p[t[refs[0]].v[v]], *b = &p[t[refs[1]].v[v]];
    pair_d xy_a = *(const pair_d_load *)&a->x, xy_b = *(const pair_d_load *)&b->x;
    out[0] = PAIR_SHUFFLE(xy_a, xy_b, 0, 2) - o.x;
    out[1] = PAIR_SHUFFLE(xy_a, xy_b, 1, 3) - o.y;
    out[2] = (pair_d){a->z, b->z} - o.z;
}

/* A mask vector's lanes (all ones or all zeros) as bits. */
__attribute__((always_inline)) static inline LEAF_TARGET unsigned lanes_bits2(pair_i m)
{
#ifdef __SSE2__
    return (unsigned)__builtin_ia32_movmskpd((pair_d)m); /* the sign bits, in one instruction */
#else
    return (unsigned)(m[0] != 0) | (unsigned)(m[1] != 0) << 1;
#endif
}

#define LANES 2
#include "bvh_leaf_lanes.h"
#undef LANES

#ifdef LEAF_QUADS
/* The same for four triangles in 256-bit vectors (the avx2 kernel's any-hit leaves). */
typedef double quad_d __attribute__((vector_size(32)));
typedef int64_t quad_i __attribute__((vector_size(32)));

/* Vertex v of triangles refs[0 .. 4) relative to the origin o, a coordinate per vector. */
__attribute__((always_inline)) static inline LEAF_TARGET void lanes_vertex4(const rt_scene *scene, const uint32_t *refs,
                                                                            int v, rt_vec3 o, quad_d out[3])
{
    const rt_vec3 *p = scene->positions;
    const rt_triangle *t = scene->triangles;
    const rt_vec3 *a = &p[t[refs[0]].v[v]], *b = &p[t[refs[1]].v[v]], *c = &p[t[refs[2]].v[v]];
    const rt_vec3 *d = &p[t[refs[3]].v[v]];
    pair_d xy_a = *(const pair_d_load *)&a->x, xy_b = *(const pair_d_load *)&b->x;
    pair_d xy_c = *(const pair_d_load *)&c->x, xy_d = *(const pair_d_load *)&d->x;
    quad_d ac = __builtin_shufflevector(xy_a, xy_c, 0, 1, 2, 3), bd = __builtin_shufflevector(xy_b, xy_d, 0, 1, 2, 3);
    out[0] = __builtin_shufflevector(ac, bd, 0, 4, 2, 6) - o.x;
    out[1] = __builtin_shufflevector(ac, bd, 1, 5, 3, 7) - o.y;
    out[2] = (quad_d){a->z, b->z, c->z, d->z} - o.z;
}

__attribute__((always_inline)) static inline LEAF_TARGET unsigned lanes_bits4(quad_i m)
{
    return (unsigned)__builtin_ia32_movmskpd256((quad_d)m);
}

#define LANES 4
#include "bvh_leaf_lanes.h"
#undef LANES
#endif
#else
#define EDGE_PAIRS 0
#endif

__attribute__((always_inline)) static inline LEAF_TARGET bool leaf_loop(const rt_scene *scene, uint32_t first,
                                                                        uint32_t count, const rt_ray_setup *rs,
                                                                        bool any, rt_scene_hit *best, bool *found,
                                                                        int kx, int ky, int kz, bool bounded)
{
    const uint32_t *refs = scene->bvh.prim_refs;
    uint32_t i = first, end = first + count;
#if EDGE_PAIRS && defined(LEAF_QUADS)
    /* Any-hit queries take four triangles at a time: faster for shadow rays, where most
     * triangles are rejected, but not for camera rays (docs/performance.md). */
    for (; any && i < end; i += 4) {
        /* Lanes past the leaf's end take the next leaf's references (or the zeros past the
         * last one, RT_BVH_REF_PAD) and are masked out. */
        uint32_t q[4] = {refs[i], refs[i + 1], refs[i + 2], refs[i + 3]}, n = end - i < 4 ? end - i : 4;
        unsigned in_leaf = (1u << n) - 1, tc = scene->triangle_count;
        if ((q[0] < tc) & (q[1] < tc) & (q[2] < tc) & (q[3] < tc)) {
            lanes_crossings4 x;
            unsigned crossed = lanes_cross4(scene, q, rs, kx, ky, kz, &x) & in_leaf;
            if (!crossed) continue;
            keep_crossing(q[__builtin_ctz(crossed)], lane_crossing4(&x, __builtin_ctz(crossed)), best, found);
            return true;
        }
        for (; in_leaf; in_leaf &= in_leaf - 1) { /* spheres and cylinders take their own test */
            consider(scene, q[__builtin_ctz(in_leaf)], rs, best, found, kx, ky, kz, bounded);
            if (*found) return true;
        }
    }
#endif
#if EDGE_PAIRS
    for (; i + 2 <= end; i += 2) {
        if (refs[i] < scene->triangle_count && refs[i + 1] < scene->triangle_count) {
            lanes_crossings2 x;
            for (unsigned crossed = lanes_cross2(scene, refs + i, rs, kx, ky, kz, &x); crossed;
                 crossed &= crossed - 1) {
                keep_crossing(refs[i + __builtin_ctz(crossed)], lane_crossing2(&x, __builtin_ctz(crossed)), best,
                              found);
                if (any) return true;
            }
            continue;
        }
        consider(scene, refs[i], rs, best, found, kx, ky, kz, bounded); /* spheres and cylinders take their own test */
        if (any && *found) return true;
        consider(scene, refs[i + 1], rs, best, found, kx, ky, kz, bounded);
        if (any && *found) return true;
    }
#endif
    for (; i < end; i++) {
        consider(scene, refs[i], rs, best, found, kx, ky, kz, bounded);
        if (any && *found) break;
    }
    return *found;
}

/* leaf_loop with one copy per axis permutation. */
__attribute__((always_inline)) static inline LEAF_TARGET bool leaf_permuted(const rt_scene *scene, uint32_t first,
                                                                            uint32_t count, const rt_ray_setup *rs,
                                                                            bool any, rt_scene_hit *best, bool *found,
                                                                            bool bounded)
{
    switch (rs->order) {
    case 0: return leaf_loop(scene, first, count, rs, any, best, found, 1, 2, 0, bounded);
    case 1: return leaf_loop(scene, first, count, rs, any, best, found, 2, 1, 0, bounded);
    case 2: return leaf_loop(scene, first, count, rs, any, best, found, 2, 0, 1, bounded);
    case 3: return leaf_loop(scene, first, count, rs, any, best, found, 0, 2, 1, bounded);
    case 4: return leaf_loop(scene, first, count, rs, any, best, found, 0, 1, 2, bounded);
    default: return leaf_loop(scene, first, count, rs, any, best, found, 1, 0, 2, bounded);
    }
}

/* The references prim_refs[first .. first + count), out of line so that the traversal
 * loop keeps its registers; with `any`, stops at the first hit. Returns *found. The fixed
 * build has a second copy without saturation tests for the rays and scenes that cannot
 * reach the rails (rt_triangle_unsaturated: every scene within RT_TRIANGLE_RANGE). */
__attribute__((noinline, unused)) static LEAF_TARGET bool visit_leaf(const rt_scene *scene, uint32_t first,
                                                                     uint32_t count, const rt_ray_setup *rs, bool any,
                                                                     rt_scene_hit *best, bool *found)
{
#ifdef RT_REAL_FIXED
    if (rt_triangle_unsaturated(rs, scene->bvh.extent))
        return leaf_permuted(scene, first, count, rs, any, best, found, true);
#endif
    return leaf_permuted(scene, first, count, rs, any, best, found, false);
}

#endif

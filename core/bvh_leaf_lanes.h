/* The watertight test of several triangles at once, a triangle per lane of a vector of
 * doubles, by exactly rt_triangle_cross's operations: so a lane crosses exactly when that
 * test does, with the same t, v, w and det. Included by bvh_leaf.h once per width, with
 * LANES 2 (pairs: SSE2, NEON) and, in the avx2 kernel, LANES 4 (quads); each width
 * provides, before the include, lanes_vertexN (vertex v of the triangles refs[0 .. N),
 * a coordinate per vector, relative to the origin) and lanes_bitsN (a mask vector's lanes
 * as bits). */
#define LANES_PASTE_(name, n) name##n
#define LANES_PASTE(name, n) LANES_PASTE_(name, n)
#define LN(name) LANES_PASTE(name, LANES)

typedef double LN(lanes_d) __attribute__((vector_size(LANES * 8)));
typedef int64_t LN(lanes_i) __attribute__((vector_size(LANES * 8)));

/* Each lane's crossing, as rt_triangle_crossing's fields. */
typedef struct {
    LN(lanes_d) t, v, w, det;
} LN(lanes_crossings);

__attribute__((always_inline)) static inline LEAF_TARGET LN(lanes_d) LN(lanes_magnitude)(LN(lanes_d) a)
{
    return (LN(lanes_d))((LN(lanes_i))a & INT64_MAX); /* the sign bit cleared */
}

/* Which of the triangles refs[0 .. LANES) the ray crosses (bit l: lane l), with each
 * lane's crossing in *x. Returns 0 early when every triangle has edge functions of both
 * signs, most of a leaf's tests. */
__attribute__((always_inline)) static inline LEAF_TARGET unsigned LN(lanes_cross)(const rt_scene *scene,
                                                                                  const uint32_t *refs,
                                                                                  const rt_ray_setup *rs, int kx,
                                                                                  int ky, int kz,
                                                                                  LN(lanes_crossings) * x)
{
    LN(lanes_d) pa[3], pb[3], pc[3];
    LN(lanes_vertex)(scene, refs, 0, rs->ray.origin, pa);
    LN(lanes_vertex)(scene, refs, 1, rs->ray.origin, pb);
    LN(lanes_vertex)(scene, refs, 2, rs->ray.origin, pc);
    LN(lanes_d) ax = pa[kx] - rs->sx * pa[kz], ay = pa[ky] - rs->sy * pa[kz];
    LN(lanes_d) bx = pb[kx] - rs->sx * pb[kz], by = pb[ky] - rs->sy * pb[kz];
    LN(lanes_d) cx = pc[kx] - rs->sx * pc[kz], cy = pc[ky] - rs->sy * pc[kz];
    LN(lanes_d) u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax, zero = {0.0};
    LN(lanes_i) outside = ((u < zero) | (v < zero) | (w < zero)) & ((u > zero) | (v > zero) | (w > zero));
    if (LN(lanes_bits)(outside) == (1u << LANES) - 1) return 0;
    LN(lanes_d) det = (u + v) + w;
    LN(lanes_d) extent_x = (LN(lanes_magnitude)(ax) + LN(lanes_magnitude)(bx)) + LN(lanes_magnitude)(cx);
    LN(lanes_d) extent_y = (LN(lanes_magnitude)(ay) + LN(lanes_magnitude)(by)) + LN(lanes_magnitude)(cy);
    LN(lanes_i) edge_on = LN(lanes_magnitude)(det) <= (extent_x * extent_y) * 1e-12;
    LN(lanes_d) t = ((u * (rs->sz * pa[kz]) + v * (rs->sz * pb[kz])) + w * (rs->sz * pc[kz])) / det;
    LN(lanes_i) inside = (t > rs->ray.t_min) & (t < rs->ray.t_max) & (t - t == zero);
    *x = (LN(lanes_crossings)){t, v, w, det};
    return LN(lanes_bits)(inside & ~edge_on & ~outside);
}

/* Lane l's crossing. */
__attribute__((always_inline)) static inline LEAF_TARGET rt_triangle_crossing
LN(lane_crossing)(const LN(lanes_crossings) * x, int l)
{
    return (rt_triangle_crossing){x->t[l], x->v[l], x->w[l], x->det[l]};
}

#undef LN
#undef LANES_PASTE
#undef LANES_PASTE_

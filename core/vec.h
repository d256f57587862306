/* Small vectors and affine matrices over rt_real. Header-only so the compiler can
 * inline the hot paths; every operation is written out in a fixed order so that
 * results do not depend on how the compiler schedules it. */
#ifndef RT_VEC_H
#define RT_VEC_H

#include "real.h"

typedef struct {
    rt_real x, y, z;
} rt_vec3;
typedef struct {
    rt_real u, v;
} rt_vec2;
/* Row-major 3x3 matrix. */
typedef struct {
    rt_real m[3][3];
} rt_mat3;
/* Affine transform p' = linear * p + translation (the bottom row is always 0 0 0 1). */
typedef struct {
    rt_mat3 linear;
    rt_vec3 translation;
} rt_affine;

static inline rt_vec3 rt_v3(rt_real x, rt_real y, rt_real z)
{
    rt_vec3 r = {x, y, z};
    return r;
}
static inline rt_vec3 rt_v3_add(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_add(a.x, b.x), rt_add(a.y, b.y), rt_add(a.z, b.z));
}
static inline rt_vec3 rt_v3_sub(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_sub(a.x, b.x), rt_sub(a.y, b.y), rt_sub(a.z, b.z));
}
static inline rt_vec3 rt_v3_mul(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_mul(a.x, b.x), rt_mul(a.y, b.y), rt_mul(a.z, b.z));
}
static inline rt_vec3 rt_v3_scale(rt_vec3 a, rt_real s)
{
    return rt_v3(rt_mul(a.x, s), rt_mul(a.y, s), rt_mul(a.z, s));
}
static inline rt_vec3 rt_v3_neg(rt_vec3 a) { return rt_v3(rt_neg(a.x), rt_neg(a.y), rt_neg(a.z)); }
/* a + b * s, the common "point along a ray" step. */
static inline rt_vec3 rt_v3_madd(rt_vec3 a, rt_vec3 b, rt_real s) { return rt_v3_add(a, rt_v3_scale(b, s)); }
static inline rt_real rt_v3_dot(rt_vec3 a, rt_vec3 b)
{
    return rt_add(rt_add(rt_mul(a.x, b.x), rt_mul(a.y, b.y)), rt_mul(a.z, b.z));
}
static inline rt_vec3 rt_v3_cross(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_sub(rt_mul(a.y, b.z), rt_mul(a.z, b.y)), rt_sub(rt_mul(a.z, b.x), rt_mul(a.x, b.z)),
                 rt_sub(rt_mul(a.x, b.y), rt_mul(a.y, b.x)));
}
/* The k for which m 16^k lies in [1/2, top), or 0 for a zero, infinite or NaN m
 * (m - m is 0 for any other value). Scaling by powers of two is exact in double, so
 * results computed on scaled values and scaled back equal the unscaled ones there; in
 * Q32.32 it keeps squares from saturating and small values' significant bits. */
static inline int rt_pow16_exponent(rt_real m, rt_real top)
{
    int k = 0;
    for (; m >= top && rt_sub(m, m) == RT_ZERO; m = rt_over16(m)) k--;
    for (; m > RT_ZERO && m < RT_C(0.5); m = rt_times16(m)) k++;
    return k;
}
/* x 16^k, one factor of 16 (or 1/16) at a time. */
static inline rt_real rt_scale_pow16(rt_real x, int k)
{
    for (; k > 0; k--) x = rt_times16(x);
    for (; k < 0; k++) x = rt_over16(x);
    return x;
}
/* a 16^k with its largest component in [1/2, 8): in Q32.32 its squared length keeps at
 * least 30 significant bits and the reciprocal of its length (above 1/14) at least 28. */
static inline rt_vec3 rt_v3_rescale(rt_vec3 a, int *k)
{
    *k = rt_pow16_exponent(rt_max(rt_max(rt_abs(a.x), rt_abs(a.y)), rt_abs(a.z)), RT_C(8.0));
    return rt_v3(rt_scale_pow16(a.x, *k), rt_scale_pow16(a.y, *k), rt_scale_pow16(a.z, *k));
}
static inline rt_real rt_v3_length(rt_vec3 a)
{
    int k;
    rt_vec3 b = rt_v3_rescale(a, &k);
    return rt_scale_pow16(rt_sqrt(rt_v3_dot(b, b)), -k);
}
/* Unit vector along a; the zero vector stays zero. */
static inline rt_vec3 rt_v3_normalize(rt_vec3 a)
{
    int k;
    rt_vec3 b = rt_v3_rescale(a, &k);
    rt_real len = rt_sqrt(rt_v3_dot(b, b));
    return len > RT_ZERO ? rt_v3_scale(b, rt_div(RT_ONE, len)) : a;
}
static inline rt_real rt_v3_get(rt_vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
static inline rt_vec3 rt_v3_div(rt_vec3 a, rt_real d) { return rt_v3(rt_div(a.x, d), rt_div(a.y, d), rt_div(a.z, d)); }
static inline bool rt_v3_is_finite(rt_vec3 a) { return rt_is_finite(a.x) && rt_is_finite(a.y) && rt_is_finite(a.z); }
static inline bool rt_v3_is_zero(rt_vec3 a) { return a.x == RT_ZERO && a.y == RT_ZERO && a.z == RT_ZERO; }
static inline bool rt_v3_equal(rt_vec3 a, rt_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
static inline rt_vec3 rt_v3_min(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_min(a.x, b.x), rt_min(a.y, b.y), rt_min(a.z, b.z));
}
static inline rt_vec3 rt_v3_max(rt_vec3 a, rt_vec3 b)
{
    return rt_v3(rt_max(a.x, b.x), rt_max(a.y, b.y), rt_max(a.z, b.z));
}

static inline rt_vec3 rt_mat3_apply(const rt_mat3 *m, rt_vec3 v)
{
    return rt_v3(rt_add(rt_add(rt_mul(m->m[0][0], v.x), rt_mul(m->m[0][1], v.y)), rt_mul(m->m[0][2], v.z)),
                 rt_add(rt_add(rt_mul(m->m[1][0], v.x), rt_mul(m->m[1][1], v.y)), rt_mul(m->m[1][2], v.z)),
                 rt_add(rt_add(rt_mul(m->m[2][0], v.x), rt_mul(m->m[2][1], v.y)), rt_mul(m->m[2][2], v.z)));
}
static inline rt_vec3 rt_affine_point(const rt_affine *a, rt_vec3 p)
{
    return rt_v3_add(rt_mat3_apply(&a->linear, p), a->translation);
}
static inline rt_vec3 rt_affine_vector(const rt_affine *a, rt_vec3 v) { return rt_mat3_apply(&a->linear, v); }
static inline bool rt_mat3_is_diagonal(const rt_mat3 *m)
{
    return m->m[0][1] == RT_ZERO && m->m[0][2] == RT_ZERO && m->m[1][0] == RT_ZERO && m->m[1][2] == RT_ZERO &&
           m->m[2][0] == RT_ZERO && m->m[2][1] == RT_ZERO;
}
/* rt_mat3_apply and rt_affine_point of a diagonal matrix from its diagonal alone. In
 * Q32.32 a zero coefficient's product is exactly 0 and adding it changes nothing, so these
 * are the same bits; in double they are not (-0 + +0, infinity times 0), so only the fixed
 * build takes them (rt_object_point and its kin). */
static inline rt_vec3 rt_mat3_apply_diagonal(const rt_mat3 *m, rt_vec3 v)
{
    return rt_v3(rt_mul(m->m[0][0], v.x), rt_mul(m->m[1][1], v.y), rt_mul(m->m[2][2], v.z));
}
static inline rt_vec3 rt_affine_point_diagonal(const rt_affine *a, rt_vec3 p)
{
    return rt_v3_add(rt_mat3_apply_diagonal(&a->linear, p), a->translation);
}

rt_mat3 rt_mat3_mul(const rt_mat3 *a, const rt_mat3 *b);
rt_mat3 rt_mat3_transpose(const rt_mat3 *a);
/* Inverse of a; false (and *out untouched) when a is singular or not finite. */
bool rt_mat3_inverse(const rt_mat3 *a, rt_mat3 *out);
rt_affine rt_affine_identity(void);
rt_affine rt_affine_mul(const rt_affine *a, const rt_affine *b);
/* Inverse of a; false (and *out untouched) when it is singular or not finite. */
bool rt_affine_inverse(const rt_affine *a, rt_affine *out);
/* Every entry finite (no overflow to infinity, no NaN). */
bool rt_affine_is_finite(const rt_affine *a);
/* The format's node transform: T(translation) * Rx * Ry * Rz * S(scale), angles in degrees. */
rt_affine rt_affine_trs(rt_vec3 translation, rt_vec3 rotation_degrees, rt_vec3 scale);

#endif

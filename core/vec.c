/* Matrix operations that are too large to inline. */
#include "vec.h"

rt_mat3 rt_mat3_mul(const rt_mat3 *a, const rt_mat3 *b)
{
    rt_mat3 r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.m[i][j] = rt_add(rt_add(rt_mul(a->m[i][0], b->m[0][j]), rt_mul(a->m[i][1], b->m[1][j])),
                               rt_mul(a->m[i][2], b->m[2][j]));
    return r;
}

rt_mat3 rt_mat3_transpose(const rt_mat3 *a)
{
    rt_mat3 r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r.m[i][j] = a->m[j][i];
    return r;
}

static rt_real cofactor(const rt_mat3 *a, int r0, int r1, int c0, int c1)
{
    return rt_sub(rt_mul(a->m[r0][c0], a->m[r1][c1]), rt_mul(a->m[r0][c1], a->m[r1][c0]));
}

/* Each column j is scaled by 16^k[j] into [1/2, 8) first, and row j of the inverse scaled
 * back by the same factor (A = B D^-1, so A^-1 = D B^-1). In Q32.32 a large scale would
 * otherwise leave 1 / det only a few significant bits (1 / 939^3 is about five lsb), and a
 * small or uneven one would lose det itself; in double the scaling is exact, so the
 * result is the unscaled formula's to the bit. */
bool rt_mat3_inverse(const rt_mat3 *a, rt_mat3 *out)
{
    int k[3];
    rt_mat3 b;
    for (int j = 0; j < 3; j++) {
        rt_real m = rt_max(rt_max(rt_abs(a->m[0][j]), rt_abs(a->m[1][j])), rt_abs(a->m[2][j]));
        k[j] = rt_pow16_exponent(m, RT_C(8.0));
        for (int i = 0; i < 3; i++) b.m[i][j] = rt_scale_pow16(a->m[i][j], k[j]);
    }
    /* Adjugate over determinant; cofactor(i, j) uses the rows and columns other than i and j. */
    rt_mat3 adj;
    adj.m[0][0] = cofactor(&b, 1, 2, 1, 2);
    adj.m[0][1] = rt_neg(cofactor(&b, 0, 2, 1, 2));
    adj.m[0][2] = cofactor(&b, 0, 1, 1, 2);
    adj.m[1][0] = rt_neg(cofactor(&b, 1, 2, 0, 2));
    adj.m[1][1] = cofactor(&b, 0, 2, 0, 2);
    adj.m[1][2] = rt_neg(cofactor(&b, 0, 1, 0, 2));
    adj.m[2][0] = cofactor(&b, 1, 2, 0, 1);
    adj.m[2][1] = rt_neg(cofactor(&b, 0, 2, 0, 1));
    adj.m[2][2] = cofactor(&b, 0, 1, 0, 1);
    rt_real det =
        rt_add(rt_add(rt_mul(b.m[0][0], adj.m[0][0]), rt_mul(b.m[0][1], adj.m[1][0])), rt_mul(b.m[0][2], adj.m[2][0]));
    if (det == RT_ZERO || !rt_is_finite(det)) return false;
    /* det is scaled into [1/2, 8) too: in Q32.32 the reciprocal of det = 1327 (scales near
     * 0.65 under rotation) would keep 22 significant bits, of det 16^kd at least 29. */
    int kd = rt_pow16_exponent(rt_abs(det), RT_C(8.0));
    rt_real inv_det = rt_div(RT_ONE, rt_scale_pow16(det, kd));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            rt_real v = rt_scale_pow16(rt_mul(adj.m[i][j], inv_det), k[i] + kd);
            if (!rt_is_finite(v)) return false;
            out->m[i][j] = v;
        }
    return true;
}

rt_affine rt_affine_identity(void)
{
    rt_affine r = {{{{RT_ONE, RT_ZERO, RT_ZERO}, {RT_ZERO, RT_ONE, RT_ZERO}, {RT_ZERO, RT_ZERO, RT_ONE}}},
                   {RT_ZERO, RT_ZERO, RT_ZERO}};
    return r;
}

rt_affine rt_affine_mul(const rt_affine *a, const rt_affine *b)
{
    rt_affine r;
    r.linear = rt_mat3_mul(&a->linear, &b->linear);
    r.translation = rt_affine_point(a, b->translation);
    return r;
}

bool rt_affine_inverse(const rt_affine *a, rt_affine *out)
{
    rt_mat3 inv;
    if (!rt_mat3_inverse(&a->linear, &inv)) return false;
    /* A far translation under a small scale can overflow: 1e308 scaled by 2. */
    rt_vec3 t = rt_v3_neg(rt_mat3_apply(&inv, a->translation));
    if (!rt_is_finite(t.x) || !rt_is_finite(t.y) || !rt_is_finite(t.z)) return false;
    out->linear = inv;
    out->translation = t;
    return true;
}

static rt_mat3 rotation_about(int axis, rt_real degrees)
{
    rt_real rad = rt_mul(degrees, rt_div(RT_PI, rt_from_int(180)));
    rt_real c = rt_cos(rad), s = rt_sin(rad);
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    rt_mat3 r = rt_affine_identity().linear;
    r.m[i][i] = c;
    r.m[i][j] = rt_neg(s);
    r.m[j][i] = s;
    r.m[j][j] = c;
    return r;
}

bool rt_affine_is_finite(const rt_affine *a)
{
    for (int i = 0; i < 3; i++)
        if (!rt_v3_is_finite(rt_v3(a->linear.m[i][0], a->linear.m[i][1], a->linear.m[i][2]))) return false;
    return rt_v3_is_finite(a->translation);
}

rt_affine rt_affine_trs(rt_vec3 translation, rt_vec3 rotation_degrees, rt_vec3 scale)
{
    rt_mat3 rx = rotation_about(0, rotation_degrees.x);
    rt_mat3 ry = rotation_about(1, rotation_degrees.y);
    rt_mat3 rz = rotation_about(2, rotation_degrees.z);
    rt_mat3 rxy = rt_mat3_mul(&rx, &ry);
    rt_mat3 rot = rt_mat3_mul(&rxy, &rz);
    rt_affine r;
    for (int i = 0; i < 3; i++) {
        r.linear.m[i][0] = rt_mul(rot.m[i][0], scale.x);
        r.linear.m[i][1] = rt_mul(rot.m[i][1], scale.y);
        r.linear.m[i][2] = rt_mul(rot.m[i][2], scale.z);
    }
    r.translation = translation;
    return r;
}

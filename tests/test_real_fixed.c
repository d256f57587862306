/* The Q32.32 backend (core/real_fixed.h, core/real_fixed.c): arithmetic exactly against
 * 128-bit references, elementary functions against long double libm on deterministic
 * samples. Compiled only in the fixed build (make RT_REAL=fixed). */
#ifdef RT_REAL_FIXED

#include <criterion/criterion.h>
#include <math.h>

#include "intersect.h"
#include "real.h"
#include "vec.h"

#define LSB 0x1p-32L
/* The bounds documented in core/real_fixed.c, in lsb (2^-32), given the exact result ref. */
#define ROUNDED 0.5L
static long double sin_cos_bound(long double ref)
{
    (void)ref;
    return ROUNDED + 0x1p-26L;
}
static long double tan_bound(long double ref) { return ROUNDED + 0x1p-27L * (1.0L + ref * ref); }
static long double exp_bound(long double ref) { return ROUNDED + 0x1p-26L + fabsl(ref) * 0x1p-59L / LSB; }
static long double log_bound(long double ref)
{
    (void)ref;
    return ROUNDED + 0x1p-26L;
}
static long double pow_bound(long double ref, long double e)
{
    return ROUNDED + 0x1p-26L + fabsl(ref) * (fabsl(e) * 0x1p-57L + 0x1p-59L) / LSB;
}

/* 64-bit LCG (Knuth's MMIX constants): the same samples on every run and platform. */
typedef struct {
    uint64_t s;
} lcg;
static uint64_t lcg_next(lcg *g)
{
    g->s = g->s * 6364136223846793005u + 1442695040888963407u;
    return g->s;
}
/* A raw value uniform in [lo, hi] (given as reals). */
static rt_real lcg_real(lcg *g, long double lo, long double hi)
{
    uint64_t span = (uint64_t)((hi - lo) / LSB);
    return (rt_real)(lo / LSB) + (rt_real)(lcg_next(g) % (span + 1));
}
/* A raw value with a random number of significant bits, so every magnitude appears. */
static rt_real lcg_any(lcg *g)
{
    uint64_t u = lcg_next(g) >> (lcg_next(g) % 64);
    rt_real a = (rt_real)(u >> 1);
    return lcg_next(g) & 1 ? -a : a;
}

static long double real_of(rt_real a) { return (long double)a * LSB; } /* exact with a 64-bit mantissa */
static long double lsb_error(rt_real got, long double ref) { return fabsl((long double)got - ref / LSB); }

typedef struct {
    const char *name;
    rt_real (*f)(rt_real);
    long double (*ref)(long double);
    long double (*bound)(long double);
} unary_case;

/* Max error (over the bound) of c on n samples of gen; fails naming the worst input. */
static void check_unary(unary_case c, lcg g, rt_real (*gen)(lcg *), int n)
{
    long double worst = 0.0L, worst_ratio = 0.0L;
    rt_real worst_x = 0;
    for (int i = 0; i < n; i++) {
        rt_real x = gen(&g);
        long double ref = c.ref(real_of(x));
        long double err = lsb_error(c.f(x), ref), ratio = err / c.bound(ref);
        if (ratio > worst_ratio) {
            worst_ratio = ratio;
            worst = err;
            worst_x = x;
        }
    }
    cr_log_info("%s: max %.6Lf lsb (%.4Lf of the bound) at %.12Lf", c.name, worst, worst_ratio, real_of(worst_x));
    cr_assert(worst_ratio <= 1.0L, "%s: %.6Lf lsb at x = %.12Lf (raw %lld)", c.name, worst, real_of(worst_x),
              (long long)worst_x);
}

static rt_real gen_pm1e4(lcg *g) { return lcg_real(g, -1e4L, 1e4L); }
static rt_real gen_pm2pi(lcg *g) { return lcg_real(g, -6.3L, 6.3L); }
static rt_real gen_tan_domain(lcg *g) { return lcg_real(g, -1.5707L, 1.5707L); }
static rt_real gen_exp_range(lcg *g) { return lcg_real(g, -23.0L, 21.48L); }
static rt_real gen_positive(lcg *g)
{
    rt_real a = lcg_any(g);
    return a > 0 ? a : a < 0 ? -a : 1;
}
static rt_real gen_near_one(lcg *g) { return RT_ONE + lcg_real(g, -1e-3L, 1e-3L); }

static const unary_case sin_case = {"sin", rt_sin, sinl, sin_cos_bound};
static const unary_case cos_case = {"cos", rt_cos, cosl, sin_cos_bound};
static const unary_case tan_case = {"tan", rt_tan, tanl, tan_bound};
static const unary_case exp_case = {"exp", rt_exp, expl, exp_bound};
static const unary_case log_case = {"log", rt_log, logl, log_bound};

/* ---- representation and arithmetic ---------------------------------------------- */

/* RT_C must be usable where only constant expressions are allowed. */
static const rt_real constants[] = {RT_C(1.5), RT_C(-0.25), RT_C(1e30), RT_C(-1e30), RT_PI, RT_C(1e-10)};

Test(real_fixed, constants_are_rounded_and_saturated)
{
    cr_assert_eq(constants[0], INT64_C(3) << 31);
    cr_assert_eq(constants[1], -(INT64_C(1) << 30));
    cr_assert_eq(constants[2], RT_REAL_MAX);
    cr_assert_eq(constants[3], -RT_REAL_MAX);
    cr_assert_eq(constants[4], INT64_C(13493037705)); /* round(pi * 2^32) = 13493037704.52 -> up */
    cr_assert_eq(constants[5], 0);                    /* 1e-10 * 2^32 = 0.43 */
    cr_assert_eq(RT_ONE, rt_from_int(1));
    cr_assert_eq(rt_from_int(-7), -7 * RT_ONE);
    cr_assert_eq(rt_from_int(INT64_C(1) << 40), RT_REAL_MAX);
    cr_assert_eq(rt_from_int(INT32_MIN), -RT_REAL_MAX);
}

Test(real_fixed, add_and_sub_saturate_symmetrically)
{
    cr_assert_eq(rt_add(RT_REAL_MAX, RT_ONE), RT_REAL_MAX);
    cr_assert_eq(rt_add(-RT_REAL_MAX, -RT_ONE), -RT_REAL_MAX);
    cr_assert_eq(rt_add(-RT_REAL_MAX, -1), -RT_REAL_MAX); /* would be INT64_MIN */
    cr_assert_eq(rt_sub(RT_REAL_MAX, -RT_ONE), RT_REAL_MAX);
    cr_assert_eq(rt_sub(-RT_REAL_MAX, RT_ONE), -RT_REAL_MAX);
    cr_assert_eq(rt_sub(-RT_REAL_MAX, 1), -RT_REAL_MAX);
    cr_assert_eq(rt_add(RT_C(1.25), RT_C(-3.5)), RT_C(-2.25));
    cr_assert_eq(rt_neg(INT64_MIN), RT_REAL_MAX);
    cr_assert_eq(rt_abs(-RT_REAL_MAX), RT_REAL_MAX);
    cr_assert(!rt_is_finite(RT_REAL_MAX) && !rt_is_finite(-RT_REAL_MAX) && rt_is_finite(RT_C(-2e9)));
}

#ifdef __SIZEOF_INT128__
/* Exact references: round half away from zero of n / d on 128-bit magnitudes. */
static __int128 round_div(__int128 n, __int128 d)
{
    bool neg = (n < 0) != (d < 0);
    unsigned __int128 un = n < 0 ? -(unsigned __int128)n : (unsigned __int128)n;
    unsigned __int128 ud = d < 0 ? -(unsigned __int128)d : (unsigned __int128)d;
    unsigned __int128 q = un / ud, r = un % ud;
    if (2 * r >= ud) q++;
    return neg ? -(__int128)q : (__int128)q;
}
static rt_real saturate(__int128 v) { return v > INT64_MAX ? RT_REAL_MAX : v < -INT64_MAX ? -RT_REAL_MAX : (rt_real)v; }
#endif

Test(real_fixed, mul_rounds_to_nearest_and_saturates)
{
#ifdef __SIZEOF_INT128__
    lcg g = {1};
    for (int i = 0; i < 200000; i++) {
        rt_real a = lcg_any(&g), b = lcg_any(&g);
        rt_real want = saturate(round_div((__int128)a * b, (__int128)1 << 32));
        cr_assert_eq(rt_mul(a, b), want, "%lld * %lld", (long long)a, (long long)b);
        cr_assert_eq(rt_mul(rt_neg(a), b), rt_neg(rt_mul(a, b)));
    }
#endif
    cr_assert_eq(rt_mul(RT_C(1.5), RT_C(-2.5)), RT_C(-3.75));
    cr_assert_eq(rt_mul(1, RT_C(0.5)), 1); /* 0.5 lsb rounds away from zero */
    cr_assert_eq(rt_mul(-1, RT_C(0.5)), -1);
    cr_assert_eq(rt_mul(1, RT_C(0.25)), 0);
    cr_assert_eq(rt_mul(RT_C(1e5), RT_C(1e5)), RT_REAL_MAX);
    cr_assert_eq(rt_mul(RT_C(-1e5), RT_C(1e5)), -RT_REAL_MAX);
    cr_assert_eq(rt_mul(RT_REAL_MAX, RT_REAL_MAX), RT_REAL_MAX);
}

Test(real_fixed, half_is_mul_by_one_half)
{
    const rt_real edges[] = {0, 1, -1, 2, -2, 3, -3, RT_REAL_MAX, -RT_REAL_MAX, INT64_MIN, RT_C(1.5), RT_C(-2.25)};
    for (int i = 0; i < (int)(sizeof edges / sizeof edges[0]); i++)
        cr_assert_eq(rt_half(edges[i]), rt_mul(edges[i], RT_C(0.5)), "%lld", (long long)edges[i]);
    lcg g = {7};
    for (int i = 0; i < 200000; i++) {
        rt_real a = lcg_any(&g);
        cr_assert_eq(rt_half(a), rt_mul(a, RT_C(0.5)), "%lld", (long long)a);
    }
}

/* Where rt_mul's 64-bit rounding hands over to the 128-bit one (a high word of -2^31 or
 * 2^31 - 1 and beyond: products near +-2^95 and +-(2^95 - 2^64)), and exact ties, against
 * the exact reference. */
Test(real_fixed, mul_matches_exact_product_near_rails_and_ties)
{
#ifdef __SIZEOF_INT128__
    lcg g = {13};
    for (int i = 0; i < 1000000; i++) {
        rt_real a = (rt_real)(lcg_next(&g) >> (1 + lcg_next(&g) % 30)) | (INT64_C(1) << 33), b;
        if (i % 2 == 0) { /* a b within 4 a of 2^95 or of 2^95 - 2^64 */
            unsigned __int128 edge = ((unsigned __int128)1 << 95) - ((unsigned __int128)(lcg_next(&g) & 1) << 64);
            b = (rt_real)(edge / (uint64_t)a) + (rt_real)(lcg_next(&g) % 9) - 4;
        } else {
            a |= 1; /* an odd a times 2^31 (2k + 1) has a fraction of exactly half an lsb */
            b = (rt_real)(lcg_next(&g) % 64 * 2 + 1) << 31;
        }
        if (lcg_next(&g) & 1) a = -a;
        if (lcg_next(&g) & 1) b = -b;
        rt_real want = saturate(round_div((__int128)a * b, (__int128)1 << 32));
        cr_assert_eq(rt_mul(a, b), want, "%lld * %lld", (long long)a, (long long)b);
    }
#endif
    cr_assert_eq(rt_mul(RT_ONE, RT_REAL_MAX - 5), RT_REAL_MAX - 5); /* a high word of 2^31 - 1 */
    cr_assert_eq(rt_mul(-RT_ONE, RT_REAL_MAX), -RT_REAL_MAX);       /* -2^31 */
    cr_assert_eq(rt_mul(RT_C(0.5), RT_REAL_MAX), INT64_C(1) << 62); /* 2^62 - 1/2 rounds up */
}

/* The unsaturated operations (for operands the caller bounds below the rails) against
 * the saturating ones and the exact product, on operands up to 2^15.5 in magnitude (and
 * ties). */
Test(real_fixed, unsaturated_operations_match_within_the_rails)
{
    lcg g = {17};
    for (int i = 0; i < 1000000; i++) {
        rt_real a = lcg_real(&g, -46340.0L, 46340.0L), b = lcg_real(&g, -46340.0L, 46340.0L);
        if (i % 4 == 0) b = (rt_real)(lcg_next(&g) % 64 * 2 + 1) << 31; /* a tie when a is odd */
        cr_assert_eq(rt_mul_unsaturated(a, b), rt_mul(a, b), "%lld * %lld", (long long)a, (long long)b);
#ifdef __SIZEOF_INT128__
        cr_assert_eq(rt_mul(a, b), saturate(round_div((__int128)a * b, (__int128)1 << 32)));
#endif
        rt_real c = a * 16384, d = b * 16384; /* up to 2^30 */
        cr_assert_eq(rt_add_unsaturated(c, d), rt_add(c, d));
        cr_assert_eq(rt_sub_unsaturated(c, d), rt_sub(c, d));
    }
}

/* rt_fx_mul_sub_sign against the exact 128-bit difference, on operands of every length
 * and on equal products. */
Test(real_fixed, mul_sub_sign_is_the_exact_sign)
{
#ifdef __SIZEOF_INT128__
    lcg g = {29};
    for (int i = 0; i < 1000000; i++) {
        rt_real a = lcg_any(&g), b = lcg_any(&g), c = lcg_any(&g), d = lcg_any(&g);
        if (i % 4 == 0) { /* the same product, or one lsb of a factor away */
            c = b;
            d = a + (rt_real)(lcg_next(&g) % 3) - 1;
        }
        if (i % 16 == 1) a = 0;
        __int128 diff = (__int128)a * b - (__int128)c * d; /* below 2^127: no overflow */
        int want = (diff > 0) - (diff < 0);
        cr_assert_eq(rt_fx_mul_sub_sign(a, b, c, d), want, "%lld %lld %lld %lld", (long long)a, (long long)b,
                     (long long)c, (long long)d);
        /* The rounded difference never has the other sign. */
        rt_real rounded = rt_sub(rt_mul(a, b), rt_mul(c, d));
        cr_assert(want == 0 ? rounded == 0 : (rounded == 0 || (rounded > 0) == (want > 0)));
    }
#endif
    cr_assert_eq(rt_fx_mul_sub_sign(103011, -413, 12455, 103017), -1); /* rounds to 0 as a difference */
    cr_assert_eq(rt_sub(rt_mul(103011, -413), rt_mul(12455, 103017)), 0);
    cr_assert_eq(rt_fx_mul_sub_sign(RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX - 1), 1);
    cr_assert_eq(rt_fx_mul_sub_sign(-RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX, -RT_REAL_MAX), 0);
}

/* rt_fx_mul_sub, the triangle test's edge function: the rounded difference of the two
 * products and the exact sign, as rt_sub of two rt_mul and rt_fx_mul_sub_sign give them;
 * unsaturated for operands up to 2^15 (products and difference below 2^31). */
Test(real_fixed, mul_sub_is_two_rounded_products_and_the_exact_sign)
{
    lcg g = {31};
    for (int i = 0; i < 1000000; i++) {
        bool bounded = i % 2;
        rt_real a, b, c, d;
        if (bounded) {
            a = lcg_real(&g, -32767.0L, 32767.0L), b = lcg_real(&g, -32767.0L, 32767.0L);
            c = lcg_real(&g, -32767.0L, 32767.0L), d = lcg_real(&g, -32767.0L, 32767.0L);
        } else {
            a = lcg_any(&g), b = lcg_any(&g), c = lcg_any(&g), d = lcg_any(&g);
        }
        if (i % 8 < 2) { /* the same product, or one lsb of a factor away */
            c = b;
            d = a + (rt_real)(lcg_next(&g) % 3) - 1;
        }
        if (i % 16 == 5) b = (rt_real)(lcg_next(&g) % 64 * 2 + 1) << 31; /* a rounding tie */
        int sign = 2;
        rt_real got = rt_fx_mul_sub(a, b, c, d, bounded, &sign);
        cr_assert_eq(got, rt_sub(rt_mul(a, b), rt_mul(c, d)), "%lld %lld %lld %lld", (long long)a, (long long)b,
                     (long long)c, (long long)d);
        cr_assert_eq(sign, rt_fx_mul_sub_sign(a, b, c, d));
    }
}

/* rt_triangle_unsaturated's bound: within it the unsaturated triangle test gives the
 * saturating one's crossing, at the corners of the range (vertices and origins at
 * +-4096, the largest relative and sheared coordinates) and inside it. */
Test(real_fixed, unsaturated_triangle_test_matches_within_its_bound)
{
    lcg g = {23};
    const long double r = 4096.0L;
    int crossings = 0;
    for (int i = 0; i < 200000; i++) {
        rt_vec3 p[4]; /* three vertices and the origin */
        for (int k = 0; k < 4; k++) {
            rt_real c[3];
            for (int j = 0; j < 3; j++)
                c[j] = i % 8 < 3 ? lcg_real(&g, -r, r) : (lcg_next(&g) & 1 ? RT_C(4096.0) : RT_C(-4096.0));
            p[k] = rt_v3(c[0], c[1], c[2]);
        }
        /* Aim at a point of the triangle, anywhere, or along a diagonal (|sx| = |sy| = 1:
         * with corner points, sheared coordinates up to 4 r and a determinant near 96 r^2). */
        rt_real w0 = lcg_real(&g, 0.0L, 1.0L), w1 = lcg_real(&g, 0.0L, 1.0L);
        rt_vec3 target = rt_v3_add(p[0], rt_v3_add(rt_v3_scale(rt_v3_sub(p[1], p[0]), rt_mul(w0, w1)),
                                                   rt_v3_scale(rt_v3_sub(p[2], p[0]), rt_sub(w0, rt_mul(w0, w1)))));
        rt_vec3 dir = rt_v3_sub(target, p[3]);
        if (i % 4 == 1) dir = rt_v3(lcg_real(&g, -r, r), lcg_real(&g, -r, r), lcg_real(&g, -r, r));
        if (i % 4 == 3)
            dir = rt_v3(lcg_next(&g) & 1 ? RT_ONE : -RT_ONE, lcg_next(&g) & 1 ? RT_ONE : -RT_ONE,
                        lcg_next(&g) & 1 ? RT_ONE : -RT_ONE);
        rt_ray_setup rs = rt_intersect_prepare(rt_ray_make(p[3], dir, RT_REAL_MAX));
        cr_assert(rt_triangle_unsaturated(&rs, RT_C(4096.0)));
        rt_triangle_crossing a = {0}, b = {0};
        bool hit_a = rt_triangle_cross(&rs, p[0], p[1], p[2], &a, rs.kx, rs.ky, rs.kz, true);
        bool hit_b = rt_triangle_cross(&rs, p[0], p[1], p[2], &b, rs.kx, rs.ky, rs.kz, false);
        cr_assert_eq(hit_a, hit_b, "case %d", i);
        cr_assert(!hit_a || (a.t == b.t && a.v == b.v && a.w == b.w && a.det == b.det), "case %d", i);
        crossings += hit_a;
    }
    cr_log_info("%d crossings", crossings);
    cr_assert_gt(crossings, 25000); /* the aimed rays (half of them) mostly cross */
    rt_ray_setup far = rt_intersect_prepare(
        rt_ray_make(rt_v3(RT_C(4097.0), RT_ZERO, RT_ZERO), rt_v3(RT_ONE, RT_ZERO, RT_ZERO), RT_REAL_MAX));
    cr_assert(!rt_triangle_unsaturated(&far, RT_C(4096.0)));
    cr_assert(!rt_triangle_unsaturated(&far, RT_C(4096.5)));
}

Test(real_fixed, div_rounds_to_nearest_and_saturates)
{
#ifdef __SIZEOF_INT128__
    lcg g = {2};
    for (int i = 0; i < 200000; i++) {
        rt_real a = lcg_any(&g), b = lcg_any(&g);
        if (b == 0) continue;
        rt_real want = saturate(round_div((__int128)a * ((__int128)1 << 32), b));
        cr_assert_eq(rt_div(a, b), want, "%lld / %lld", (long long)a, (long long)b);
    }
#endif
    cr_assert_eq(rt_div(RT_ONE, RT_C(3.0)), INT64_C(1431655765)); /* 2^32 / 3 = 1431655765.33 */
    cr_assert_eq(rt_div(RT_C(-7.5), RT_C(2.5)), RT_C(-3.0));
    cr_assert_eq(rt_div(RT_ONE, 0), RT_REAL_MAX);
    cr_assert_eq(rt_div(-RT_ONE, 0), -RT_REAL_MAX);
    cr_assert_eq(rt_div(0, 0), 0);
    cr_assert_eq(rt_div(RT_C(1e9), RT_C(0.01)), RT_REAL_MAX);
    cr_assert_eq(rt_div(RT_C(1e9), RT_C(-0.01)), -RT_REAL_MAX);
    cr_assert_eq(rt_div(RT_REAL_MAX, RT_REAL_MAX), RT_ONE);
}

#ifdef __SIZEOF_INT128__
/* The specification of rt_fx_div_round: round(n 2^shift / d), halves up, UINT64_MAX from 2^63. */
static uint64_t div_round_ref(uint64_t n, unsigned shift, uint64_t d)
{
    unsigned __int128 q = ((unsigned __int128)n << shift) / d, r = ((unsigned __int128)n << shift) % d;
    if (2 * r >= d) q++;
    return q >> 63 ? UINT64_MAX : (uint64_t)q;
}
#endif

/* The division kernel against the exact quotient (the divq path on x86-64, the bit-serial
 * one in a -DRT_FIXED_PORTABLE or 32-bit build), on operands of every length: small divisors
 * (frequent ties), quotients near 2^64 and the 2^63 rail, divisors from 2^63, every shift. */
Test(real_fixed, div_round_matches_exact_quotient)
{
#ifdef __SIZEOF_INT128__
    lcg g = {9};
    for (int i = 0; i < 3000000; i++) {
        uint64_t n = lcg_next(&g) >> (lcg_next(&g) % 64), d = lcg_next(&g) >> (lcg_next(&g) % 64);
        unsigned shift = i % 4 == 0 ? 62 : i % 4 == 1 ? 32 : 1 + (unsigned)(lcg_next(&g) % 63);
        if (i % 8 == 7) d = (n >> (64 - shift)) + (lcg_next(&g) % 5); /* quotient near 2^64 */
        if (i % 8 == 6) d = 1 + lcg_next(&g) % 64;
        if (i % 16 == 5) d |= UINT64_C(1) << 63;
        if (d == 0) continue;
        cr_assert_eq(rt_fx_div_round(n, shift, d), div_round_ref(n, shift, d), "%llu << %u / %llu",
                     (unsigned long long)n, shift, (unsigned long long)d);
    }
#endif
    cr_assert_eq(rt_fx_div_round(3, 1, 4), 2);                          /* 1.5 rounds up */
    cr_assert_eq(rt_fx_div_round(UINT64_C(1) << 62, 1, 1), UINT64_MAX); /* 2^63 */
    cr_assert_eq(rt_fx_div_round(UINT64_MAX, 62, UINT64_MAX), UINT64_C(1) << 62);
    cr_assert_eq(rt_fx_div_round(0, 32, 7), 0);
}

/* The triangle's t: one rounding of an exact sum of products that may itself pass the
 * Q32.32 range, against signed 128-bit arithmetic (operands below 2^62 keep it exact). */
Test(real_fixed, dot3_div_rounds_the_exact_sum_once)
{
#ifdef __SIZEOF_INT128__
    lcg g = {11};
    for (int i = 0; i < 1000000; i++) {
        rt_real v[7];
        for (int k = 0; k < 7; k++) v[k] = lcg_any(&g) / 2;
        if (i % 3 == 0) v[6] = (v[6] >> 40) | 1; /* small divisors: large quotients, the rail */
        if (i % 5 == 0) v[5] = -v[1] / 3;        /* cancellation */
        if (v[6] == 0) continue;
        __int128 sum = (__int128)v[0] * v[1] + (__int128)v[2] * v[3] + (__int128)v[4] * v[5];
        unsigned __int128 mag = sum < 0 ? -(unsigned __int128)sum : (unsigned __int128)sum;
        unsigned __int128 d = v[6] < 0 ? -(unsigned __int128)v[6] : (unsigned __int128)v[6];
        unsigned __int128 q = mag / d + (2 * (mag % d) >= d);
        rt_real want = q >= (unsigned __int128)INT64_MAX ? RT_REAL_MAX : (rt_real)q;
        if ((sum < 0) != (v[6] < 0)) want = -want;
        cr_assert_eq(rt_dot3_div(v[0], v[1], v[2], v[3], v[4], v[5], v[6]), want, "case %d", i);
    }
#endif
    /* 2^20 * 2^20 * 3 = 3 * 2^40 passes the range; divided by 2^20 it is 3 * 2^20 */
    rt_real m = RT_C(1048576.0);
    cr_assert_eq(rt_dot3_div(m, m, m, m, m, m, m), RT_C(3145728.0));
    cr_assert_eq(rt_dot3_div(m, m, -m, m, RT_ONE, RT_C(0.5), RT_C(2.0)), RT_C(0.25));
    cr_assert_eq(rt_dot3_div(RT_ONE, RT_ONE, 0, 0, 0, 0, 0), RT_REAL_MAX);
    cr_assert_eq(rt_dot3_div(-RT_ONE, RT_ONE, 0, 0, 0, 0, 0), -RT_REAL_MAX);
    cr_assert_eq(rt_dot3_div(0, RT_ONE, 0, 0, 0, 0, 0), 0);
}

Test(real_fixed, sqrt_is_correctly_rounded)
{
    lcg g = {3};
    for (int i = 0; i < 1000000; i++) {
        /* every length, then the smallest inputs and those at the rail */
        rt_real a = i < 600000 ? gen_positive(&g) : i < 800000 ? i - 599999 : RT_REAL_MAX - (i - 800000);
        rt_real r = rt_sqrt(a);
#ifdef __SIZEOF_INT128__
        /* r correctly rounded <=> (2r - 1)^2 <= 4 a 2^32 < (2r + 1)^2 (no ties: the left side is odd) */
        unsigned __int128 n4 = (unsigned __int128)a << 34, lo = 2 * (unsigned __int128)r - 1, hi = lo + 2;
        cr_assert(lo * lo <= n4 && n4 < hi * hi, "sqrt of raw %lld gave %lld", (long long)a, (long long)r);
#else
        cr_assert(lsb_error(r, sqrtl(real_of(a))) <= ROUNDED + 0x1p-20L);
#endif
    }
    cr_assert_eq(rt_sqrt(RT_C(4.0)), RT_C(2.0));
    cr_assert_eq(rt_sqrt(RT_C(2.25)), RT_C(1.5));
    cr_assert_eq(rt_sqrt(0), 0);
    cr_assert_eq(rt_sqrt(-RT_ONE), 0);
    cr_assert_eq(rt_sqrt(1), 65536);                              /* sqrt(2^-32) = 2^-16 */
    cr_assert_eq(rt_sqrt(RT_REAL_MAX), INT64_C(199032864766430)); /* round(sqrt(2^63 - 1) * 2^16) */
}

Test(real_fixed, sqrt_mul_is_correctly_rounded_from_the_exact_product)
{
    lcg g = {5};
    for (int i = 0; i < 1000000; i++) {
        rt_real a = i % 4 == 0 ? 1 + (rt_real)(lcg_next(&g) % 4096) : gen_positive(&g), b = gen_positive(&g);
        rt_real r = rt_sqrt_mul(a, b);
        cr_assert_eq(rt_sqrt_mul(b, a), r);
#ifdef __SIZEOF_INT128__
        /* r = round(sqrt(n)) for the integer n = a b <=> r^2 - r < n <= r^2 + r */
        unsigned __int128 n = (unsigned __int128)a * (unsigned __int128)b, r2 = (unsigned __int128)r * r;
        cr_assert(r2 - r < n && n <= r2 + r, "sqrt_mul of raw %lld, %lld gave %lld", (long long)a, (long long)b,
                  (long long)r);
#else
        cr_assert(lsb_error(r, sqrtl(real_of(a) * real_of(b))) <= ROUNDED + 0x1p-20L);
#endif
    }
    cr_assert_eq(rt_sqrt_mul(RT_C(2.0), RT_C(8.0)), RT_C(4.0));
    cr_assert_eq(rt_sqrt_mul(1, 1), 1); /* sqrt(2^-64) = 2^-32, which rt_sqrt(rt_mul(1, 1)) loses */
    cr_assert_eq(rt_sqrt_mul(RT_C(3.0), RT_ONE), rt_sqrt(RT_C(3.0)));
    cr_assert_eq(rt_sqrt_mul(RT_REAL_MAX, RT_REAL_MAX), RT_REAL_MAX);
    cr_assert_eq(rt_sqrt_mul(-RT_ONE, -RT_ONE), 0);
    cr_assert_eq(rt_sqrt_mul(0, RT_ONE), 0);
}

Test(real_fixed, floor_int_and_unit_to_byte)
{
    cr_assert_eq(rt_floor_int(RT_C(2.75)), 2);
    cr_assert_eq(rt_floor_int(RT_C(-0.5)), -1);
    cr_assert_eq(rt_floor_int(RT_C(-3.0)), -3);
    cr_assert_eq(rt_floor_int(-1), -1);
    cr_assert_eq(rt_floor_int(RT_REAL_MAX), INT32_MAX);
    cr_assert_eq(rt_floor_int(-RT_REAL_MAX), INT32_MIN);
    /* floor(255 c + 2^-20): the step to k comes 2^-20 / 255 early, like the float rounding
     * of the solution; a clear 2^-16 below k/255 still gives k - 1. */
    for (int64_t k = 1; k <= 255; k++) {
        rt_real exact = (rt_real)((k << 32) + 254) / 255; /* smallest raw c with floor(255 c) = k */
        rt_real first = (rt_real)((k << 32) - (INT64_C(1) << 12) + 254) / 255;
        cr_assert_eq(rt_unit_to_byte(exact), k);
        cr_assert_eq(rt_unit_to_byte(first), k);
        cr_assert_eq(rt_unit_to_byte(first - 1), k - 1);
        cr_assert_eq(rt_unit_to_byte(exact - (INT64_C(1) << 16)), k - 1);
    }
    cr_assert_eq(rt_unit_to_byte(RT_ONE), 255);
    cr_assert_eq(rt_unit_to_byte(RT_C(7.0)), 255);
    cr_assert_eq(rt_unit_to_byte(RT_C(-0.5)), 0);
}

Test(real_fixed, host_conversions)
{
    cr_assert_eq(rt_from_double(1.5), RT_C(1.5));
    cr_assert_eq(rt_from_double(-0x1p-33), -1); /* -0.5 lsb rounds away from zero */
    cr_assert_eq(rt_from_double(0x1p-34), 0);
    cr_assert_eq(rt_from_double(3e9), RT_REAL_MAX);
    cr_assert_eq(rt_from_double(-INFINITY), -RT_REAL_MAX);
    cr_assert_eq(rt_from_double(NAN), 0);
    cr_assert(rt_to_double(RT_C(-2.5)) == -2.5);
    cr_assert_eq(rt_real_to_bits(RT_C(-1.0)), UINT64_C(0xffffffff00000000));
    cr_assert_eq(rt_real_from_bits(UINT64_C(0xffffffff00000000)), RT_C(-1.0));
    cr_assert_eq(rt_real_from_bits(rt_real_to_bits(INT64_MIN)), INT64_MIN);
    lcg g = {4};
    for (int i = 0; i < 10000; i++) {
        rt_real a = lcg_real(&g, -1e6L, 1e6L); /* below 2^53 raw: the round trip is exact */
        cr_assert_eq(rt_from_double(rt_to_double(a)), a);
    }
}

/* ---- elementary functions --------------------------------------------------------- */

Test(real_fixed, sin_cos_within_bound)
{
    check_unary(sin_case, (lcg){10}, gen_pm1e4, 200000);
    check_unary(cos_case, (lcg){11}, gen_pm1e4, 200000);
    check_unary(sin_case, (lcg){12}, gen_pm2pi, 100000);
    check_unary(cos_case, (lcg){13}, gen_pm2pi, 100000);
    check_unary(sin_case, (lcg){14}, lcg_any, 100000); /* the whole range, up to 2^31 */
    check_unary(cos_case, (lcg){15}, lcg_any, 100000);
}

Test(real_fixed, tan_within_bound)
{
    check_unary(tan_case, (lcg){16}, gen_tan_domain, 200000);
    check_unary(tan_case, (lcg){17}, gen_pm1e4, 200000);
}

Test(real_fixed, exp_within_bound)
{
    check_unary(exp_case, (lcg){20}, gen_exp_range, 300000);
    check_unary(exp_case, (lcg){21}, gen_pm2pi, 100000);
}

Test(real_fixed, log_within_bound)
{
    check_unary(log_case, (lcg){30}, gen_positive, 300000);
    check_unary(log_case, (lcg){31}, gen_near_one, 100000);
}

/* pow over the Blinn-Phong domain: base in (0, 1], e in [0, 1000]. */
Test(real_fixed, pow_within_bound_on_specular_domain)
{
    lcg g = {40};
    long double worst = 0.0L, worst_ratio = 0.0L;
    rt_real wx = 0, wy = 0;
    for (int i = 0; i < 300000; i++) {
        rt_real x = i % 2 ? lcg_real(&g, 0.0L, 1.0L) : RT_ONE - lcg_real(&g, 0.0L, 1e-4L);
        rt_real y = i % 5 ? lcg_real(&g, 0.0L, 1000.0L) : rt_from_int((int64_t)(lcg_next(&g) % 1001));
        if (x == 0) continue;
        long double ref = powl(real_of(x), real_of(y));
        long double err = lsb_error(rt_pow(x, y), ref), ratio = err / pow_bound(ref, real_of(y));
        if (ratio > worst_ratio) {
            worst_ratio = ratio;
            worst = err;
            wx = x;
            wy = y;
        }
    }
    cr_log_info("pow: max %.6Lf lsb (%.4Lf of the bound) at %.12Lf ^ %.6Lf", worst, worst_ratio, real_of(wx),
                real_of(wy));
    cr_assert(worst_ratio <= 1.0L, "pow: %.6Lf lsb at %.12Lf ^ %.6Lf", worst, real_of(wx), real_of(wy));
}

/* Other bases: the error grows with |e log base| (exp of a Q58 argument known to |e| 2^-57). */
Test(real_fixed, pow_within_bound_on_other_bases)
{
    lcg g = {41};
    for (int i = 0; i < 100000; i++) {
        rt_real x = lcg_real(&g, 0.5L, 4.0L), y = lcg_real(&g, -20.0L, 20.0L);
        long double ref = powl(real_of(x), real_of(y));
        if (ref > 2e9L) continue;
        long double err = lsb_error(rt_pow(x, y), ref);
        cr_assert(err <= pow_bound(ref, real_of(y)), "pow: %.3Lf lsb at %.12Lf ^ %.12Lf", err, real_of(x), real_of(y));
    }
}

Test(real_fixed, elementary_special_values)
{
    cr_assert_eq(rt_sin(0), 0);
    cr_assert_eq(rt_cos(0), RT_ONE);
    cr_assert_eq(rt_tan(0), 0);
    cr_assert_eq(rt_exp(0), RT_ONE);
    cr_assert_eq(rt_exp(RT_C(30.0)), RT_REAL_MAX);
    cr_assert_eq(rt_exp(RT_C(-30.0)), 0);
    cr_assert_eq(rt_exp(RT_REAL_MAX), RT_REAL_MAX);
    cr_assert_eq(rt_exp(-RT_REAL_MAX), 0);
    cr_assert_eq(rt_log(RT_ONE), 0);
    cr_assert_eq(rt_log(0), -RT_REAL_MAX);
    cr_assert_eq(rt_log(-RT_ONE), -RT_REAL_MAX);
    cr_assert(lsb_error(rt_log(1), logl(LSB)) <= ROUNDED);
    cr_assert(lsb_error(rt_log(RT_REAL_MAX), logl(real_of(RT_REAL_MAX))) <= ROUNDED + 0x1p-20L);
    cr_assert_eq(rt_pow(0, 0), RT_ONE);
    cr_assert_eq(rt_pow(0, RT_C(2.5)), 0);
    cr_assert_eq(rt_pow(-RT_ONE, RT_C(2.0)), 0);
    cr_assert_eq(rt_pow(0, RT_C(-1.0)), RT_REAL_MAX);
    cr_assert_eq(rt_pow(RT_C(0.37), 0), RT_ONE);
    cr_assert_eq(rt_pow(RT_ONE, RT_C(1000.0)), RT_ONE);
    cr_assert_eq(rt_pow(RT_C(0.5), RT_C(2.0)), RT_C(0.25));
    cr_assert_eq(rt_pow(RT_C(2.0), RT_C(10.0)), RT_C(1024.0));
    cr_assert_eq(rt_pow(RT_C(10.0), RT_C(10.0)), RT_REAL_MAX);
    cr_assert_eq(rt_pow(1, RT_C(1000.0)), 0);
}

Test(real_fixed, trig_exact_symmetry)
{
    lcg g = {50};
    for (int i = 0; i < 50000; i++) {
        rt_real x = lcg_any(&g);
        cr_assert_eq(rt_sin(rt_neg(x)), rt_neg(rt_sin(x)));
        cr_assert_eq(rt_cos(rt_neg(x)), rt_cos(x));
        cr_assert_eq(rt_tan(rt_neg(x)), rt_neg(rt_tan(x)));
    }
}

/* rt_times16 and rt_over16 against rt_mul by 16 and 1/16: ties, the rails and around them. */
Test(real_fixed, times16_and_over16_are_rt_mul)
{
    lcg g = {37};
    const rt_real most = RT_REAL_MAX / 16;
    const rt_real edge[] = {0, 1, -1, 7, 8, 9, -7, -8, -9, 24, -24, most, most + 1, -most, -most - 1, RT_REAL_MAX};
    for (int i = 0; i < 1000000; i++) {
        rt_real a = i < (int)(sizeof edge / sizeof *edge) ? edge[i] : lcg_any(&g);
        cr_assert_eq(rt_times16(a), rt_mul(a, RT_C(16.0)), "%lld", (long long)a);
        cr_assert_eq(rt_over16(a), rt_mul(a, RT_C(0.0625)), "%lld", (long long)a);
        cr_assert_eq(rt_times16(-a), rt_mul(-a, RT_C(16.0)), "%lld", (long long)-a);
        cr_assert_eq(rt_over16(-a), rt_mul(-a, RT_C(0.0625)), "%lld", (long long)-a);
    }
}

#endif

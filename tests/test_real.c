/* The double backend's elementary functions (core/real_double.c) against long double
 * libm on deterministic samples, their special cases, and rotations against cglm. */
#ifndef RT_REAL_FIXED

#include <cglm/cglm.h>
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "real.h"
#include "vec.h"

/* The error bounds documented in core/real_double.c, in ulps of the exact result. */
#define SIN_COS_ULP 1.0L
#define TAN_ULP 1.0L
#define EXP_ULP 1.0L
#define LOG_ULP 1.0L
#define POW_ULP 1.0L

/* 64-bit LCG (Knuth's MMIX constants): the same samples on every run and platform. */
typedef struct {
    uint64_t s;
} lcg;
static uint64_t lcg_next(lcg *g)
{
    g->s = g->s * 6364136223846793005u + 1442695040888963407u;
    return g->s;
}
static double lcg_uniform(lcg *g, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(lcg_next(g) >> 11) * 0x1p-53);
}
/* A random finite positive double (any exponent, subnormals included). */
static double lcg_positive(lcg *g)
{
    uint64_t u = lcg_next(g) % 0x7ff0000000000000u;
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* |got - ref| in units of the last place of the double nearest ref (subnormal ulp below 2^-1022). */
static long double ulp_error(double got, long double ref)
{
    if (isinf(got) || isinf(ref)) return (long double)got == ref ? 0.0L : INFINITY;
    int e = ref == 0.0L ? -1022 : ilogbl(ref);
    if (e < -1022) e = -1022;
    return fabsl((long double)got - ref) / ldexpl(1.0L, e - 52);
}

typedef double (*sample_fn)(lcg *g);
typedef struct {
    const char *name;
    rt_real (*f)(rt_real);
    long double (*ref)(long double);
    long double bound;
} unary_case;

/* Max ulp error of c over n samples from gen; fails naming the worst input. */
static void check_unary(unary_case c, sample_fn gen, uint64_t seed, int n)
{
    lcg g = {seed};
    long double worst = 0.0L;
    double worst_x = 0.0;
    for (int i = 0; i < n; i++) {
        double x = gen(&g);
        long double err = ulp_error(c.f(x), c.ref(x));
        if (err > worst) {
            worst = err;
            worst_x = x;
        }
    }
    cr_log_info("%s: max %.3Lf ulp at %.17g", c.name, worst, worst_x);
    cr_assert(worst <= c.bound, "%s: %.3Lf ulp at x = %a (bound %.1Lf)", c.name, worst, worst_x, c.bound);
}

static double gen_pm1e4(lcg *g) { return lcg_uniform(g, -1e4, 1e4); }
static double gen_small(lcg *g) { return ldexp(lcg_uniform(g, -1.0, 1.0), (int)(lcg_next(g) % 40) - 38); }
/* The doubles nearest k*pi/2, where the reduction cancels the most. */
static double gen_near_pio2(lcg *g)
{
    return (double)((long double)(lcg_next(g) % 12733) * (3.14159265358979323846264338327950288L / 2));
}
static double gen_huge(lcg *g) { return ldexp(lcg_uniform(g, -2.0, 2.0), 17 + (int)(lcg_next(g) % 1006)); }
static double gen_exp_range(lcg *g) { return lcg_uniform(g, -745.0, 709.78); }
static double gen_unit(lcg *g) { return lcg_uniform(g, -1.0, 1.0); }
static double gen_exp_tiny(lcg *g) { return ldexp(lcg_uniform(g, -1.0, 1.0), -(int)(lcg_next(g) % 60)); }
static double gen_near_one(lcg *g) { return 1.0 + ldexp(lcg_uniform(g, -1.0, 1.0), -(int)(lcg_next(g) % 53)); }

static const unary_case sin_case = {"sin", rt_sin, sinl, SIN_COS_ULP};
static const unary_case cos_case = {"cos", rt_cos, cosl, SIN_COS_ULP};
static const unary_case tan_case = {"tan", rt_tan, tanl, TAN_ULP};
static const unary_case exp_case = {"exp", rt_exp, expl, EXP_ULP};
static const unary_case log_case = {"log", rt_log, logl, LOG_ULP};

Test(real, trig_within_bound_on_pm1e4)
{
    check_unary(sin_case, gen_pm1e4, 1, 200000);
    check_unary(cos_case, gen_pm1e4, 2, 200000);
    check_unary(tan_case, gen_pm1e4, 3, 200000);
}

Test(real, trig_within_bound_small_arguments)
{
    check_unary(sin_case, gen_small, 4, 50000);
    check_unary(cos_case, gen_small, 5, 50000);
    check_unary(tan_case, gen_small, 6, 50000);
}

Test(real, trig_within_bound_near_multiples_of_half_pi)
{
    check_unary(sin_case, gen_near_pio2, 7, 20000);
    check_unary(cos_case, gen_near_pio2, 8, 20000);
    check_unary(tan_case, gen_near_pio2, 9, 20000); /* includes the poles' nearest doubles */
}

Test(real, trig_within_bound_beyond_cody_waite_range)
{
    check_unary(sin_case, gen_huge, 10, 50000);
    check_unary(cos_case, gen_huge, 11, 50000);
    check_unary(tan_case, gen_huge, 12, 50000);
}

/* Doubles closest to a multiple of pi/2: 6411027962775774 * 2^-47 (~29 pi/2, 2^-60.5
 * away, the worst below 2^17) and 6381956970095103 * 2^797 (2^-60.9 away, the worst of
 * all doubles). Expected values: mpmath at 2000 bits, printed to 20 digits. */
Test(real, trig_hardest_reductions)
{
    double a = 0x1.6c6cbc45dc8dep+5, b = 0x1.6ac5b262ca1ffp+849;
    cr_assert(ulp_error(rt_cos(a), -6.1898063658835770002e-19L) <= SIN_COS_ULP);
    cr_assert(ulp_error(rt_tan(a), -1615559422846748268.4L) <= TAN_ULP);
    cr_assert_eq(rt_sin(a), 1.0);
    cr_assert(ulp_error(rt_cos(b), -4.6871659242546276111e-19L) <= SIN_COS_ULP);
    cr_assert(ulp_error(rt_tan(b), -2133485385753703843.7L) <= TAN_ULP);
    cr_assert_eq(rt_sin(b), 1.0);
}

Test(real, trig_special_values)
{
    cr_assert(isnan(rt_sin(NAN)) && isnan(rt_cos(NAN)) && isnan(rt_tan(NAN)));
    cr_assert(isnan(rt_sin(INFINITY)) && isnan(rt_cos(-INFINITY)) && isnan(rt_tan(INFINITY)));
    cr_assert(rt_sin(-0.0) == 0.0 && signbit(rt_sin(-0.0)));
    cr_assert(rt_tan(-0.0) == 0.0 && signbit(rt_tan(-0.0)));
    cr_assert_eq(rt_cos(0.0), 1.0);
    cr_assert_eq(rt_sin(0x1p-1074), 0x1p-1074);
    cr_assert_eq(rt_sin(1e-300), 1e-300);
    cr_assert_eq(rt_cos(1e-300), 1.0);
}

Test(real, trig_exact_symmetry)
{
    lcg g = {13};
    for (int i = 0; i < 20000; i++) {
        double x = i & 1 ? gen_pm1e4(&g) : gen_huge(&g);
        cr_assert_eq(rt_sin(-x), -rt_sin(x), "x = %a", x);
        cr_assert_eq(rt_cos(-x), rt_cos(x), "x = %a", x);
        cr_assert_eq(rt_tan(-x), -rt_tan(x), "x = %a", x);
    }
}

Test(real, exp_within_bound)
{
    check_unary(exp_case, gen_exp_range, 20, 200000); /* includes subnormal results */
    check_unary(exp_case, gen_unit, 21, 100000);
    check_unary(exp_case, gen_exp_tiny, 22, 50000);
}

Test(real, exp_special_values)
{
    cr_assert_eq(rt_exp(0.0), 1.0);
    cr_assert_eq(rt_exp(-0.0), 1.0);
    cr_assert(isinf(rt_exp(1000.0)) && rt_exp(1000.0) > 0.0);
    cr_assert(isinf(rt_exp(709.79)));
    cr_assert(isfinite(rt_exp(709.78)));
    cr_assert_eq(rt_exp(-1000.0), 0.0);
    cr_assert_eq(rt_exp(-746.0), 0.0);
    cr_assert_eq(rt_exp(-745.0), 0x1p-1074); /* e^-745 = 2^-1074.8, rounds up to the least subnormal */
    cr_assert(isinf(rt_exp(INFINITY)));
    cr_assert_eq(rt_exp(-INFINITY), 0.0);
    cr_assert(isnan(rt_exp(NAN)));
}

Test(real, log_within_bound)
{
    check_unary(log_case, lcg_positive, 30, 200000); /* every binade, subnormals included */
    check_unary(log_case, gen_near_one, 31, 100000);
}

Test(real, log_special_values)
{
    cr_assert_eq(rt_log(1.0), 0.0);
    cr_assert(rt_log(0.0) < 0.0 && isinf(rt_log(0.0)));
    cr_assert(rt_log(-0.0) < 0.0 && isinf(rt_log(-0.0)));
    cr_assert(isnan(rt_log(-1.0)) && isnan(rt_log(-INFINITY)) && isnan(rt_log(NAN)));
    cr_assert(rt_log(INFINITY) > 0.0 && isinf(rt_log(INFINITY)));
    cr_assert(ulp_error(rt_log(0x1p-1074), logl(0x1p-1074L)) <= LOG_ULP);
    cr_assert(ulp_error(rt_log(1.7976931348623157e308), logl(1.7976931348623157e308L)) <= LOG_ULP);
    cr_assert(ulp_error(rt_log(2.0), 0.693147180559945309417232121458176568L) <= 0.5L);
}

/* pow over the Blinn-Phong domain: base in (0, 1] (uniform, tiny, and just below 1), e in [0, 1000]. */
Test(real, pow_within_bound_on_specular_domain)
{
    lcg g = {40};
    long double worst = 0.0L;
    double wx = 0.0, wy = 0.0;
    for (int i = 0; i < 300000; i++) {
        double x = i % 3 == 0   ? lcg_uniform(&g, 0.0, 1.0)
                   : i % 3 == 1 ? ldexp(lcg_uniform(&g, 0.5, 1.0), -(int)(lcg_next(&g) % 40))
                                : 1.0 - ldexp(lcg_uniform(&g, 0.0, 1.0), -(int)(lcg_next(&g) % 50));
        double y = i % 5 == 0 ? (double)(lcg_next(&g) % 1001) : lcg_uniform(&g, 0.0, 1000.0);
        if (x == 0.0) continue;
        long double err = ulp_error(rt_pow(x, y), powl(x, y));
        if (err > worst) {
            worst = err;
            wx = x;
            wy = y;
        }
    }
    cr_log_info("pow: max %.3Lf ulp at %.17g ^ %.17g", worst, wx, wy);
    cr_assert(worst <= POW_ULP, "pow: %.3Lf ulp at %a ^ %a", worst, wx, wy);
}

Test(real, pow_special_values)
{
    cr_assert_eq(rt_pow(0.0, 0.0), 1.0);
    cr_assert_eq(rt_pow(0.0, 2.5), 0.0);
    cr_assert_eq(rt_pow(0.0, 1000.0), 0.0);
    cr_assert(isinf(rt_pow(0.0, -1.0)));
    cr_assert_eq(rt_pow(0.37, 0.0), 1.0);
    cr_assert_eq(rt_pow(NAN, 0.0), 1.0);
    cr_assert_eq(rt_pow(1.0, 1000.0), 1.0);
    cr_assert_eq(rt_pow(1.0, NAN), 1.0);
    cr_assert_eq(rt_pow(0.5, 2.0), 0.25);
    cr_assert_eq(rt_pow(2.0, 10.0), 1024.0);
    cr_assert_eq(rt_pow(0x1p-1074, 1.0), 0x1p-1074);
    cr_assert_eq(rt_pow(1e-300, 1000.0), 0.0);
    cr_assert(isinf(rt_pow(10.0, 400.0)));
    cr_assert_eq(rt_pow(0.5, INFINITY), 0.0);
    cr_assert(isinf(rt_pow(2.0, INFINITY)));
    cr_assert(isinf(rt_pow(INFINITY, 3.0)));
    cr_assert_eq(rt_pow(INFINITY, -3.0), 0.0);
    cr_assert(isnan(rt_pow(-2.0, 2.0)) && isnan(rt_pow(NAN, 1.0)) && isnan(rt_pow(0.5, NAN)));
}

/* cglm as an independent oracle: rt_affine_trs's rotation Rx * Ry * Rz (degrees) from
 * rt_sin/rt_cos against glm_rotate about x, then y, then z (cglm is float: 1e-6). */
Test(real, rotation_matches_cglm)
{
    lcg g = {50};
    for (int i = 0; i < 2000; i++) {
        /* float-representable degrees in [-180, 180], so both sides start from the same angles */
        double ax = (float)lcg_uniform(&g, -180.0, 180.0), ay = (float)lcg_uniform(&g, -180.0, 180.0),
               az = (float)lcg_uniform(&g, -180.0, 180.0);
        rt_affine a = rt_affine_trs(rt_v3(0.0, 0.0, 0.0), rt_v3(ax, ay, az), rt_v3(1.0, 1.0, 1.0));
        mat4 m;
        glm_mat4_identity(m);
        glm_rotate(m, glm_rad((float)ax), (vec3){1.0f, 0.0f, 0.0f});
        glm_rotate(m, glm_rad((float)ay), (vec3){0.0f, 1.0f, 0.0f});
        glm_rotate(m, glm_rad((float)az), (vec3){0.0f, 0.0f, 1.0f});
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) /* cglm is column-major: m[column][row] */
                cr_assert(fabs(a.linear.m[r][c] - (double)m[c][r]) <= 1e-6,
                          "angles (%g, %g, %g): [%d][%d] rt %.9f cglm %.9f", ax, ay, az, r, c, a.linear.m[r][c],
                          (double)m[c][r]);
    }
}

/* Plain cglm angles too: sin/cos of a float angle agree with glm's own rotation entries. */
Test(real, sin_cos_match_cglm_rotation_entries)
{
    lcg g = {51};
    for (int i = 0; i < 2000; i++) {
        float t = (float)lcg_uniform(&g, -100.0, 100.0);
        mat4 m;
        glm_rotate_make(m, t, (vec3){0.0f, 0.0f, 1.0f});
        cr_assert(fabs(rt_cos(t) - (double)m[0][0]) <= 1e-6, "cos(%g)", (double)t);
        cr_assert(fabs(rt_sin(t) - (double)m[0][1]) <= 1e-6, "sin(%g)", (double)t);
    }
}

#endif

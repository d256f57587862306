/* Inverse trigonometry (texture coordinates of quadrics), written once over rt_real for
 * both builds. atan: reduction to |x| <= tan(pi/12) through
 * atan(x) = pi/6 + atan((x*sqrt3 - 1)/(sqrt3 + x)), then the Taylor series to 15 terms
 * (truncation below 1e-18, so the error is a few ulp in double, a few lsb in fixed). */
#include "real.h"

#define SQRT3 RT_C(1.7320508075688772935)
#define PI_2 RT_C(1.5707963267948966192)
#define PI_6 RT_C(0.52359877559829887308)
#define TAN_PI_12 RT_C(0.26794919243112270647)

static rt_real atan_small(rt_real x)
{
    rt_real x2 = rt_mul(x, x), term = x, terms[15], sum = RT_ZERO;
    for (int k = 0; k < 15; k++) {
        terms[k] = rt_div(term, rt_from_int(2 * k + 1));
        term = rt_neg(rt_mul(term, x2));
    }
    /* Smallest terms first keeps the rounding error small. */
    for (int k = 14; k >= 0; k--) sum = rt_add(sum, terms[k]);
    return sum;
}

/* atan(x) for 0 <= x <= 1 */
static rt_real atan_unit(rt_real x)
{
    if (x <= TAN_PI_12) return atan_small(x);
    return rt_add(PI_6, atan_small(rt_div(rt_sub(rt_mul(x, SQRT3), RT_ONE), rt_add(SQRT3, x))));
}

rt_real rt_atan2(rt_real y, rt_real x)
{
    if (!rt_is_finite(x) || !rt_is_finite(y)) return RT_ZERO;
    if (x == RT_ZERO) return y > RT_ZERO ? PI_2 : y < RT_ZERO ? rt_neg(PI_2) : RT_ZERO;
    rt_real ay = rt_abs(y), ax = rt_abs(x);
    /* atan(ay/ax) without forming a ratio above 1. */
    rt_real a = ay > ax ? rt_sub(PI_2, atan_unit(rt_div(ax, ay))) : atan_unit(rt_div(ay, ax));
    if (x < RT_ZERO) a = rt_sub(RT_PI, a);
    return y < RT_ZERO ? rt_neg(a) : a;
}

rt_real rt_asin(rt_real x)
{
    if (!(x > rt_neg(RT_ONE))) return rt_neg(PI_2);
    if (!(x < RT_ONE)) return PI_2;
    return rt_atan2(x, rt_sqrt(rt_mul(rt_sub(RT_ONE, x), rt_add(RT_ONE, x))));
}

/* Inverse trigonometry for the double build (texture coordinates of quadrics).
 * atan: reduction to |x| <= tan(pi/12) with atan(x) = pi/6 + atan((x*sqrt3 - 1)/(sqrt3 + x)),
 * then the Taylor series to 15 terms (truncation < 1e-18); error a few ulp. */
#include "real.h"

#define SQRT3 1.7320508075688772935
#define PI_2 1.5707963267948966192
#define PI_6 0.52359877559829887308
#define TAN_PI_12 0.26794919243112270647

static double atan_small(double x)
{
    double x2 = x * x, term = x, sum = 0.0;
    /* Sum from the smallest term up so rounding errors stay small. */
    double terms[15];
    for (int k = 0; k < 15; k++) {
        terms[k] = term / (double)(2 * k + 1);
        term = -term * x2;
    }
    for (int k = 14; k >= 0; k--) sum += terms[k];
    return sum;
}

static double atan_unit(double x) /* 0 <= x <= 1 */
{
    if (x <= TAN_PI_12) return atan_small(x);
    return PI_6 + atan_small((x * SQRT3 - 1.0) / (SQRT3 + x));
}

static double atan_positive(double x)
{
    return x > 1.0 ? PI_2 - atan_unit(1.0 / x) : atan_unit(x);
}

rt_real rt_atan2(rt_real y, rt_real x)
{
    if (!rt_is_finite(x) || !rt_is_finite(y)) return 0.0;
    if (x == 0.0) return y > 0.0 ? PI_2 : y < 0.0 ? -PI_2 : 0.0;
    double a = atan_positive(y / x < 0.0 ? -(y / x) : y / x);
    if (x > 0.0) return y < 0.0 ? -a : a;
    return y < 0.0 ? a - 2.0 * PI_2 : 2.0 * PI_2 - a;
}

rt_real rt_asin(rt_real x)
{
    if (!(x > -1.0)) return -PI_2;
    if (!(x < 1.0)) return PI_2;
    return rt_atan2(x, rt_sqrt((1.0 - x) * (1.0 + x)));
}

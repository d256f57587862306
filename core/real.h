/* The one scalar type of the kernel. Every algorithm does its arithmetic through
 * the operations below, so the same source builds as IEEE double (default) or as
 * signed 64-bit fixed point (RT_REAL_FIXED). Comparisons (<, ==, ...) work directly
 * on rt_real in both builds; + - * / do not: use rt_add and friends. */
#ifndef RT_REAL_H
#define RT_REAL_H

#include <stdbool.h>
#include <stdint.h>

#if defined(RT_REAL_FIXED)
#include "real_fixed.h"
#else
#include "real_double.h"
#endif

static inline rt_real rt_min(rt_real a, rt_real b) { return a < b ? a : b; }
static inline rt_real rt_max(rt_real a, rt_real b) { return a > b ? a : b; }
static inline rt_real rt_clamp(rt_real x, rt_real lo, rt_real hi) { return rt_min(rt_max(x, lo), hi); }
static inline rt_real rt_abs(rt_real a) { return a < RT_ZERO ? rt_neg(a) : a; }
/* |a| for comparisons (and sums and products that are only compared): in the double
 * build the sign bit cleared, one instruction instead of rt_abs's choice, which gives +0
 * where rt_abs keeps -0; no comparison tells the two apart. */
#ifdef RT_REAL_FIXED
static inline rt_real rt_magnitude(rt_real a) { return rt_abs(a); }
#else
static inline rt_real rt_magnitude(rt_real a) { return __builtin_fabs(a); }
#endif

/* Elementary functions, implemented by the backend without libm (see docs/determinism.md). */
rt_real rt_sin(rt_real radians);
rt_real rt_cos(rt_real radians);
rt_real rt_tan(rt_real radians);
rt_real rt_exp(rt_real x);
rt_real rt_log(rt_real x);               /* x > 0 */
rt_real rt_pow(rt_real base, rt_real e); /* base >= 0; pow(0, e > 0) = 0 */
rt_real rt_atan2(rt_real y, rt_real x);  /* in [-pi, pi]; atan2(0, 0) = 0 */
rt_real rt_asin(rt_real x);              /* x in [-1, 1] */

#endif

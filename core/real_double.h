/* rt_real as IEEE-754 binary64. Determinism rests on: no FMA contraction
 * (-ffp-contract=off), SSE2/NEON arithmetic (no x87 excess precision), and sqrt
 * being correctly rounded by IEEE-754. Included only through real.h. */
#ifndef RT_REAL_DOUBLE_H
#define RT_REAL_DOUBLE_H

typedef double rt_real;
_Static_assert(sizeof(rt_real) == 8, "the double build needs IEEE binary64");

#define RT_REAL_NAME "double"
/* A compile-time constant from a decimal literal. */
#define RT_C(x) ((rt_real)(x))
#define RT_ZERO RT_C(0.0)
#define RT_ONE RT_C(1.0)
#define RT_PI RT_C(3.14159265358979323846)
/* Largest finite value: "no hit yet" distances start here. */
#define RT_REAL_MAX RT_C(1.7976931348623157e308)
/* How far from the origin triangles are traced: the watertight test forms products of
 * three coordinates relative to the ray origin (t's numerator, about 333 R^3 for points
 * and origins within R), finite up to R = 8e101. Scenes with triangles keep every
 * object and the camera's ray origins within it (core/scene_build.c). */
#define RT_TRIANGLE_RANGE RT_C(1e100)
#define RT_TRIANGLE_RANGE_TEXT "1e100"

static inline rt_real rt_add(rt_real a, rt_real b) { return a + b; }
static inline rt_real rt_sub(rt_real a, rt_real b) { return a - b; }
static inline rt_real rt_mul(rt_real a, rt_real b) { return a * b; }
/* The fixed build's forms for bounded operands (real_fixed.h): the same operations here. */
static inline rt_real rt_add_unsaturated(rt_real a, rt_real b) { return a + b; }
static inline rt_real rt_sub_unsaturated(rt_real a, rt_real b) { return a - b; }
static inline rt_real rt_mul_unsaturated(rt_real a, rt_real b) { return a * b; }
static inline rt_real rt_div(rt_real a, rt_real b) { return a / b; }
/* (a0 b0 + a1 b1 + a2 b2) / d, rounded step by step left to right. */
static inline rt_real rt_dot3_div(rt_real a0, rt_real b0, rt_real a1, rt_real b1, rt_real a2, rt_real b2, rt_real d)
{
    return (a0 * b0 + a1 * b1 + a2 * b2) / d;
}
static inline rt_real rt_neg(rt_real a) { return -a; }
static inline rt_real rt_half(rt_real a) { return a * 0.5; }
/* rt_mul(a, 16) and rt_mul(a, 1/16). */
static inline rt_real rt_times16(rt_real a) { return a * 16.0; }
static inline rt_real rt_over16(rt_real a) { return a * 0.0625; }
static inline rt_real rt_from_int(int64_t i) { return (rt_real)i; }
static inline rt_real rt_sqrt(rt_real a) { return a > 0.0 ? __builtin_sqrt(a) : 0.0; }
/* sqrt(a * b); 0 when the product is not positive. */
static inline rt_real rt_sqrt_mul(rt_real a, rt_real b) { return rt_sqrt(a * b); }

/* A BVH box coordinate in four bytes: a float rounded outwards, so the stored box holds
 * the exact one. `grid` is the fixed build's (rt_bound_grid); floats need none. */
typedef float rt_bound;
#define RT_FLOAT_MAX 3.4028234663852886e38
static inline int rt_bound_grid(rt_real max_abs) { return (void)max_abs, 0; }
/* The float next to f (finite) towards +infinity (up) or -infinity. */
static inline float rt_float_step(float f, bool up)
{
    if (f == 0.0f) return up ? 0x1p-149f : -0x1p-149f;
    union {
        float f;
        uint32_t u;
    } b = {f};
    b.u = (f > 0.0f) == up ? b.u + 1 : b.u - 1;
    return b.f;
}
static inline rt_bound rt_bound_below(rt_real x, int grid)
{
    (void)grid;
    if (x >= RT_FLOAT_MAX) return (float)RT_FLOAT_MAX;
    if (x < -RT_FLOAT_MAX) return -__builtin_inff();
    float f = (float)x;
    return (double)f > x ? rt_float_step(f, false) : f;
}
static inline rt_bound rt_bound_above(rt_real x, int grid)
{
    (void)grid;
    if (x <= -RT_FLOAT_MAX) return (float)-RT_FLOAT_MAX;
    if (x > RT_FLOAT_MAX) return __builtin_inff();
    float f = (float)x;
    return (double)f < x ? rt_float_step(f, true) : f;
}
static inline rt_real rt_bound_value(rt_bound b, int grid) { return (void)grid, (double)b; }

/* Largest integer <= a, saturated to the int32 range. */
static inline int32_t rt_floor_int(rt_real a)
{
    if (!(a > -2147483648.0)) return INT32_MIN; /* also NaN */
    if (a >= 2147483647.0) return INT32_MAX;
    int32_t i = (int32_t)a;
    return (rt_real)i > a ? i - 1 : i;
}

/* Largest integer <= a, for 0 <= a < 2^31 only (a conversion that truncates). */
static inline int32_t rt_floor_nonneg(rt_real a) { return (int32_t)a; }

/* True when a is neither NaN nor infinite. */
static inline bool rt_is_finite(rt_real a) { return a - a == 0.0; }

/* The sample solution's final quantisation: (uint8)(255.0f * (float)c), c in [0,1]. */
static inline uint8_t rt_unit_to_byte(rt_real c)
{
    float f = (float)c * 255.0f;
    return (uint8_t)f;
}

/* The value's 64 bits, for blobs (core/blob.c); exact in both directions. */
static inline uint64_t rt_real_to_bits(rt_real a)
{
    union {
        double d;
        uint64_t u;
    } c;
    c.d = a;
    return c.u;
}
static inline rt_real rt_real_from_bits(uint64_t bits)
{
    union {
        double d;
        uint64_t u;
    } c;
    c.u = bits;
    return c.d;
}

/* Host-side conversion for loaders and tests; never called by the core. */
static inline rt_real rt_from_double(double d) { return d; }
static inline double rt_to_double(rt_real a) { return a; }

#endif

/* rt_real as signed 64-bit fixed point, Q32.32: value = raw / 2^32, so the range is
 * about +-2.1e9 (scene coordinates up to 1e4, squared distances up to 1e8 and more)
 * with a resolution of 2^-32 = 2.3e-10. Every operation rounds to nearest (halves away
 * from zero, so negation commutes with rounding) and saturates at +-RT_REAL_MAX
 * instead of wrapping; nothing here is undefined behaviour, and nothing uses the FPU
 * except the two host conversions at the end. See docs/fixed-point.md.
 * Included only through real.h. */
#ifndef RT_REAL_FIXED_H
#define RT_REAL_FIXED_H

typedef int64_t rt_real;
_Static_assert(sizeof(rt_real) == 8, "Q32.32 needs a 64-bit integer");

#define RT_REAL_NAME "fixed"
/* A compile-time constant from a decimal literal: round(x * 2^32), saturated. It folds
 * to an integer at compile time, so no floating-point instruction is emitted. */
#define RT_C(x)                                    \
    ((rt_real)((x) >= 2147483648.0    ? INT64_MAX  \
               : (x) <= -2147483648.0 ? -INT64_MAX \
                                      : (int64_t)((x)*4294967296.0 + ((x) < 0 ? -0.5 : 0.5))))
#define RT_ZERO ((rt_real)0)
#define RT_ONE ((rt_real)INT64_C(0x100000000))
#define RT_PI RT_C(3.14159265358979323846)
/* The saturation rail (about 2^31): "no hit yet" distances start here. The range is
 * symmetric, [-RT_REAL_MAX, RT_REAL_MAX]; INT64_MIN is never produced. */
#define RT_REAL_MAX ((rt_real)INT64_MAX)
/* How far from the origin triangles are traced (see real_double.h): the determinant
 * u + v + w, up to 96 R^2 for points and ray origins within R, stays below the rail
 * for R < 4729. */
#define RT_TRIANGLE_RANGE RT_C(4096.0)
#define RT_TRIANGLE_RANGE_TEXT "4096"

/* a * b as 128 bits: the high half is returned, the low half stored in *lo. */
static inline uint64_t rt_fx_umul128(uint64_t a, uint64_t b, uint64_t *lo)
{
#if defined(__SIZEOF_INT128__) && !defined(RT_FIXED_PORTABLE)
    unsigned __int128 p = (unsigned __int128)a * b;
    *lo = (uint64_t)p;
    return (uint64_t)(p >> 64);
#else /* 32-bit targets (i686, arm): schoolbook on 32-bit halves, same result */
    uint64_t a0 = (uint32_t)a, a1 = a >> 32, b0 = (uint32_t)b, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (uint32_t)p01 + (uint32_t)p10; /* < 3 * 2^32 */
    *lo = mid << 32 | (uint32_t)p00;
    return p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/* round(a * b / 2^shift) for 1 <= shift <= 64, halves up; UINT64_MAX when it does not fit. */
static inline uint64_t rt_fx_umulshift(uint64_t a, uint64_t b, unsigned shift)
{
    uint64_t lo, hi = rt_fx_umul128(a, b, &lo);
    if (shift < 64 && hi >> shift) return UINT64_MAX;
    uint64_t q = shift == 64 ? hi : hi << (64 - shift) | lo >> shift;
    return q == UINT64_MAX ? UINT64_MAX : q + (lo >> (shift - 1) & 1);
}

/* |a| without overflow (|INT64_MIN| = 2^63). */
static inline uint64_t rt_fx_mag(int64_t a) { return a < 0 ? 0u - (uint64_t)a : (uint64_t)a; }

/* The value with magnitude mag and the given sign, saturated to +-RT_REAL_MAX. */
static inline rt_real rt_fx_signed(uint64_t mag, bool negative)
{
    int64_t m = mag > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)mag;
    return negative ? -m : m;
}

/* The value's 64 bits (two's complement), for blobs (core/blob.c); exact both ways. */
static inline uint64_t rt_real_to_bits(rt_real a) { return (uint64_t)a; }
static inline rt_real rt_real_from_bits(uint64_t bits)
{
    return bits <= INT64_MAX ? (rt_real)bits : -(rt_real)~bits - 1;
}

static inline rt_real rt_add(rt_real a, rt_real b)
{
    rt_real r;
    if (__builtin_add_overflow(a, b, &r)) return a < 0 ? -RT_REAL_MAX : RT_REAL_MAX;
    return r == INT64_MIN ? -RT_REAL_MAX : r;
}

static inline rt_real rt_sub(rt_real a, rt_real b)
{
    rt_real r;
    if (__builtin_sub_overflow(a, b, &r)) return a < 0 ? -RT_REAL_MAX : RT_REAL_MAX;
    return r == INT64_MIN ? -RT_REAL_MAX : r;
}

/* rt_add and rt_sub (and rt_mul_unsaturated below) for a caller that has bounded the
 * operands and the result below 2^31 in magnitude, so that nothing reaches the rails:
 * the same values without the tests. */
static inline rt_real rt_add_unsaturated(rt_real a, rt_real b) { return a + b; }
static inline rt_real rt_sub_unsaturated(rt_real a, rt_real b) { return a - b; }

#if defined(__SIZEOF_INT128__) && !defined(RT_FIXED_PORTABLE)
/* The signed 128-bit product p rounded as in rt_mul and saturated: truncating (p +- 2^31) /
 * 2^32 rounds halves away from zero. */
static inline rt_real rt_fx_mul_rails(__int128 p)
{
    __int128 half = (__int128)1 << 31;
    __int128 q = (p < 0 ? p - half : p + half) / ((__int128)1 << 32);
    return q > INT64_MAX ? RT_REAL_MAX : q < -INT64_MAX ? -RT_REAL_MAX : (rt_real)q;
}

/* A signed 128-bit product p rounded to Q32.32 as rt_mul rounds it, for p / 2^32 below
 * 2^31 in magnitude (no rails): floor((p + 2^31 - [p < 0]) / 2^32), the high 64 bits of
 * p / 2^32 plus the carry out of its low 32 bits, with no branch on the sign. */
__attribute__((always_inline)) static inline rt_real rt_fx_round_product(__int128 p)
{
    unsigned __int128 u = (unsigned __int128)p;
    uint64_t hi = (uint64_t)(u >> 64), lo = (uint64_t)u;
    uint64_t carry = ((lo & UINT32_MAX) + (UINT64_C(1) << 31) - (hi >> 63)) >> 32;
    return rt_real_from_bits((hi << 32 | lo >> 32) + carry);
}

/* p rounded and saturated: the same result as the magnitude form below. */
__attribute__((always_inline)) static inline rt_real rt_fx_round_product_rails(__int128 p)
{
    uint64_t hi = (uint64_t)((unsigned __int128)p >> 64);
    /* The signed high word outside (-2^31, 2^31 - 1): the result may reach the rails. */
    if (hi + ((UINT64_C(1) << 31) - 1) > (UINT64_C(1) << 32) - 3) return rt_fx_mul_rails(p);
    return rt_fx_round_product(p);
}

/* Opaque operands (the empty asm): otherwise gcc may widen an operand shared by several
 * products once, and build each product from three multiplies instead of one imul. */
static inline rt_real rt_mul(rt_real a, rt_real b)
{
    __asm__("" : "+r"(a), "+r"(b));
    return rt_fx_round_product_rails((__int128)a * b);
}

/* rt_mul for operands whose product the caller has bounded below 2^31 (no rails): the
 * same value without the test. */
static inline rt_real rt_mul_unsaturated(rt_real a, rt_real b)
{
    __asm__("" : "+r"(a), "+r"(b));
    return rt_fx_round_product((__int128)a * b);
}

/* rt_sub(rt_mul(a, b), rt_mul(c, d)), or its unsaturated form when the caller has bounded
 * every value below 2^31, and in *sign that of the exact a b - c d: one pair of products. */
__attribute__((always_inline)) static inline rt_real rt_fx_mul_sub(rt_real a, rt_real b, rt_real c, rt_real d,
                                                                   bool bounded, int *sign)
{
    __asm__("" : "+r"(a), "+r"(b), "+r"(c), "+r"(d));
    __int128 p = (__int128)a * b, q = (__int128)c * d;
    *sign = (p > q) - (p < q);
    if (bounded) return rt_sub_unsaturated(rt_fx_round_product(p), rt_fx_round_product(q));
    return rt_sub(rt_fx_round_product_rails(p), rt_fx_round_product_rails(q));
}
#else
static inline rt_real rt_mul(rt_real a, rt_real b)
{
    return rt_fx_signed(rt_fx_umulshift(rt_fx_mag(a), rt_fx_mag(b), 32), (a < 0) != (b < 0));
}
static inline rt_real rt_mul_unsaturated(rt_real a, rt_real b) { return rt_mul(a, b); }
#endif

/* The sign (-1, 0 or 1) of a b - c d, exactly: rt_sub(rt_mul(a, b), rt_mul(c, d)) has
 * that sign or is 0 (rounding and saturation are monotonic), and is 0 for a difference
 * below half an lsb that is not. */
static inline int rt_fx_mul_sub_sign(rt_real a, rt_real b, rt_real c, rt_real d)
{
#if defined(__SIZEOF_INT128__) && !defined(RT_FIXED_PORTABLE)
    __int128 p = (__int128)a * b, q = (__int128)c * d;
    return (p > q) - (p < q);
#else
    uint64_t p_lo, q_lo, p_hi = rt_fx_umul128(rt_fx_mag(a), rt_fx_mag(b), &p_lo);
    uint64_t q_hi = rt_fx_umul128(rt_fx_mag(c), rt_fx_mag(d), &q_lo);
    bool p_neg = ((a < 0) != (b < 0)) && (p_hi | p_lo), q_neg = ((c < 0) != (d < 0)) && (q_hi | q_lo);
    if (p_neg != q_neg) return p_neg ? -1 : 1;
    int larger = p_hi != q_hi ? (p_hi > q_hi ? 1 : -1) : p_lo != q_lo ? (p_lo > q_lo ? 1 : -1) : 0;
    return p_neg ? -larger : larger; /* magnitudes compare the other way for two negatives */
#endif
}

#if !defined(__SIZEOF_INT128__) || defined(RT_FIXED_PORTABLE)
/* rt_fx_mul_sub's portable form: the same values from the magnitude products. */
__attribute__((always_inline)) static inline rt_real rt_fx_mul_sub(rt_real a, rt_real b, rt_real c, rt_real d,
                                                                   bool bounded, int *sign)
{
    (void)bounded; /* rt_mul_unsaturated is rt_mul here */
    *sign = rt_fx_mul_sub_sign(a, b, c, d);
    return rt_sub(rt_mul(a, b), rt_mul(c, d));
}
#endif

/* round(n * 2^shift / d) for 1 <= shift <= 63 and d > 0, halves up, or UINT64_MAX when that
 * is 2^63 or more. One divq on x86-64, two 64-bit divisions on aarch64, bit-serial elsewhere
 * (no libgcc helper on 32-bit targets); the same bits every way. */
uint64_t rt_fx_div_round(uint64_t n, unsigned shift, uint64_t d);
/* round(hi:lo / d) for d > 0, halves up, or UINT64_MAX when that is 2^63 or more. */
uint64_t rt_fx_div128_round(uint64_t hi, uint64_t lo, uint64_t d);

/* Rounded to nearest; x / 0 saturates to +-RT_REAL_MAX by the sign of x, and 0 / 0 = 0. */
rt_real rt_div(rt_real a, rt_real b);
/* (a0 b0 + a1 b1 + a2 b2) / d rounded once from the exact 128-bit sum, which may pass the
 * Q32.32 range when the quotient does not (a triangle's t far from the origin). */
rt_real rt_dot3_div(rt_real a0, rt_real b0, rt_real a1, rt_real b1, rt_real a2, rt_real b2, rt_real d);

static inline rt_real rt_neg(rt_real a) { return a == INT64_MIN ? RT_REAL_MAX : -a; }

/* rt_mul(a, RT_C(0.5)) without the product: a / 2 rounded half away from zero. */
static inline rt_real rt_half(rt_real a) { return a / 2 + a % 2; }
/* rt_mul(a, 16), exact or on the rails, and rt_mul(a, 1/16), halves away from zero,
 * without a multiply. */
static inline rt_real rt_times16(rt_real a)
{
    const rt_real most = RT_REAL_MAX / 16;
    return a > most ? RT_REAL_MAX : a < -most ? -RT_REAL_MAX : a * 16;
}
static inline rt_real rt_over16(rt_real a) { return a / 16 + (a % 16 >= 8) - (a % 16 <= -8); }

static inline rt_real rt_from_int(int64_t i)
{
    if (i > INT32_MAX) return RT_REAL_MAX;
    if (i <= INT32_MIN) return -RT_REAL_MAX; /* -2^31 itself is one unit beyond the rail */
    return i * INT64_C(0x100000000);
}

/* Correctly rounded square root; 0 for a <= 0 (as in the double build). */
rt_real rt_sqrt(rt_real a);
/* sqrt(a * b) correctly rounded from the exact 128-bit product, so a small product keeps
 * its significant bits (rt_sqrt(rt_mul(a, b)) would round it to 2^-32 first); 0 when a or
 * b is not positive. */
rt_real rt_sqrt_mul(rt_real a, rt_real b);

/* A BVH box coordinate in four bytes: the value in units of 2^grid lsb (2^(grid - 32)),
 * rounded outwards, so the stored box holds the exact one. A scene's grid is the
 * smallest that keeps its largest coordinate below 2^31 - 2 units: 2^-27 for a scene
 * within +-32, 2^-16 within +-32768. */
typedef int32_t rt_bound;
static inline int rt_bound_grid(rt_real max_abs)
{
    uint64_t m = rt_fx_mag(max_abs);
    int grid = 0;
    while (grid < 32 && m >> grid >= (UINT64_C(1) << 31) - 2) grid++;
    return grid;
}
static inline rt_bound rt_fx_bound(int64_t units)
{
    return units > INT32_MAX ? INT32_MAX : units < -INT32_MAX ? -INT32_MAX : (rt_bound)units;
}
/* floor and ceil of x / 2^grid by shifts of the magnitude (no signed right shift). */
static inline rt_bound rt_bound_below(rt_real x, int grid)
{
    uint64_t m = rt_fx_mag(x), q = m >> grid, up = q + ((m & ((UINT64_C(1) << grid) - 1)) != 0);
    return rt_fx_bound(x < 0 ? -(int64_t)up : (int64_t)q);
}
static inline rt_bound rt_bound_above(rt_real x, int grid)
{
    uint64_t m = rt_fx_mag(x), q = m >> grid, up = q + ((m & ((UINT64_C(1) << grid) - 1)) != 0);
    return rt_fx_bound(x < 0 ? -(int64_t)q : (int64_t)up);
}
static inline rt_real rt_bound_value(rt_bound b, int grid) { return (rt_real)b * ((rt_real)1 << grid); }

/* Largest integer <= a (the high word); always within the int32 range. */
static inline int32_t rt_floor_int(rt_real a)
{
    uint32_t hi = (uint32_t)((uint64_t)a >> 32); /* two's complement: floor(a / 2^32) mod 2^32 */
    return hi <= INT32_MAX ? (int32_t)hi : (int32_t)(hi - 2147483648u) - INT32_MAX - 1;
}

/* Largest integer <= a, for 0 <= a < 2^31 only (the high word). */
static inline int32_t rt_floor_nonneg(rt_real a) { return (int32_t)(a >> 32); }

/* True when a is strictly inside the saturation rails (a saturated result means overflow). */
static inline bool rt_is_finite(rt_real a) { return a > -RT_REAL_MAX && a < RT_REAL_MAX; }

/* floor(255 * c + 2^-20) for c in [0, 1], clamped to 0..255 outside. The solution
 * computes (uint8)(255.0f * (float)c), whose float roundings lift a value a few lsb
 * below k/255 (such as 127/255 in Q32.32) to k; the 2^-20 nudge does the same. */
static inline uint8_t rt_unit_to_byte(rt_real c)
{
    if (c <= RT_ZERO) return 0;
    if (c >= RT_ONE) return 255;
    uint64_t scaled = (uint64_t)c * 255u + (UINT64_C(1) << 12);
    return scaled >> 32 >= 255u ? 255 : (uint8_t)(scaled >> 32);
}

/* Host-side conversion for loaders and tests; never called by the core (they are the
 * only floating-point code here). round(d * 2^32), saturated; NaN gives 0. */
static inline rt_real rt_from_double(double d)
{
    if (d != d) return RT_ZERO;
    if (d >= 2147483648.0) return RT_REAL_MAX;
    if (d <= -2147483648.0) return -RT_REAL_MAX;
    double v = d * 4294967296.0; /* exact */
    int64_t i = (int64_t)v;      /* truncated; v - i is exact */
    if (v - (double)i >= 0.5) i++;
    if (v - (double)i <= -0.5) i--;
    return i == INT64_MIN ? -RT_REAL_MAX : i;
}

static inline double rt_to_double(rt_real a) { return (double)a * 0x1p-32; }

#endif

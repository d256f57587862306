/* Elementary functions for rt_real = double, without libm.
 *
 * Only IEEE-754 binary64 + - * / with round-to-nearest are used (no FMA, no long
 * double), in a fixed evaluation order, so every platform computes the same bits.
 * Extra precision comes from double-double ("hi + lo") steps built on the exact
 * error-free transformations two_sum and two_prod (Dekker/Veltkamp, valid without FMA).
 *
 * Each function states the largest error measured against long double libm over
 * about 2 million deterministic samples, backed by the analysis in the comments;
 * tests/test_real.c asserts 1 ulp. Every NaN result is the same quiet NaN, so
 * outputs are identical bits everywhere. Constants were printed by python3 + mpmath (mp.prec = 2000) as the
 * nearest double ("float(v)"), or split as stated at each constant. */
#include "real.h"

static uint64_t bits_of(double d)
{
    union {
        double d;
        uint64_t u;
    } v = {d};
    return v.u;
}

static double from_bits(uint64_t u)
{
    union {
        uint64_t u;
        double d;
    } v = {u};
    return v.d;
}

#define NAN_BITS 0x7ff8000000000000u
#define INF_BITS 0x7ff0000000000000u

/* 2^k for -1022 <= k <= 1023. */
static double pow2(int k) { return from_bits((uint64_t)(k + 1023) << 52); }

/* Nearest integer (halves away from zero) for |v| < 2^31. */
static int round_int(double v) { return (int)(v < 0.0 ? v - 0.5 : v + 0.5); }

/* s + e == a + b exactly (Knuth's TwoSum, any magnitudes). */
static void two_sum(double a, double b, double *s, double *e)
{
    double sum = a + b;
    double bb = sum - a;
    *e = (a - (sum - bb)) + (b - bb);
    *s = sum;
}

/* Splits a into hi + lo with 26-bit halves (Veltkamp); |a| < 2^995. */
static void split(double a, double *hi, double *lo)
{
    double c = 134217729.0 * a; /* 2^27 + 1 */
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* p + e == a * b exactly (Dekker), barring overflow and underflow. */
static void two_prod(double a, double b, double *p, double *e)
{
    double ah, al, bh, bl;
    split(a, &ah, &al);
    split(b, &bh, &bl);
    *p = a * b;
    *e = ((ah * bh - *p) + ah * bl + al * bh) + al * bl;
}

/* ---- sin, cos, tan ---------------------------------------------------------- */

/* pi/2 = P1 + P2 + P3 to 2^-130: P1 and P2 are rounded to 36 bits so n*P1 and n*P2
 * are exact for |n| < 2^17. */
#define INV_PIO2 0.6366197723675814
#define PIO2_P1 0x1.921fb5444p+0
#define PIO2_P2 0x1.68c234c4cp-39
#define PIO2_P3 0x1.98a2e03707345p-77
/* pi/2 = PIO2_HI + PIO2_LO to 2^-107. */
#define PIO2_HI 1.5707963267948966
#define PIO2_LO 6.123233995736766e-17

/* Bits of 2/pi, 32 per word, most significant first: word k = floor(2/pi * 2^(32k+32)) mod 2^32. */
static const uint32_t two_over_pi[38] = {
    0xa2f9836e, 0x4e441529, 0xfc2757d1, 0xf534ddc0, 0xdb629599, 0x3c439041, 0xfe5163ab, 0xdebbc561,
    0xb7246e3a, 0x424dd2e0, 0x06492eea, 0x09d1921c, 0xfe1deb1c, 0xb129a73e, 0xe88235f5, 0x2ebb4484,
    0xe99c7026, 0xb45f7e41, 0x3991d639, 0x835339f4, 0x9c845f8b, 0xbdf9283b, 0x1ff897ff, 0xde05980f,
    0xef2f118b, 0x5a0a6d1f, 0x6d367ecf, 0x27cb09b7, 0x4f463f66, 0x9e5fea2d, 0x7527bac7, 0xebe5f17b,
    0x3d0739f7, 0x8a5292ea, 0x6bfb5fb1, 0x1f8d5d08, 0x56033046, 0xfc7b6bab,
};

/* Bits pos .. pos+63 of the little-endian multiword number p. */
static uint64_t bits_at(const uint32_t *p, int pos)
{
    int w = pos >> 5, b = pos & 31;
    uint64_t v = p[w] | (uint64_t)p[w + 1] << 32;
    return b ? v >> b | (uint64_t)p[w + 2] << (64 - b) : v;
}

/* Payne-Hanek reduction for finite |x| >= 2^17: x*2/pi is computed exactly enough in
 * integers (53-bit mantissa times a 256-bit window of 2/pi, the bits above the window
 * only add multiples of 4), keeping 2 quadrant bits and a 128-bit fraction. */
static unsigned reduce_large(double x, double *hi, double *lo)
{
    uint64_t u = bits_of(x);
    int e = (int)(u >> 52 & 0x7ff) - 1075; /* |x| = m * 2^e */
    uint64_t m = (u & 0xfffffffffffffu) | 1ull << 52;
    int k0 = e >= 34 ? (e - 34) / 32 + 1 : 0; /* words before k0 contribute multiples of 4 */
    int sh = 256 + 32 * k0 - e;               /* y mod 4 = (m * window) / 2^sh, 223 <= sh <= 291 */
    uint32_t p[12] = {0};
    for (int i = 0; i < 8; i++) {
        uint64_t w = two_over_pi[k0 + 7 - i];
        uint64_t t = p[i] + w * (uint32_t)m;
        p[i] = (uint32_t)t;
        t = p[i + 1] + w * (m >> 32) + (t >> 32);
        p[i + 1] = (uint32_t)t;
        p[i + 2] = (uint32_t)(t >> 32);
    }
    unsigned q = (unsigned)bits_at(p, sh) & 3;
    uint64_t a = bits_at(p, sh - 64), b = bits_at(p, sh - 128); /* fraction = (a:b) / 2^128 */
    bool neg = a >> 63;
    if (neg) { /* fraction >= 1/2: use fraction - 1, one quadrant up */
        a = ~a + (b == 0);
        b = -b;
        q++;
    }
    int lead = 0;
    for (; lead < 128 && !(a >> 63); lead++) {
        a = a << 1 | b >> 63;
        b <<= 1;
    }
    /* 53 + 32 leading bits of the fraction as fh + fl (conversions of < 2^53 are exact). */
    double fh = (double)(int64_t)(a >> 11) * pow2(-53 - lead);
    double fl = (double)(int64_t)((a & 0x7ff) << 21 | b >> 43) * pow2(-85 - lead);
    double ph, pl;
    two_prod(fh, PIO2_HI, &ph, &pl);
    two_sum(ph, pl + (fh * PIO2_LO + fl * PIO2_HI), hi, lo);
    if (neg) {
        *hi = -*hi;
        *lo = -*lo;
    }
    if (x < 0.0) {
        *hi = -*hi;
        *lo = -*lo;
        q = 0u - q;
    }
    return q & 3;
}

/* x = n*pi/2 + hi + lo with |hi| <= pi/4 (+ a rounding), returns n mod 4; x finite.
 * |x| < 2^17: Cody-Waite with the 3-part pi/2; n*P1, n*P2 and both subtractions are
 * exact, so hi + lo is off by at most n*2^-129 + 2^-112 <= 2^-111. Continued fractions
 * of pi/2 * 2^(52-E) show no double below 2^17 lies closer than 2^-60.5 to a nonzero
 * multiple of pi/2, so the reduced argument keeps a relative error below 2^-63.
 * Larger |x| goes through reduce_large, which is as accurate for every finite double. */
static unsigned reduce(double x, double *hi, double *lo)
{
    if (!(x < 0x1p17 && x > -0x1p17)) return reduce_large(x, hi, lo);
    double n = round_int(x * INV_PIO2);
    double a, e;
    two_sum(x - n * PIO2_P1, -(n * PIO2_P2), &a, &e);
    two_sum(a, e - n * PIO2_P3, hi, lo);
    return (unsigned)(int)n & 3;
}

/* sin(hi + lo) = result + *err, |hi| <= pi/4. Taylor series to x^17 (coefficients
 * (-1)^k/(2k+1)! rounded to double); the first omitted term is below 2^-63 relative. */
static double sin_kernel(double hi, double lo, double *err)
{
    double z = hi * hi;
    /* clang-format off */
    double p = -0.16666666666666666 +
        z * (0.008333333333333333 +
        z * (-0.0001984126984126984 +
        z * (2.7557319223985893e-06 +
        z * (-2.505210838544172e-08 +
        z * (1.6059043836821613e-10 +
        z * (-7.647163731819816e-13 +
        z * 2.8114572543455206e-15))))));
    /* clang-format on */
    /* sin(hi + lo) ~ sin(hi) + lo * cos(hi), and cos(hi) ~ 1 - z/2 to the needed precision. */
    double tail = hi * z * p + lo * (1.0 - 0.5 * z);
    double s = hi + tail;
    *err = (hi - s) + tail;
    return s;
}

/* cos(hi + lo) = result + *err, |hi| <= pi/4. Taylor series to x^16 (coefficients
 * (-1)^k/(2k)!); 1 - hi^2/2 is formed exactly so only the small tail is rounded. */
static double cos_kernel(double hi, double lo, double *err)
{
    double z, zl;
    two_prod(hi, hi, &z, &zl);
    /* clang-format off */
    double p = 0.041666666666666664 +
        z * (-0.001388888888888889 +
        z * (2.48015873015873e-05 +
        z * (-2.755731922398589e-07 +
        z * (2.08767569878681e-09 +
        z * (-1.1470745597729725e-11 +
        z * 4.779477332387385e-14)))));
    /* clang-format on */
    double hz = 0.5 * z;
    double w = 1.0 - hz;
    /* ((1 - w) - hz) is the exact rounding error of w; -hi*lo is the first-order term in lo. */
    double tail = (((1.0 - w) - hz) - 0.5 * zl) + (z * z * p - hi * lo);
    double c = w + tail;
    *err = (w - c) + tail;
    return c;
}

/* Handles what the kernels must not see: NaN/Inf give NaN, tiny |x| is its own answer
 * (then x^3/6 is below half an ulp). Returns true when *out is the result. */
static bool trig_special(double x, double tiny_result, double *out)
{
    if (x - x != 0.0) {
        *out = from_bits(NAN_BITS);
        return true;
    }
    if (x < 0x1p-27 && x > -0x1p-27) {
        *out = tiny_result;
        return true;
    }
    return false;
}

/* Max error 0.76 ulp measured on [-1e4, 1e4], 0.78 ulp for |x| up to 2^1023
 * (the reduction is accurate for every finite x). */
rt_real rt_sin(rt_real x)
{
    double out, hi, lo, err;
    if (trig_special(x, x, &out)) return out;
    unsigned q = reduce(x, &hi, &lo);
    double r = q & 1 ? cos_kernel(hi, lo, &err) : sin_kernel(hi, lo, &err);
    return q & 2 ? -r : r;
}

/* Max error 0.78 ulp measured on [-1e4, 1e4] and beyond. */
rt_real rt_cos(rt_real x)
{
    double out, hi, lo, err;
    if (trig_special(x, 1.0, &out)) return out;
    unsigned q = reduce(x, &hi, &lo);
    double r = q & 1 ? sin_kernel(hi, lo, &err) : cos_kernel(hi, lo, &err);
    return (q + 1) & 2 ? -r : r;
}

/* sin/cos of the reduced argument, each carried as hi + lo, divided with one
 * correction step. Max error 0.85 ulp measured on [-1e4, 1e4] (the doubles nearest
 * the poles included), 0.91 ulp for |x| up to 2^1023. */
rt_real rt_tan(rt_real x)
{
    double out, hi, lo, sl, cl;
    if (trig_special(x, x, &out)) return out;
    unsigned q = reduce(x, &hi, &lo);
    double sh = sin_kernel(hi, lo, &sl), ch = cos_kernel(hi, lo, &cl);
    double nh = sh, nl = sl, dh = ch, dl = cl; /* tan = s/c, or -c/s in odd quadrants */
    if (q & 1) {
        nh = -ch;
        nl = -cl;
        dh = sh;
        dl = sl;
    }
    double t = nh / dh, p, pe;
    two_prod(t, dh, &p, &pe);
    return t + ((((nh - p) - pe) + nl) - t * dl) / dh;
}

/* ---- exp, log, pow ---------------------------------------------------------- */

#define INV_LN2 1.4426950408889634
/* ln 2 = LN2_HI + LN2_LO to 2^-102; LN2_HI has 42 bits so k*LN2_HI is exact for |k| < 2^11. */
#define LN2_HI 0x1.62e42fefa38p-1
#define LN2_LO 5.497923018708371e-14

/* x * 2^k with a single rounding (only the final step can go subnormal or overflow). */
static double scale2(double x, int k)
{
    if (k > 1000) return x * pow2(1000) * pow2(k - 1000);
    if (k < -1000) return x * pow2(k + 1000) * pow2(-1000);
    return x * pow2(k);
}

/* exp(hi + lo), |lo| <= ulp(hi). x = k ln2 + r with |r| <= ln2/2 (+ a rounding), r
 * carried as a + b; exp(r) by Taylor series to r^13 (coefficients 1/n!; the first
 * omitted term is below 2^-57 relative). */
static double exp_dd(double hi, double lo)
{
    if (hi != hi) return from_bits(NAN_BITS);
    if (hi > 710.0) return from_bits(INF_BITS);
    if (hi < -746.0) return 0.0;
    int k = round_int(hi * INV_LN2);
    double a, b;
    two_sum(hi - k * LN2_HI, lo - k * LN2_LO, &a, &b); /* hi - k*LN2_HI is exact */
    /* clang-format off */
    double q = 0.5 +
        a * (0.16666666666666666 +
        a * (0.041666666666666664 +
        a * (0.008333333333333333 +
        a * (0.001388888888888889 +
        a * (0.0001984126984126984 +
        a * (2.48015873015873e-05 +
        a * (2.7557319223985893e-06 +
        a * (2.755731922398589e-07 +
        a * (2.505210838544172e-08 +
        a * (2.08767569878681e-09 +
        a * 1.6059043836821613e-10))))))))));
    /* clang-format on */
    /* exp(a + b) ~ 1 + a + a^2 q(a) + b (1 + a) */
    double y = 1.0 + (a + (a * a * q + b * (1.0 + a)));
    return scale2(y, k);
}

/* Max error 0.83 ulp measured over [-745, 709.78] (subnormal results in subnormal ulps);
 * exp(x > 709.78) = inf, exp(x < -745.13) = 0, exp(NaN) = NaN. */
rt_real rt_exp(rt_real x) { return exp_dd(x, 0.0); }

/* log(j/32), j = 23..45, as hi + lo. */
static const double log_table[23][2] = {
    {-0.33024168687057687, 1.0828321637483858e-17}, {-0.2876820724517809, -2.607160616442564e-17},
    {-0.24686007793152578, -1.361743371748368e-17}, {-0.2076393647782445, -1.2053243216686129e-17},
    {-0.16989903679539747, 4.868008764439071e-19},  {-0.13353139262452263, 3.664457663660085e-18},
    {-0.09844007281325252, 4.439009633675136e-18},  {-0.06453852113757118, 6.470486661692933e-18},
    {-0.0317486983145803, -3.0382263084680858e-18}, {0.0, 0.0},
    {0.030771658666753687, 1.0431732029005968e-18}, {0.06062462181643484, 2.6424025938726934e-18},
    {0.08961215868968714, -5.4268129336647135e-18}, {0.11778303565638346, -1.1971685747593677e-18},
    {0.1451820098444979, 8.242418783022475e-18},    {0.17185025692665923, -6.0224538210113705e-18},
    {0.19782574332991987, 1.2821194372980142e-17},  {0.22314355131420976, -9.091270597324799e-18},
    {0.24783616390458127, -1.2432209578702523e-17}, {0.27193371548364176, 7.83319637697442e-19},
    {0.2954642128938359, -2.16461086040599e-17},    {0.3184537311185346, 2.7114779367326236e-17},
    {0.3409265869705932, 1.7467136443544747e-17},
};

/* log(x) = result + *lo for finite x > 0, to about 2^-68 relative (pow needs far more
 * than double precision). x = 2^k m with m in [sqrt(1/2), sqrt(2)], c = j/32 nearest
 * to m, s = (m - c)/(m + c) (|s| < 0.0112) as a double-double, and
 * log(m) = log(c) + 2 atanh(s) = log(c) + 2s + 2s^3/3 + ... + 2s^9/9 (coefficients
 * 2/(2i+1)); the first omitted term is below 2^-68 relative. */
static double log_dd(double x, double *lo)
{
    int k = 0;
    if (x < 0x1p-1022) { /* subnormal: make it normal */
        x *= 0x1p54;
        k = -54;
    }
    uint64_t u = bits_of(x);
    k += (int)(u >> 52) - 1023;
    double m = from_bits((u & 0xfffffffffffffu) | 0x3ff0000000000000u); /* [1, 2) */
    if (m > 1.4142135623730951) {
        m *= 0.5;
        k++;
    }
    int j = round_int(m * 32.0);
    double c = j * 0x1p-5;
    double num = m - c; /* exact: |num| <= 1/64 and m, c are multiples of 2^-53 */
    double den = 2.0 * c + num, den_lo = num - (den - 2.0 * c); /* m + c exactly */
    double sh = num / den, p, pe;
    two_prod(sh, den, &p, &pe);
    double sl = (((num - p) - pe) - sh * den_lo) / den;
    double z = sh * sh;
    double tail = sh * z * (0.6666666666666666 + z * (0.4 + z * (0.2857142857142857 + z * 0.2222222222222222)));
    double h1, e1, h2, e2;
    two_sum(k * LN2_HI, log_table[j - 23][0], &h1, &e1);
    two_sum(h1, 2.0 * sh, &h2, &e2);
    double l = (e1 + e2) + (((k * LN2_LO + log_table[j - 23][1]) + 2.0 * sl) + tail);
    double r = h2 + l;
    *lo = (h2 - r) + l;
    return r;
}

/* Max error 0.50 ulp measured over all positive doubles (nearly correctly rounded).
 * log(0) = -inf, log(x < 0) = NaN, log(inf) = inf. */
rt_real rt_log(rt_real x)
{
    double lo;
    if (x != x || x < 0.0) return from_bits(NAN_BITS);
    if (x == 0.0) return -from_bits(INF_BITS);
    if (x - x != 0.0) return x; /* +inf */
    return log_dd(x, &lo);
}

/* exp(e * log(base)) with the product formed as a double-double, so the result stays
 * within about 1 ulp even when |e log(base)| is large. Max error 0.83 ulp measured for
 * base in (0, 1], e in [0, 1000]. Defined cases: pow(x, 0) = 1 (also 0^0 and NaN^0),
 * pow(0, e > 0) = 0, pow(0, e < 0) = inf, pow(1, e) = 1; base < 0 or a NaN gives NaN. */
rt_real rt_pow(rt_real base, rt_real e)
{
    if (e == 0.0 || base == 1.0) return 1.0;
    if (base != base || e != e || base < 0.0) return from_bits(NAN_BITS);
    if (base == 0.0) return e > 0.0 ? 0.0 : from_bits(INF_BITS);
    if (base - base != 0.0) return e > 0.0 ? base : 0.0; /* base = +inf */
    if (e - e != 0.0) return (base < 1.0) == (e > 0.0) ? 0.0 : from_bits(INF_BITS);
    double lh, ll, ph, pl;
    lh = log_dd(base, &ll);
    ph = e * lh;
    if (ph > 710.0) return from_bits(INF_BITS);
    if (ph < -746.0) return 0.0; /* also keeps two_prod's operands far from overflow */
    two_prod(e, lh, &ph, &pl);
    return exp_dd(ph, pl + e * ll);
}

/* Division, square root and the elementary functions for the Q32.32 build, in integer
 * arithmetic only (the core compiles with -mgeneral-regs-only here).
 *
 * The kernels work in Q62 (signed, value = raw / 2^62, |value| < 2), thirty bits
 * finer than the output, so each result is within half an lsb (2^-33) plus a few 2^-58
 * of the exact value (tan near its poles excepted); exp and pow results above 1 keep
 * about 2^-59 relative accuracy.
 * Bounds are stated per function, measured by tests/test_real_fixed.c against long
 * double libm. Constants are round(v * 2^62) (or the power stated), printed by
 * python3 + mpmath at 1000 bits; the series are Taylor series whose coefficients are
 * exact fractions (1/n!, 1/(2k+1)) rounded the same way. */
#include "real.h"

#define Q62_ONE (INT64_C(1) << 62)

/* round(a * b / 2^shift) for a result that fits (all kernel operands stay below 2). */
static int64_t mulq(int64_t a, int64_t b, unsigned shift)
{
    return rt_fx_signed(rt_fx_umulshift(rt_fx_mag(a), rt_fx_mag(b), shift), (a < 0) != (b < 0));
}

/* round(v / 2^shift), halves away from zero, 1 <= shift <= 63. */
static int64_t shift_round(int64_t v, unsigned shift)
{
    uint64_t m = rt_fx_mag(v);
    return rt_fx_signed((m >> shift) + (m >> (shift - 1) & 1), v < 0);
}

/* The two's complement reading of u, without implementation-defined conversion. */
static int64_t to_signed(uint64_t u) { return u <= INT64_MAX ? (int64_t)u : -(int64_t)~u - 1; }

/* Three ways to the same quotient: one x86-64 divq; on aarch64 two 64-bit hardware divisions;
 * elsewhere (i686, arm: 64-bit division would be a libgcc call) one bit at a time.
 * tests/test_real_fixed.c checks them against the exact quotient (-DRT_FIXED_PORTABLE forces
 * the last one on any host; the aarch64 one was checked the same way under qemu-aarch64). */
#if defined(__x86_64__) && !defined(RT_FIXED_PORTABLE)
/* hi:lo / d for hi < d (otherwise divq faults). */
static uint64_t udiv128(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem)
{
    uint64_t q;
    __asm__("divq %4" : "=a"(q), "=d"(*rem) : "a"(lo), "d"(hi), "rm"(d));
    return q;
}
#elif defined(__aarch64__) && !defined(RT_FIXED_PORTABLE)
/* hi:lo / d for hi < d, from two 64-by-32-bit quotient digits (Knuth's algorithm D with
 * base 2^32, as in Hacker's Delight divlu): hardware 64-bit division, no libgcc helper. */
static uint64_t udiv128(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem)
{
    const uint64_t base = UINT64_C(1) << 32;
    int s = __builtin_clzll(d);
    d <<= s; /* normalised: the top digit of d is at least base / 2, so each estimate is at most 2 over */
    uint64_t d1 = d >> 32, d0 = (uint32_t)d;
    uint64_t n32 = s ? hi << s | lo >> (64 - s) : hi, n10 = lo << s;
    uint64_t n1 = n10 >> 32, n0 = (uint32_t)n10;
    uint64_t q1 = n32 / d1, rhat = n32 - q1 * d1;
    while (q1 >= base || q1 * d0 > (rhat << 32 | n1)) {
        q1--;
        rhat += d1;
        if (rhat >= base) break;
    }
    uint64_t n21 = (n32 << 32 | n1) - q1 * d; /* the partial remainder, below d: wraps to it exactly */
    uint64_t q0 = n21 / d1;
    rhat = n21 - q0 * d1;
    while (q0 >= base || q0 * d0 > (rhat << 32 | n0)) {
        q0--;
        rhat += d1;
        if (rhat >= base) break;
    }
    *rem = ((n21 << 32 | n0) - q0 * d) >> s;
    return q1 << 32 | q0;
}
#endif

#if (defined(__x86_64__) || defined(__aarch64__)) && !defined(RT_FIXED_PORTABLE)
uint64_t rt_fx_div128_round(uint64_t hi, uint64_t lo, uint64_t d)
{
    uint64_t r;
    if (hi >= d) return UINT64_MAX; /* the quotient needs more than 64 bits */
    uint64_t q = udiv128(hi, lo, d, &r);
    if (q >> 63) return UINT64_MAX;
    if (r >= d - r) q++;
    return q >> 63 ? UINT64_MAX : q;
}
#else
/* Restoring division one bit at a time, so 32-bit targets need no libgcc helper. */
uint64_t rt_fx_div128_round(uint64_t hi, uint64_t lo, uint64_t d)
{
    if (hi == 0 && lo == 0) return 0;
    uint64_t q = 0, r = 0;
    for (int i = hi ? 127 - __builtin_clzll(hi) : 63 - __builtin_clzll(lo); i >= 0; i--) {
        uint64_t carry = r >> 63; /* r < d < 2^64, so r * 2 + bit may need a 65th bit */
        r = r << 1 | ((i >= 64 ? hi >> (i - 64) : lo >> i) & 1);
        if (q >> 62) return UINT64_MAX;
        q <<= 1;
        if (carry || r >= d) {
            r -= d;
            q |= 1;
        }
    }
    if (r >= d - r) q++;
    return q >> 63 ? UINT64_MAX : q;
}
#endif

uint64_t rt_fx_div_round(uint64_t n, unsigned shift, uint64_t d)
{
    return rt_fx_div128_round(n >> (64 - shift), n << shift, d);
}

rt_real rt_div(rt_real a, rt_real b)
{
    if (b == 0) return a == 0 ? RT_ZERO : rt_fx_signed(UINT64_MAX, a < 0);
    return rt_fx_signed(rt_fx_div_round(rt_fx_mag(a), 32, rt_fx_mag(b)), (a < 0) != (b < 0));
}

/* Adds the exact product a b (Q64.64) to the positive or the negative sum. */
static void add_product(rt_real a, rt_real b, uint64_t sum[2][2])
{
    uint64_t lo, hi = rt_fx_umul128(rt_fx_mag(a), rt_fx_mag(b), &lo);
    uint64_t *s = sum[(a < 0) != (b < 0)];
    s[1] += lo;
    s[0] += hi + (s[1] < lo);
}

/* Each sum holds at most three products below 2^126, so neither wraps. */
rt_real rt_dot3_div(rt_real a0, rt_real b0, rt_real a1, rt_real b1, rt_real a2, rt_real b2, rt_real d)
{
    uint64_t sum[2][2] = {{0, 0}, {0, 0}}; /* {hi, lo} of the positive and the negative products */
    add_product(a0, b0, sum);
    add_product(a1, b1, sum);
    add_product(a2, b2, sum);
    bool negative = sum[1][0] > sum[0][0] || (sum[1][0] == sum[0][0] && sum[1][1] > sum[0][1]);
    const uint64_t *big = sum[negative], *small = sum[!negative];
    uint64_t lo = big[1] - small[1], hi = big[0] - small[0] - (big[1] < small[1]);
    if (d == 0) return hi == 0 && lo == 0 ? RT_ZERO : rt_fx_signed(UINT64_MAX, negative);
    return rt_fx_signed(rt_fx_div128_round(hi, lo, rt_fx_mag(d)), negative != (d < 0));
}

/* 1/sqrt(x) on each 256th [x0, x0 + 2^-8) of [1/4, 1) by its best straight line
 * a - b (x - x0), a in Q29 and b in Q29 (python3 with mpmath: the chord's slope, the
 * chord lowered by half its largest gap to the curve): within 2^-16.4 of 1/sqrt(x)
 * relative, the seed of the Newton iteration in rt_sqrt. */
static const uint32_t rsqrt_line_a[192] = {
    1073729772, 1065438660, 1057336690, 1049416779, 1041672209, 1034096604, 1026683909, 1019428367, 1012324503,
    1005367105, 998551208,  991872080,  985325207,  978906282,  972611191,  966436002,  960376958,  954430462,
    948593072,  942861494,  937232567,  931703265,  926270682,  920932033,  915684639,  910525932,  905453441,
    900464790,  895557696,  890729960,  885979466,  881304176,  876702126,  872171425,  867710247,  863316832,
    858989482,  854726559,  850526477,  846387710,  842308780,  838288257,  834324763,  830416960,  826563558,
    822763305,  819014991,  815317443,  811669526,  808070139,  804518216,  801012722,  797552656,  794137043,
    790764941,  787435434,  784147631,  780900670,  777693712,  774525943,  771396570,  768304825,  765249958,
    762231244,  759247974,  756299460,  753385032,  750504039,  747655847,  744839837,  742055408,  739301974,
    736578965,  733885824,  731222008,  728586991,  725980256,  723401301,  720849637,  718324785,  715826278,
    713353663,  710906495,  708484340,  706086776,  703713388,  701363773,  699037538,  696734296,  694453672,
    692195298,  689958814,  687743870,  685550120,  683377230,  681224872,  679092723,  676980469,  674887804,
    672814425,  670760040,  668724358,  666707099,  664707986,  662726749,  660763123,  658816848,  656887671,
    654975342,  653079618,  651200260,  649337033,  647489709,  645658062,  643841872,  642040923,  640255002,
    638483903,  636727420,  634985354,  633257509,  631543692,  629843715,  628157393,  626484543,  624824987,
    623178550,  621545060,  619924348,  618316249,  616720599,  615137239,  613566013,  612006765,  610459344,
    608923602,  607399393,  605886572,  604384999,  602894535,  601415043,  599946391,  598488445,  597041077,
    595604159,  594177566,  592761176,  591354866,  589958518,  588572016,  587195243,  585828086,  584470435,
    583122179,  581783211,  580453424,  579132714,  577820979,  576518116,  575224027,  573938614,  572661779,
    571393428,  570133468,  568881805,  567638351,  566403015,  565175709,  563956346,  562744842,  561541113,
    560345075,  559156647,  557975748,  556802300,  555636225,  554477445,  553325885,  552181469,  551044126,
    549913781,  548790364,  547673804,  546564032,  545460978,  544364577,  543274760,  542191462,  541114619,
    540044167,  538980043,  537922184,
};
static const uint32_t rsqrt_line_b[192] = {
    2122641086, 2074214634, 2027601967, 1982709380, 1939449302, 1897739812, 1857504200, 1818670565, 1781171457,
    1744943540, 1709927291, 1676066724, 1643309135, 1611604870, 1580907113, 1551171692, 1522356892, 1494423299,
    1467333639, 1441052643, 1415546913, 1390784805, 1366736317, 1343372985, 1320667786, 1298595056, 1277130401,
    1256250625, 1235933655, 1216158480, 1196905087, 1178154400, 1159888236, 1142089244, 1124740866, 1107827291,
    1091333414, 1075244798, 1059547637, 1044228727, 1029275428, 1014675640, 1000417771, 986490716,  972883827,
    959586893,  946590120,  933884105,  921459824,  909308607,  897422125,  885792374,  874411656,  863272570,
    852367993,  841691072,  831235207,  820994044,  810961460,  801131557,  791498648,  782057250,  772802074,
    763728019,  754830160,  746103746,  737544186,  729147047,  720908049,  712823051,  704888055,  697099193,
    689452724,  681945030,  674572611,  667332079,  660220154,  653233661,  646369524,  639624765,  632996496,
    626481920,  620078326,  613783084,  607593646,  601507537,  595522360,  589635786,  583845556,  578149477,
    572545418,  567031314,  561605153,  556264987,  551008918,  545835104,  540741754,  535727128,  530789531,
    525927318,  521138887,  516422680,  511777181,  507200915,  502692446,  498250376,  493873343,  489560024,
    485309126,  481119392,  476989598,  472918549,  468905083,  464948065,  461046390,  457198980,  453404786,
    449662781,  445971967,  442331368,  438740034,  435197035,  431701466,  428252443,  424849102,  421490601,
    418176118,  414904848,  411676007,  408488830,  405342565,  402236484,  399169869,  396142024,  393152265,
    390199925,  387284351,  384404906,  381560966,  378751922,  375977175,  373236144,  370528257,  367852957,
    365209695,  362597939,  360017165,  357466860,  354946524,  352455666,  349993804,  347560470,  345155202,
    342777549,  340427069,  338103330,  335805907,  333534385,  331288358,  329067426,  326871198,  324699292,
    322551332,  320426950,  318325786,  316247485,  314191701,  312158094,  310146330,  308156082,  306187030,
    304238858,  302311259,  300403929,  298516571,  296648894,  294800611,  292971441,  291161110,  289369346,
    287595884,  285840464,  284102829,  282382728,  280679915,  278994147,  277325186,  275672799,  274036756,
    272416831,  270812804,  269224457,
};

/* True when s^2 > hi:lo. */
static bool square_above(uint64_t s, uint64_t hi, uint64_t lo)
{
    uint64_t sq_lo, sq_hi = rt_fx_umul128(s, s, &sq_lo);
    return sq_hi > hi || (sq_hi == hi && sq_lo > lo);
}

/* round(sqrt(n)) for n = hi:lo < 2^126, from multiplications only: x = n 4^k scaled into
 * [1/4, 1) as 64 bits, a seed from a straight line and two Newton steps
 * y <- y (3 - x y^2) / 2 towards 1/sqrt(x) (Q61, 2^-16.4 -> 2^-32.2 -> about 2^-60: the
 * line spares a step of three dependent products), then s ~ x y / 2^k, which lands within a
 * few units of floor(sqrt(n)) and is corrected exactly. It is rounded up exactly when
 * n - s^2 > s. */
static uint64_t root128(uint64_t hi, uint64_t lo)
{
    int k = (hi ? __builtin_clzll(hi) : 64 + __builtin_clzll(lo)) / 2;
    uint64_t x = k == 0 ? hi : k < 32 ? hi << 2 * k | lo >> (64 - 2 * k) : lo << (2 * k - 64);
    unsigned i = (unsigned)(x >> 56) - 64; /* x's 256th; its next 32 bits are 2^40 (x - x0) */
    uint64_t y = ((uint64_t)rsqrt_line_a[i] << 32) - ((uint64_t)rsqrt_line_b[i] * (uint32_t)(x >> 24) >> 8), plo;
    for (int step = 0; step < 2; step++) {
        uint64_t phi = rt_fx_umul128(y, y, &plo);
        uint64_t xyy = rt_fx_umul128(x, phi << 3 | plo >> 61, &plo); /* x y^2 in Q61 */
        phi = rt_fx_umul128(y, (UINT64_C(3) << 61) - xyy, &plo);
        y = phi << 2 | plo >> 62;
    }
    uint64_t phi = rt_fx_umul128(x, y, &plo); /* x y in Q125: sqrt(n) is it over 2^(61 + k) */
    uint64_t s = k >= 3 ? phi >> (k - 3) : phi << (3 - k) | plo >> (61 + k);
    while (square_above(s, hi, lo)) s--;
    while (!square_above(s + 1, hi, lo)) s++;
    uint64_t sq_lo;
    rt_fx_umul128(s, s, &sq_lo);
    return lo - sq_lo > s ? s + 1 : s; /* n - s^2 <= 2s fits the low word */
}

/* The root of a is that of n = a * 2^32. */
rt_real rt_sqrt(rt_real a)
{
    if (a <= 0) return RT_ZERO;
    return (rt_real)root128((uint64_t)a >> 32, (uint64_t)a << 32);
}

/* a * b as an exact Q64.64 number n, whose root is sqrt(a b) in Q32.32. */
rt_real rt_sqrt_mul(rt_real a, rt_real b)
{
    if (a <= 0 || b <= 0) return RT_ZERO;
    uint64_t lo, hi = rt_fx_umul128((uint64_t)a, (uint64_t)b, &lo);
    return (rt_real)root128(hi, lo);
}

/* ---- sin, cos, tan ---------------------------------------------------------- */

#define PIO2_Q62 INT64_C(0x6487ed5110b4611a)
/* floor(2/pi * 2^128) as two words. */
#define TWO_OVER_PI_HI UINT64_C(0xa2f9836e4e441529)
#define TWO_OVER_PI_LO UINT64_C(0xfc2757d1f534ddc0)

/* (-1)^k / (2k+1)!, k = 1..8: sin r = r + r z P(z), z = r^2; next term < 2^-63 for |r| <= pi/4. */
static const int64_t sin_coef[8] = {
    -INT64_C(0x0aaaaaaaaaaaaaab), INT64_C(0x0088888888888889),  -INT64_C(0x0003403403403403),
    INT64_C(0x00000b8ef1d2ab64),  -INT64_C(0x0000001ae64567f5), INT64_C(0x000000002c248c27),
    -INT64_C(0x000000000035cfe8), INT64_C(0x00000000000032a6),
};
/* (-1)^k / (2k)!, k = 1..9: cos r = 1 + z P(z); next term < 2^-67. */
static const int64_t cos_coef[9] = {
    -INT64_C(0x2000000000000000), INT64_C(0x02aaaaaaaaaaaaab),  -INT64_C(0x0016c16c16c16c17),
    INT64_C(0x0000680680680680),  -INT64_C(0x00000127e4fb778a), INT64_C(0x000000023ddb1dff),
    -INT64_C(0x0000000003272e95), INT64_C(0x0000000000035cfe),  -INT64_C(0x00000000000002d0),
};

/* P(z) by Horner, highest coefficient first. */
static int64_t horner(const int64_t *coef, int n, int64_t z)
{
    int64_t p = coef[n - 1];
    for (int i = n - 2; i >= 0; i--) p = mulq(p, z, 62) + coef[i];
    return p;
}

static int64_t sin_q62(int64_t r)
{
    int64_t z = mulq(r, r, 62);
    return r + mulq(mulq(r, z, 62), horner(sin_coef, 8, z), 62);
}

static int64_t cos_q62(int64_t r)
{
    int64_t z = mulq(r, r, 62);
    return Q62_ONE + mulq(z, horner(cos_coef, 9, z), 62);
}

/* ux / 2^32 = (4j + q + f) * pi/2 with f in [-1/2, 1/2): returns q, *r = f * pi/2 in Q62.
 * t = ux * 2/pi is formed to 2^-96 from 128 bits of 2/pi, so r is within 2^-62. */
static unsigned reduce(uint64_t ux, int64_t *r)
{
    uint64_t lo, hi = rt_fx_umul128(ux, TWO_OVER_PI_HI, &lo);
    uint64_t lo2, hi2 = rt_fx_umul128(ux, TWO_OVER_PI_LO, &lo2); /* lo2 is below 2^-96: dropped */
    lo += hi2;
    hi += lo < hi2;                    /* t * 2^96 = hi:lo */
    unsigned q = (unsigned)(hi >> 32); /* integer part of t (mod 4 below) */
    uint64_t f = hi << 32 | lo >> 32;  /* first 64 fraction bits of t */
    if (f >> 63) q++;                  /* f >= 1/2: use f - 1 */
    *r = mulq(to_signed(f), PIO2_Q62, 64);
    return q & 3;
}

/* Q62 to the nearest Q32.32. */
static rt_real from_q62(int64_t v) { return shift_round(v, 30); }

/* Within 0.5 lsb (2^-33) + 2^-58 of sin x for every x (measured: 0.500000 lsb). */
rt_real rt_sin(rt_real x)
{
    int64_t r;
    unsigned q = reduce(rt_fx_mag(x), &r);
    int64_t v = q & 1 ? cos_q62(r) : sin_q62(r);
    if (q & 2) v = -v;
    return from_q62(x < 0 ? -v : v);
}

/* Within 0.5 lsb + 2^-58 of cos x for every x (measured: 0.500000 lsb). */
rt_real rt_cos(rt_real x)
{
    int64_t r;
    unsigned q = reduce(rt_fx_mag(x), &r);
    int64_t v = q & 1 ? sin_q62(r) : cos_q62(r);
    return from_q62((q + 1) & 2 ? -v : v);
}

/* sin/cos of the reduced argument divided once: within 0.5 lsb + (1 + tan^2 x) 2^-59, the
 * Q62 kernels' error amplified as an argument error would be near the poles (0.5 lsb on
 * [-1, 1], 2^-17 at tan x = 4e6); saturates beyond 2^31. */
rt_real rt_tan(rt_real x)
{
    int64_t r;
    unsigned q = reduce(rt_fx_mag(x), &r);
    int64_t s = sin_q62(r), c = cos_q62(r);
    int64_t num = q & 1 ? -c : s, den = q & 1 ? s : c; /* tan = s/c, or -c/s in odd quadrants */
    bool neg = ((num < 0) != (den < 0)) != (x < 0);
    if (den == 0) return rt_fx_signed(UINT64_MAX, neg);
    return rt_fx_signed(rt_fx_div_round(rt_fx_mag(num), 32, rt_fx_mag(den)), neg);
}

/* ---- exp, log, pow ---------------------------------------------------------- */

/* exp and log pass arguments in Q58 (|value| < 32), enough for |log| <= 22.2 and for
 * every exp argument whose result is neither saturated nor 0. */
#define LN2_Q62 INT64_C(0x2c5c85fdf473de6b)
/* ln 2 - LN2_Q62 / 2^62, in units of 2^-126. */
#define LN2_LO (-INT64_C(974768846722515540))
#define LN2_Q58 INT64_C(0x02c5c85fdf473de7)
#define INV_LN2_Q62 INT64_C(0x5c551d94ae0bf85e)
#define SQRT2_Q62 UINT64_C(0x5a827999fcef3242)

/* 1/n!, n = 1..15: exp r = 1 + r P(r); next term < 2^-64 for |r| <= ln2/2. */
static const int64_t exp_coef[15] = {
    INT64_C(0x4000000000000000), INT64_C(0x2000000000000000), INT64_C(0x0aaaaaaaaaaaaaab), INT64_C(0x02aaaaaaaaaaaaab),
    INT64_C(0x0088888888888889), INT64_C(0x0016c16c16c16c17), INT64_C(0x0003403403403403), INT64_C(0x0000680680680680),
    INT64_C(0x00000b8ef1d2ab64), INT64_C(0x00000127e4fb778a), INT64_C(0x0000001ae64567f5), INT64_C(0x000000023ddb1dff),
    INT64_C(0x000000002c248c27), INT64_C(0x0000000003272e95), INT64_C(0x000000000035cfe8),
};
/* 1/(2k+1), k = 0..11: atanh s = s P(s^2); next term < 2^-67 for |s| <= 0.1716. */
static const int64_t atanh_coef[12] = {
    INT64_C(0x4000000000000000), INT64_C(0x1555555555555555), INT64_C(0x0ccccccccccccccd), INT64_C(0x0924924924924925),
    INT64_C(0x071c71c71c71c71c), INT64_C(0x05d1745d1745d174), INT64_C(0x04ec4ec4ec4ec4ec), INT64_C(0x0444444444444444),
    INT64_C(0x03c3c3c3c3c3c3c4), INT64_C(0x035e50d79435e50d), INT64_C(0x030c30c30c30c30c), INT64_C(0x02c8590b21642c86),
};

/* exp(y) for y in Q58, as Q32.32. y = k ln2 + r, |r| <= ln2/2 (+2^-58), then
 * exp(r) * 2^k with one rounding. */
static rt_real exp_q58(int64_t y)
{
    if (y > INT64_C(22) << 58) return RT_REAL_MAX; /* e^22 > 2^31 */
    if (y < -(INT64_C(23) << 58)) return RT_ZERO;  /* e^-23 < 2^-33 */
    int k = (int)shift_round(mulq(y, INV_LN2_Q62, 62), 58);
    /* y * 16 and k * LN2_Q62 may wrap in uint64, but their difference is r, small and exact. */
    int64_t r = to_signed((uint64_t)y * 16u - (uint64_t)k * (uint64_t)LN2_Q62) - mulq(k, LN2_LO, 64);
    int64_t e = Q62_ONE + mulq(r, horner(exp_coef, 15, r), 62); /* in [0.7, 1.42] */
    int s = 30 - k;                                             /* Q62 * 2^k -> Q32.32 */
    if (s > 0) return shift_round(e, (unsigned)s);              /* k >= -33, so s <= 63 */
    return e > INT64_MAX >> -s ? RT_REAL_MAX : e << -s;
}

/* Within 0.5 lsb + 2^-59 relative (measured: 0.500 lsb for x <= 5, 2 lsb = 2^-61.7
 * relative near the 2^31 rail); exp(x > 21.49) saturates, exp(x < -22.87) = 0. */
rt_real rt_exp(rt_real x)
{
    if (x > INT64_C(22) << 32) return RT_REAL_MAX;
    if (x < -(INT64_C(23) << 32)) return RT_ZERO;
    return exp_q58(x * (INT64_C(1) << 26));
}

/* log(ux / 2^32) in Q58 for ux >= 1, within 2^-58: ux / 2^32 = m 2^e with m in
 * [sqrt(1/2), sqrt(2)), and log m = 2 atanh((m - 1)/(m + 1)). */
static int64_t log_q58(uint64_t ux)
{
    int lz = __builtin_clzll(ux); /* >= 1: ux < 2^63 */
    uint64_t m = ux << (lz - 1);  /* m / 2^62 in [1, 2), exact */
    int e = 31 - lz;
    uint64_t c = Q62_ONE;
    if (m >= SQRT2_Q62) { /* log m = ln 2 + log(m / 2); (m/2 - 1)/(m/2 + 1) = (m - 2)/(m + 2) */
        c = 2 * c;
        e++;
    }
    bool neg = m < c;
    int64_t s = rt_fx_signed(rt_fx_div_round(neg ? c - m : m - c, 62, m + c), neg); /* m + c < 2^64 */
    int64_t half_log = mulq(s, horner(atanh_coef, 12, mulq(s, s, 62)), 62);         /* atanh s */
    return e * LN2_Q58 + shift_round(half_log, 3);                                  /* 2 atanh s in Q58 */
}

/* Within 0.5 lsb + 2^-58 (measured: 0.500000 lsb); log(x <= 0) = -RT_REAL_MAX (the
 * saturated -infinity). */
rt_real rt_log(rt_real x)
{
    if (x <= 0) return -RT_REAL_MAX;
    return shift_round(log_q58((uint64_t)x), 26);
}

/* exp(e log base) with the product kept in Q58: within 0.5 lsb + (|e| 2^-57 + 2^-59)
 * relative, which for base in (0, 1] and e <= 1000 is 0.5 lsb + 2^-15 (measured: 0.500001
 * lsb). pow(x, 0) = 1 (also 0^0), pow(0, e > 0) = 0,
 * pow(0, e < 0) = RT_REAL_MAX; a negative base counts as 0 (as max(N.H, 0) would). */
rt_real rt_pow(rt_real base, rt_real e)
{
    if (e == 0 || base == RT_ONE) return RT_ONE;
    if (base <= 0) return e > 0 ? RT_ZERO : RT_REAL_MAX;
    int64_t l = log_q58((uint64_t)base);
    bool neg = (e < 0) != (l < 0);
    uint64_t y = rt_fx_umulshift(rt_fx_mag(e), rt_fx_mag(l), 32); /* |e log base| in Q58 */
    if (y > UINT64_C(23) << 58) return neg ? RT_ZERO : RT_REAL_MAX;
    return exp_q58(rt_fx_signed(y, neg));
}

/* Counter-based random numbers; see rng.h. */
#include "rng.h"
#include "hash.h"
#include "invariant.h"

/* 2^64 / golden ratio: keeps a zero input away from mix's fixed point at 0. */
#define RT_RNG_GOLDEN 0x9e3779b97f4a7c15ull

uint64_t rt_rng_hash(uint64_t a, uint64_t b) { return rt_hash_mix(rt_hash_mix(a + RT_RNG_GOLDEN) + b); }

uint64_t rt_rng_pixel_key(uint32_t column, uint32_t row)
{
    return rt_rng_hash(0x72746b, ((uint64_t)row << 32) | column);
}

uint64_t rt_rng_child(uint64_t node, uint32_t branch) { return rt_rng_hash(node, (uint64_t)branch + 1); }

rt_real rt_rng_unit(uint64_t bits)
{
    uint32_t u = (uint32_t)(bits >> 32);
    rt_real scale = RT_C(65536.0);
    rt_real low = rt_div(rt_from_int(u & 0xffffu), scale);
    return rt_div(rt_add(rt_from_int(u >> 16), low), scale);
}

uint32_t rt_rng_permute(uint32_t index, uint32_t bits, uint64_t key)
{
    RT_ASSERT(bits <= 30);
    if (bits == 0) return 0;
    uint32_t mask = (1u << bits) - 1, x = index & mask;
    /* Each step is a bijection of bits-wide words: xor with a constant, multiplication
     * by an odd number modulo 2^bits, and an xor with the word shifted right. */
    for (uint32_t round = 0; round < 4; round++) {
        uint64_t k = rt_rng_hash(key, round);
        x ^= (uint32_t)k & mask;
        x = (x * ((uint32_t)(k >> 32) | 1u)) & mask;
        x ^= x >> ((bits + 1) / 2);
    }
    return x;
}

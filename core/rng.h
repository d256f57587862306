/* Counter-based random numbers: every number is a pure function of a key (pixel,
 * sample, the path's branch history, purpose), never of a generator state, so an
 * image does not depend on thread count, tile order or how many numbers other pixels
 * drew. Integers are mixed with 64-bit hashes; the conversion to rt_real is exact
 * in both builds (32 bits, through rt_from_int and divisions by 2^16). */
#ifndef RT_RNG_H
#define RT_RNG_H

#include "real.h"

/* Mixes a into b: distinct (a, b) give unrelated 64-bit results. */
uint64_t rt_rng_hash(uint64_t a, uint64_t b);

/* The key of one pixel (its random numbers start here). */
uint64_t rt_rng_pixel_key(uint32_t column, uint32_t row);

/* The key of a path node's child along branch `branch` (the root is any constant). */
uint64_t rt_rng_child(uint64_t node, uint32_t branch);

/* A uniform number in [0, 1) from the top 32 bits of bits: exactly (bits >> 32) / 2^32. */
rt_real rt_rng_unit(uint64_t bits);

/* A bijection of [0, 2^bits) chosen by key (bits <= 30): strata in scrambled order. */
uint32_t rt_rng_permute(uint32_t index, uint32_t bits, uint64_t key);

#endif

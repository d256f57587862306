/* Turns libFuzzer's bytes into bounded values, so that invariants about geometry
 * are meaningful, or into raw scalars (NaN, infinities, extremes) for robustness. */
#ifndef FZ_BYTES_H
#define FZ_BYTES_H

#include <stddef.h>
#include <stdint.h>

#include "vec.h"

typedef struct {
    const uint8_t *data;
    size_t size, pos;
} fz_bytes;

fz_bytes fz_bytes_of(const uint8_t *data, size_t size);
/* The next bytes as an unsigned integer; 0 once the input is used up. */
uint8_t fz_u8(fz_bytes *in);
uint16_t fz_u16(fz_bytes *in);
/* An integer in [0, n) (n > 0). */
uint32_t fz_below(fz_bytes *in, uint32_t n);
/* 16 bits mapped linearly onto [lo, hi], both ends included. */
double fz_range(fz_bytes *in, double lo, double hi);
/* 2^e with e in [lo, hi], in steps of 1/16. */
double fz_pow2(fz_bytes *in, double lo, double hi);
/* A point in [lo, hi]^3. */
rt_vec3 fz_vec_range(fz_bytes *in, double lo, double hi);
/* A unit vector, never degenerate (a fixed axis when the bytes say zero). */
rt_vec3 fz_unit_vector(fz_bytes *in);
/* sizeof(rt_real) bytes as they come: any bit pattern, NaN and infinities included. */
rt_real fz_raw(fz_bytes *in);
rt_vec3 fz_vec_raw(fz_bytes *in);

#endif

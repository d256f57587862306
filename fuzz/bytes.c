/* Decoding of fuzz input; see bytes.h. */
#include "bytes.h"

#include <math.h>
#include <string.h>

fz_bytes fz_bytes_of(const uint8_t *data, size_t size)
{
    fz_bytes in = {data, size, 0};
    return in;
}

uint8_t fz_u8(fz_bytes *in) { return in->pos < in->size ? in->data[in->pos++] : 0; }

uint16_t fz_u16(fz_bytes *in)
{
    uint16_t hi = fz_u8(in);
    return (uint16_t)(hi << 8 | fz_u8(in));
}

uint32_t fz_below(fz_bytes *in, uint32_t n) { return fz_u16(in) % n; }

double fz_range(fz_bytes *in, double lo, double hi) { return lo + (hi - lo) * (fz_u16(in) / 65535.0); }

double fz_pow2(fz_bytes *in, double lo, double hi) { return exp2(floor(fz_range(in, lo, hi) * 16.0) / 16.0); }

rt_vec3 fz_vec_range(fz_bytes *in, double lo, double hi)
{
    double x = fz_range(in, lo, hi), y = fz_range(in, lo, hi);
    return rt_v3(rt_from_double(x), rt_from_double(y), rt_from_double(fz_range(in, lo, hi)));
}

rt_vec3 fz_unit_vector(fz_bytes *in)
{
    double x = fz_range(in, -1, 1), y = fz_range(in, -1, 1), z = fz_range(in, -1, 1);
    double len = sqrt(x * x + y * y + z * z);
    if (len < 1e-3) return rt_v3(RT_ZERO, RT_ZERO, rt_neg(RT_ONE));
    return rt_v3(rt_from_double(x / len), rt_from_double(y / len), rt_from_double(z / len));
}

rt_real fz_raw(fz_bytes *in)
{
    uint8_t b[sizeof(rt_real)];
    for (size_t i = 0; i < sizeof b; i++) b[i] = fz_u8(in);
    rt_real r;
    memcpy(&r, b, sizeof r);
    return r;
}

rt_vec3 fz_vec_raw(fz_bytes *in)
{
    rt_real x = fz_raw(in), y = fz_raw(in);
    return rt_v3(x, y, fz_raw(in));
}

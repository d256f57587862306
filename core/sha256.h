/* SHA-256 (FIPS 180-4), for render hashes. */
#ifndef RT_SHA256_H
#define RT_SHA256_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t state[8];
    uint64_t length; /* bytes hashed so far */
    uint8_t block[64];
    uint32_t block_used;
} rt_sha256;

void rt_sha256_init(rt_sha256 *h);
void rt_sha256_update(rt_sha256 *h, const void *data, size_t size);
void rt_sha256_final(rt_sha256 *h, uint8_t digest[32]);

/* The render hash: SHA-256 of the P6 PPM "P6\n<w> <h>\n255\n" + rgb bytes (top row first). */
void rt_sha256_ppm(const uint8_t *rgb, uint32_t width, uint32_t height, uint8_t digest[32]);

#endif

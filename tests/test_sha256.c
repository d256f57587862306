/* SHA-256 (core/sha256.c) against the FIPS 180-4 example vectors, and the render hash
 * against sha256sum of the same PPM bytes. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "sha256.h"

static void hex(const uint8_t digest[32], char out[65])
{
    for (int i = 0; i < 32; i++) sprintf(out + 2 * i, "%02x", digest[i]);
}

static void check_digest(const void *data, size_t size, const char *expected)
{
    rt_sha256 h;
    uint8_t digest[32];
    char got[65];
    rt_sha256_init(&h);
    rt_sha256_update(&h, data, size);
    rt_sha256_final(&h, digest);
    hex(digest, got);
    cr_assert_str_eq(got, expected, "%zu-byte message", size);
}

/* Expected digests: FIPS 180-4 examples (NIST "SHA256.pdf"), confirmed with sha256sum. */
Test(sha256, empty_message) { check_digest("", 0, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"); }

Test(sha256, abc) { check_digest("abc", 3, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"); }

Test(sha256, two_block_448_bit_message)
{
    const char *m = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    check_digest(m, strlen(m), "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

/* Padding boundaries: 55 bytes fit one block, 56 and 64 need a second one.
 * Expected: printf 'a%.0s' $(seq N) | sha256sum, for N = 55, 56, 64. */
Test(sha256, padding_boundaries)
{
    char a[64];
    memset(a, 'a', sizeof a);
    check_digest(a, 55, "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
    check_digest(a, 56, "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
    check_digest(a, 64, "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

/* One million 'a' fed in uneven chunks (1, 2, ..., 97 bytes, repeating), so partial
 * blocks, exact blocks and multi-block runs all occur. */
Test(sha256, million_a_in_uneven_chunks)
{
    static uint8_t a[1000000];
    memset(a, 'a', sizeof a);
    rt_sha256 h;
    uint8_t digest[32];
    char got[65];
    rt_sha256_init(&h);
    size_t done = 0;
    for (size_t chunk = 1; done < sizeof a; chunk = chunk % 97 + 1) {
        size_t n = chunk < sizeof a - done ? chunk : sizeof a - done;
        rt_sha256_update(&h, a + done, n);
        done += n;
    }
    rt_sha256_final(&h, digest);
    hex(digest, got);
    cr_assert_str_eq(got, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

/* Expected: printf 'P6\n2 1\n255\n\xff\x00\x10\x20\x80\xfe' | sha256sum */
Test(sha256, render_hash_is_sha256_of_the_ppm_file)
{
    const uint8_t rgb[6] = {0xff, 0x00, 0x10, 0x20, 0x80, 0xfe};
    uint8_t digest[32];
    char got[65];
    rt_sha256_ppm(rgb, 2, 1, digest);
    hex(digest, got);
    cr_assert_str_eq(got, "0c02c8cdf5c3b45ca48c69a7fd2740ba5164d2a9d9d5976f1623749bb17ea2a3");
}

/* Multi-digit sizes go through the same decimal formatting: the hash equals the one of
 * the header built with snprintf (allowed here, not in the core) plus the pixels. */
Test(sha256, render_hash_header_for_large_sizes)
{
    static uint8_t rgb[1234 * 10 * 3];
    for (size_t i = 0; i < sizeof rgb; i++) rgb[i] = (uint8_t)(i * 7);
    char header[32];
    int len = snprintf(header, sizeof header, "P6\n%u %u\n255\n", 1234u, 10u);
    rt_sha256 h;
    uint8_t expected[32], digest[32];
    rt_sha256_init(&h);
    rt_sha256_update(&h, header, (size_t)len);
    rt_sha256_update(&h, rgb, sizeof rgb);
    rt_sha256_final(&h, expected);
    rt_sha256_ppm(rgb, 1234, 10, digest);
    cr_assert_arr_eq(digest, expected, 32);
}

/* The accounting allocator behind --max-memory (platform/mem/mem.h). Each test runs in
 * a process of its own, so the cap set here is its own. */
#include "mem/mem.h"
#include "mem/mem_stream.h"

#include <criterion/criterion.h>
#include <stdint.h>
#include <string.h>

Test(mem, what_is_allocated_is_counted_until_freed)
{
    size_t before = rtp_mem_in_use();
    char *a = rtp_mem_alloc(1000, "a"), *b = rtp_mem_calloc(10, 100, "b");
    cr_assert(a && b);
    cr_expect_eq(rtp_mem_in_use(), before + 2000);
    a = rtp_mem_realloc(a, 3000, "a");
    cr_assert(a);
    cr_expect_eq(rtp_mem_in_use(), before + 4000);
    a = rtp_mem_realloc(a, 10, "a");
    cr_assert(a);
    cr_expect_eq(rtp_mem_in_use(), before + 1010);
    for (int i = 0; i < 1000; i++) cr_assert_eq(b[i], 0, "calloc did not clear");
    rtp_mem_free(a);
    rtp_mem_free(b);
    cr_expect_eq(rtp_mem_in_use(), before);
    cr_expect_geq(rtp_mem_peak(), before + 4000);
    cr_expect_not(rtp_mem_refused());
}

Test(mem, the_cap_refuses_and_says_what_did_not_fit)
{
    rtp_mem_set_cap(rtp_mem_in_use() + (1u << 20));
    void *ok = rtp_mem_alloc(512u << 10, "the first half");
    cr_assert(ok);
    cr_expect_null(rtp_mem_alloc(768u << 10, "the decoded texture"));
    cr_expect(rtp_mem_refused());
    cr_expect(strstr(rtp_mem_refusal(), "the decoded texture (786432 bytes) does not fit in --max-memory (") ==
                  rtp_mem_refusal(),
              "%s", rtp_mem_refusal());
    /* A failed realloc leaves the block as it was. */
    cr_expect_null(rtp_mem_realloc(ok, 2u << 20, "more"));
    memset(ok, 1, 512u << 10);
    rtp_mem_free(ok);
}

Test(mem, sizes_that_overflow_are_refused)
{
    cr_expect_null(rtp_mem_calloc(SIZE_MAX / 2, 3, "huge"));
    cr_expect_null(rtp_mem_alloc(SIZE_MAX - 4, "huge"));
    cr_expect(rtp_mem_refused());
}

Test(mem, held_bytes_count_without_being_allocated)
{
    rtp_mem_set_cap(rtp_mem_in_use() + 1000);
    cr_assert(rtp_mem_hold(800, "a library's buffers"));
    cr_expect_not(rtp_mem_fits(300, "more"));
    rtp_mem_unhold(800);
    cr_expect(rtp_mem_fits(300, "more"));
}

Test(mem, sizes_are_described_in_bytes_or_mib)
{
    char buf[32];
    cr_expect_str_eq(rtp_mem_describe(1000, buf, sizeof buf), "1000 bytes");
    cr_expect_str_eq(rtp_mem_describe((size_t)8 << 20, buf, sizeof buf), "8 MiB");
    cr_expect_str_eq(rtp_mem_describe((size_t)3 << 19, buf, sizeof buf), "1.5 MiB");
}

Test(mem, a_stream_writes_into_counted_memory_and_fails_at_the_cap)
{
    rtp_mem_buffer text = {0};
    FILE *out = rtp_mem_stream_open(&text);
    cr_assert_not_null(out);
    fprintf(out, "<svg>%d</svg>", 42);
    cr_assert_eq(fclose(out), 0);
    cr_expect_eq(text.size, 13);
    cr_expect_arr_eq(text.data, "<svg>42</svg>", 13);
    cr_expect_geq(rtp_mem_in_use(), text.capacity);
    rtp_mem_buffer_free(&text);

    rtp_mem_set_cap(rtp_mem_in_use() + 10000);
    text.what = "the digits";
    out = rtp_mem_stream_open(&text);
    for (int i = 0; i < 1000; i++) fputs("0123456789", out);
    cr_expect_neq(fclose(out), 0, "writing past the cap did not fail");
    cr_expect(rtp_mem_refused());
    cr_expect(strstr(rtp_mem_refusal(), "the digits ("), "%s", rtp_mem_refusal());
    rtp_mem_buffer_free(&text);
}

/* libFuzzer target: scene blobs (core/blob.c, the bytes `rtk pack` writes and the
 * determinism driver and the bare-metal image read) on arbitrary bytes. rt_blob_read must
 * refuse them or return a description that reads back the same: written again, read
 * and written once more, the bytes do not change (bytes the first read normalised, such
 * as a boolean of 2, may differ from the input, but never twice), and of the input's
 * size. An accepted description goes through rt_scene_build, which accepts or refuses. */
#include <string.h>

#include "blob.h"
#include "check.h"
#include "fixture.h"

static uint8_t arena_memory[4u << 20];
static uint8_t once[64u << 10], twice[64u << 10];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    rt_arena arena;
    rt_arena_init(&arena, arena_memory, sizeof arena_memory);
    rt_scene_desc desc, again;
    rt_status st = rt_blob_read(data, size, &arena, &desc);
    FZ_CHECK(st == RT_OK || st == RT_ERR_INVALID || st == RT_ERR_NOMEM, "rt_blob_read returned %s", rt_status_name(st));
    if (st != RT_OK) return 0;
    size_t n = rt_blob_size(&desc);
    FZ_CHECK(n == size, "an accepted blob of %zu bytes writes back as %zu", size, n);
    if (n > sizeof once) return 0;
    FZ_CHECK(rt_blob_write(&desc, once, sizeof once) == n, "writing the description back failed");
    FZ_CHECK(rt_blob_read(once, n, &arena, &again) == RT_OK, "the written description does not read back");
    FZ_CHECK(rt_blob_write(&again, twice, sizeof twice) == n && memcmp(once, twice, n) == 0,
             "read and written again, the bytes changed");
    rt_scene scene;
    rt_build_error err;
    fz_build(&desc, &scene, &err);
    return 0;
}

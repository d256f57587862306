/* The freestanding half of the public API (include/rtk.h): thin wrappers over the blob
 * reader, the scene build, the tile renderer and SHA-256. */
#include "blob.h"
#include "render.h"
#include "rtk_scene.h"
#include "sha256.h"

/* The public status codes extend the core's. */
_Static_assert((int)RTK_OK == (int)RT_OK && (int)RTK_ERR_NOMEM == (int)RT_ERR_NOMEM &&
                   (int)RTK_ERR_INVALID == (int)RT_ERR_INVALID && (int)RTK_ERR_RANGE == (int)RT_ERR_RANGE,
               "rtk_status and rt_status agree");

const char *rtk_version(void) { return RTK_VERSION_STRING; }

const char *rtk_build(void)
{
#if defined(RT_REAL_FIXED)
    return "fixed";
#else
    return "double";
#endif
}

const char *rtk_status_name(rtk_status status)
{
    switch (status) {
    case RTK_ERR_INPUT: return "bad input file";
    case RTK_ERR_OUTPUT: return "cannot write the output";
    case RTK_ERR_INTERRUPTED: return "interrupted";
    default: return rt_status_name((rt_status)status);
    }
}

rtk_status rtk_scene_from_blob(const void *blob, size_t blob_size, void *memory, size_t capacity, const rtk_scene **out,
                               size_t *needed)
{
    rt_arena arena;
    rt_arena_init(&arena, memory, capacity);
    struct rtk_scene *handle = RT_NEW_ARRAY(&arena, struct rtk_scene, 1);
    rt_scene *scene = RT_NEW_ARRAY(&arena, rt_scene, 1);
    rt_scene_desc desc;
    rt_build_error err;
    rt_status st = handle && scene ? rt_blob_read(blob, blob_size, &arena, &desc) : RT_ERR_NOMEM;
    if (st == RT_OK) st = rt_scene_build(&desc, &arena, NULL, scene, &err);
    if (st == RT_ERR_NOMEM && needed) {
        /* What the failed step wanted, doubled: a retry gets further, and at most a few are needed. */
        size_t want = arena.wanted > capacity ? arena.wanted : capacity;
        *needed = want > SIZE_MAX / 2 ? SIZE_MAX : 2 * want;
    }
    if (st != RT_OK) return (rtk_status)st;
    handle->scene = scene;
    handle->host = NULL;
    *out = handle;
    return RTK_OK;
}

void rtk_scene_size(const rtk_scene *scene, uint32_t *width, uint32_t *height)
{
    *width = scene->scene->camera.width;
    *height = scene->scene->camera.height;
}

void rtk_render_region(const rtk_scene *scene, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb)
{
    rt_tracer tracer = {.scene = scene->scene, .use_bvh = true};
    rt_render_region(&tracer, x0, y0, x1, y1, rgb);
}

void rtk_render_hash(const uint8_t *rgb, uint32_t width, uint32_t height, char hash[RTK_HASH_SIZE])
{
    static const char hex[] = "0123456789abcdef";
    uint8_t digest[32];
    rt_sha256_ppm(rgb, width, height, digest);
    for (int i = 0; i < 32; i++) {
        hash[2 * i] = hex[digest[i] >> 4];
        hash[2 * i + 1] = hex[digest[i] & 15];
    }
    hash[64] = '\0';
}

/* rtk on bare metal: renders the scene blob linked into the image (made at build time by
 * `rtk pack` from scenes/baremetal.yaml with the fixed build) from a static arena, and
 * prints its render hash, the arena's high-water mark and the time taken. */
#include "blob.h"
#include "board.h"
#include "render.h"
#include "sha256.h"

/* Scene data, BVH and image; the high-water mark printed below shows what is used. */
#define ARENA_BYTES (512u * 1024u)

extern const uint8_t _binary_scene_rtscene_start[], _binary_scene_rtscene_end[];

static uint8_t arena_memory[ARENA_BYTES];

static void print_number(const char *label, uint32_t value, const char *unit)
{
    char digits[12];
    int n = 0;
    do {
        digits[n++] = (char)('0' + value % 10);
        value /= 10;
    } while (value);
    char text[64];
    int k = 0;
    while (*label) text[k++] = *label++;
    while (n) text[k++] = digits[--n];
    while (*unit) text[k++] = *unit++;
    text[k] = 0;
    rt_board_print(text);
}

int main(void)
{
    rt_arena arena;
    rt_arena_init(&arena, arena_memory, sizeof arena_memory);
    rt_scene_desc desc;
    rt_scene scene;
    rt_build_error err;
    size_t blob_size = (size_t)(_binary_scene_rtscene_end - _binary_scene_rtscene_start);
    if (rt_blob_read(_binary_scene_rtscene_start, blob_size, &arena, &desc) != RT_OK) {
        rt_board_print("rtk: the linked scene is not a fixed-build blob\n");
        return 1;
    }
    if (rt_scene_build(&desc, &arena, NULL, &scene, &err) != RT_OK) {
        rt_board_print("rtk: scene build failed: ");
        rt_board_print(err.what);
        rt_board_print("\n");
        return 1;
    }
    uint32_t w = scene.camera.width, h = scene.camera.height;
    uint8_t *rgb = rt_arena_alloc(&arena, (size_t)w * h * 3);
    if (!rgb) {
        rt_board_print("rtk: arena too small for the image\n");
        return 1;
    }
    rt_tracer tracer = {.scene = &scene, .use_bvh = true};
    uint32_t start = rt_board_centiseconds();
    rt_render_region(&tracer, 0, 0, w, h, rgb);
    uint32_t elapsed = rt_board_centiseconds() - start;
    uint8_t digest[32];
    rt_sha256_ppm(rgb, w, h, digest);
    char hex[66];
    for (int i = 0; i < 32; i++) {
        hex[2 * i] = "0123456789abcdef"[digest[i] >> 4];
        hex[2 * i + 1] = "0123456789abcdef"[digest[i] & 15];
    }
    hex[64] = '\n';
    hex[65] = 0;
    rt_board_print(hex);
    print_number("arena high-water mark: ", (uint32_t)arena.high_water, " bytes\n");
    print_number("render time: ", elapsed * 10, " ms (emulated)\n");
    return 0;
}

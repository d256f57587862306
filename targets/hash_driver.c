/* Renders a scene blob (made by `rtk pack`) with nothing but the core and prints its
 * render hash. Built for every compiler, optimisation level and CPU of the determinism
 * matrix (targets/determinism.sh); it needs only a C library to read the file. An
 * optional third argument names the BVH kernel (portable, sse2, avx2, avx512; default: the
 * build's own); the matrix passes only kernels the CPU runs. */
#include "blob.h"
#include "bvh.h"
#include "render.h"
#include "sha256.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint8_t *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    uint8_t *bytes = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n > 0 && fseek(f, 0, SEEK_SET) == 0 && (bytes = malloc((size_t)n)) != NULL) {
            if (fread(bytes, 1, (size_t)n, f) != (size_t)n) {
                free(bytes);
                bytes = NULL;
            }
            *size = (size_t)n;
        }
    }
    fclose(f);
    return bytes;
}

int main(int argc, char **argv)
{
    static const char *const kernels[] = {"portable", "sse2", "avx2", "avx512"};
    int kernel = -1;
    for (int k = 0; argc == 4 && k < (int)(sizeof kernels / sizeof kernels[0]); k++)
        if (!strcmp(argv[3], kernels[k])) kernel = k;
    if (argc != 3 && !(argc == 4 && kernel >= 0)) {
        fprintf(stderr, "usage: %s SCENE.rtscene ARENA_MIB [portable|sse2|avx2|avx512]\n", argv[0]);
        return 2;
    }
    size_t blob_size = 0, arena_size = (size_t)strtoul(argv[2], NULL, 10) << 20;
    uint8_t *blob = read_file(argv[1], &blob_size);
    void *memory = malloc(arena_size);
    if (!blob || !memory) {
        fprintf(stderr, "%s: cannot read the blob or allocate the arena\n", argv[1]);
        return 3;
    }
    rt_arena arena;
    rt_arena_init(&arena, memory, arena_size);
    rt_scene_desc desc;
    rt_scene scene;
    rt_build_error err;
    rt_status st = rt_blob_read(blob, blob_size, &arena, &desc);
    if (st != RT_OK) {
        fprintf(stderr, "%s: not a scene blob of this build (%s)\n", argv[1], rt_status_name(st));
        return 3;
    }
    if (rt_scene_build(&desc, &arena, NULL, &scene, &err) != RT_OK) {
        fprintf(stderr, "%s: %s\n", argv[1], err.what);
        return 3;
    }
    if (kernel >= 0 && !rt_bvh_set_kernel(&scene.bvh, (rt_kernel)kernel)) {
        fprintf(stderr, "%s: this build has no %s kernel\n", argv[0], argv[3]);
        return 2;
    }
    uint32_t w = scene.camera.width, h = scene.camera.height;
    uint8_t *rgb = malloc((size_t)w * h * 3);
    if (!rgb) return 5;
    rt_tracer tracer = {.scene = &scene, .use_bvh = true};
    rt_render_region(&tracer, 0, 0, w, h, rgb);
    uint8_t digest[32];
    rt_sha256_ppm(rgb, w, h, digest);
    for (int i = 0; i < 32; i++) printf("%02x", digest[i]);
    printf("\n");
    free(rgb);
    free(memory);
    free(blob);
    return 0;
}

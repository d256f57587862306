/* Scene blobs (core/blob.c): a description written and read back is the same
 * description, field for field, and the same bytes when written again; every
 * truncation, a changed header and a count that lies are refused, never read past. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "blob.h"
#include "load/scene_load.h"
#include "reference.h"

static uint8_t *write_blob(const rt_scene_desc *desc, size_t *size)
{
    *size = rt_blob_size(desc);
    uint8_t *bytes = malloc(*size);
    cr_assert(bytes);
    cr_assert_eq(rt_blob_write(desc, bytes, *size), *size);
    return bytes;
}

static rt_status read_blob(const uint8_t *bytes, size_t size, rt_arena *arena, void **memory, rt_scene_desc *out)
{
    size_t capacity = 64u << 20;
    *memory = malloc(capacity);
    cr_assert(*memory);
    rt_arena_init(arena, *memory, capacity);
    return rt_blob_read(bytes, size, arena, out);
}

#define SAME_BYTES(a, b, n, what) \
    cr_expect(((a) == NULL) == ((b) == NULL) && (!(a) || memcmp((a), (b), (n)) == 0), what)

static void expect_same_desc(const rt_scene_desc *a, const rt_scene_desc *b)
{
    cr_expect(memcmp(&a->camera, &b->camera, sizeof a->camera) == 0, "camera differs");
    cr_assert_eq(a->material_count, b->material_count);
    SAME_BYTES(a->materials, b->materials, a->material_count * sizeof *a->materials, "materials differ");
    cr_assert_eq(a->texture_count, b->texture_count);
    for (uint32_t i = 0; i < a->texture_count; i++) {
        const rt_texture *x = &a->textures[i], *y = &b->textures[i];
        cr_expect(x->width == y->width && x->height == y->height && x->bilinear == y->bilinear, "texture %u", i);
        SAME_BYTES(x->rgb, y->rgb, (size_t)x->width * x->height * 3, "texels differ");
    }
    cr_assert_eq(a->mesh_count, b->mesh_count);
    for (uint32_t i = 0; i < a->mesh_count; i++) {
        const rt_mesh_desc *x = &a->meshes[i], *y = &b->meshes[i];
        cr_assert(x->vertex_count == y->vertex_count && x->triangle_count == y->triangle_count, "mesh %u counts", i);
        SAME_BYTES(x->positions, y->positions, x->vertex_count * sizeof *x->positions, "positions differ");
        SAME_BYTES(x->normals, y->normals, x->vertex_count * sizeof *x->normals, "normals differ");
        SAME_BYTES(x->uvs, y->uvs, x->vertex_count * sizeof *x->uvs, "uvs differ");
        SAME_BYTES(x->indices, y->indices, 3 * x->triangle_count * sizeof *x->indices, "indices differ");
    }
    cr_assert_eq(a->object_count, b->object_count);
    SAME_BYTES(a->objects, b->objects, a->object_count * sizeof *a->objects, "objects differ");
    cr_assert_eq(a->light_count, b->light_count);
    SAME_BYTES(a->lights, b->lights, a->light_count * sizeof *a->lights, "lights differ");
}

/* Scenes with textures, meshes with normals and uvs, every light kind between them. */
static const char *scenes[] = {"simple/texture_reflection", "trimeshes/box_sphere", "more/cornell_ray",
                               "simple/cylinder_refract"};

Test(blob, round_trip_gives_the_same_description_and_bytes)
{
    for (size_t s = 0; s < sizeof scenes / sizeof scenes[0]; s++) {
        char path[4096], err[RTP_ERR_SIZE];
        snprintf(path, sizeof path, "%s/%s.yaml", rt_test_trace_dir(), scenes[s]);
        rtp_loaded_scene loaded;
        cr_assert(rtp_scene_load(path, NULL, &loaded, err, sizeof err), "%s", err);
        size_t size, again_size;
        uint8_t *bytes = write_blob(&loaded.desc, &size);
        rt_arena arena;
        void *memory;
        rt_scene_desc back;
        cr_assert_eq(read_blob(bytes, size, &arena, &memory, &back), RT_OK, "%s: blob not read back", scenes[s]);
        expect_same_desc(&loaded.desc, &back);
        uint8_t *again = write_blob(&back, &again_size);
        cr_expect(again_size == size && memcmp(bytes, again, size) == 0, "%s: written again, other bytes", scenes[s]);
        free(again);
        free(memory);
        free(bytes);
        rtp_scene_unload(&loaded);
    }
}

Test(blob, every_truncation_and_a_changed_header_are_refused)
{
    char path[4096], err[RTP_ERR_SIZE];
    snprintf(path, sizeof path, "%s/simple/cylinder_refract.yaml", rt_test_trace_dir()); /* 1640 bytes */
    rtp_loaded_scene loaded;
    cr_assert(rtp_scene_load(path, NULL, &loaded, err, sizeof err), "%s", err);
    size_t size;
    uint8_t *bytes = write_blob(&loaded.desc, &size);
    rt_arena arena;
    void *memory;
    rt_scene_desc back;
    for (size_t n = 0; n < size; n++) {
        /* A copy of exactly n bytes, so reading past them is a sanitizer report. */
        uint8_t *prefix = malloc(n ? n : 1);
        memcpy(prefix, bytes, n);
        cr_assert_eq(read_blob(prefix, n, &arena, &memory, &back), RT_ERR_INVALID, "%zu of %zu bytes accepted", n,
                     size);
        free(memory);
        free(prefix);
    }
    uint8_t *longer = malloc(size + 1);
    memcpy(longer, bytes, size);
    longer[size] = 0;
    cr_expect_eq(read_blob(longer, size + 1, &arena, &memory, &back), RT_ERR_INVALID, "a trailing byte accepted");
    free(memory);
    /* Magic (byte 0), version (8), scalar size (16) and scalar kind (24). */
    const size_t header[] = {0, 8, 16, 24};
    for (size_t i = 0; i < 4; i++) {
        memcpy(longer, bytes, size);
        longer[header[i]] ^= 0x40;
        cr_expect_eq(read_blob(longer, size, &arena, &memory, &back), RT_ERR_INVALID,
                     "header byte %zu changed, accepted", header[i]);
        free(memory);
    }
    free(longer);
    free(bytes);
    rtp_scene_unload(&loaded);
}

Test(blob, a_count_that_lies_is_refused_before_allocating)
{
    char path[4096], err[RTP_ERR_SIZE];
    snprintf(path, sizeof path, "%s/more/cornell_ray.yaml", rt_test_trace_dir()); /* 4552 bytes */
    rtp_loaded_scene loaded;
    cr_assert(rtp_scene_load(path, NULL, &loaded, err, sizeof err), "%s", err);
    size_t size;
    uint8_t *bytes = write_blob(&loaded.desc, &size);
    /* Every 8-byte field set to 2^32 - 1 in turn: counts then claim more than the bytes
     * hold; reading must fail or succeed cleanly, and never run out of a 64 MiB arena. */
    rt_arena arena;
    void *memory;
    rt_scene_desc back;
    uint8_t *changed = malloc(size);
    for (size_t at = 32; at + 8 <= size; at += 8) {
        memcpy(changed, bytes, size);
        for (int k = 0; k < 4; k++) changed[at + k] = 0xff;
        rt_status st = read_blob(changed, size, &arena, &memory, &back);
        cr_expect(st == RT_OK || st == RT_ERR_INVALID, "field at byte %zu: %s", at, rt_status_name(st));
        free(memory);
    }
    free(changed);
    free(bytes);
    rtp_scene_unload(&loaded);
}

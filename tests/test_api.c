/* The public API (include/rtk.h) as a program sees it: hosted open, render, hash and
 * debug JSON agree with the rtk command; a blob rebuilt by the kernel alone, growing its
 * memory on RTK_ERR_NOMEM, renders the same bytes; errors are values with one line. */
#include "capture.h"
#include "cli/debug_cmd.h"
#include "cli/exit_codes.h"
#include "cli/render_cmd.h"
#include "rtk.h"

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <stdlib.h>
#include <string.h>

#define SCENE "scenes/demo.yaml"

static rtk_scene *open_small(void)
{
    char err[RTK_ERROR_SIZE];
    rtk_options opt = rtk_default_options();
    opt.width = 40;
    opt.height = 30;
    rtk_scene *s = NULL;
    cr_assert_eq(rtk_open(SCENE, &opt, &s, err, sizeof err), RTK_OK, "%s", err);
    return s;
}

static void render_hash(const rtk_scene *s, char hash[RTK_HASH_SIZE])
{
    uint32_t w, h;
    rtk_scene_size(s, &w, &h);
    uint8_t *rgb = calloc((size_t)w * h, 3);
    cr_assert(rgb);
    rtk_render_region(s, 0, 0, w, h, rgb);
    rtk_render_hash(rgb, w, h, hash);
    free(rgb);
}

Test(api, version_and_build_name_the_library)
{
    cr_expect_str_eq(rtk_version(), RTK_VERSION_STRING);
    cr_expect(!strcmp(rtk_build(), "double") || !strcmp(rtk_build(), "fixed"));
    cr_expect_str_eq(rtk_status_name(RTK_ERR_NOMEM), "out of memory");
}

Test(api, the_hosted_render_hash_is_the_commands, .init = cr_redirect_stderr)
{
    rtk_scene *s = open_small();
    uint32_t w, h;
    rtk_scene_size(s, &w, &h);
    cr_expect(w == 40 && h == 30);
    uint8_t *rgb = malloc((size_t)w * h * 3);
    cr_assert_eq(rtk_render(s, 3, rgb), RTK_OK);
    char hash[RTK_HASH_SIZE], tiles[RTK_HASH_SIZE];
    rtk_render_hash(rgb, w, h, hash);
    render_hash(s, tiles);
    cr_expect_str_eq(hash, tiles, "threads and one region agree");
    char *out = NULL;
    char *argv[] = {"render", SCENE, "--width", "40", "--height", "30", "--hash", "--quiet", NULL};
    cr_assert_eq(capture_stdout(rtp_cmd_render, 8, argv, &out), RTP_EXIT_OK);
    cr_expect(!strncmp(out, hash, 64), "rtk render --hash %s, the API %s", out, hash);
    free(out);
    free(rgb);
    rtk_close(s);
}

Test(api, a_packed_blob_renders_the_same_in_memory_grown_on_demand)
{
    rtk_scene *s = open_small();
    char want[RTK_HASH_SIZE], got[RTK_HASH_SIZE];
    render_hash(s, want);
    void *blob;
    size_t blob_size;
    cr_assert_eq(rtk_pack(s, &blob, &blob_size), RTK_OK);
    size_t capacity = 64, needed = 0;
    void *memory = NULL;
    const rtk_scene *from_blob = NULL;
    rtk_status st = RTK_ERR_NOMEM;
    int attempts = 0;
    for (; st == RTK_ERR_NOMEM && attempts < 40; attempts++) {
        free(memory);
        memory = malloc(capacity);
        st = rtk_scene_from_blob(blob, blob_size, memory, capacity, &from_blob, &needed);
        if (st == RTK_ERR_NOMEM) {
            cr_assert_gt(needed, capacity, "needed %zu must exceed the capacity %zu", needed, capacity);
            capacity = needed;
        }
    }
    cr_assert_eq(st, RTK_OK, "%s after %d attempts", rtk_status_name(st), attempts);
    cr_expect_gt(attempts, 1, "64 bytes cannot have been enough");
    render_hash(from_blob, got);
    cr_expect_str_eq(got, want);
    char err[RTK_ERROR_SIZE];
    cr_expect_null(rtk_debug_pixel_json(from_blob, 0, 0, RTK_ALL_SAMPLES, err, sizeof err));
    free(memory);
    free(blob);
    rtk_close(s);
}

Test(api, a_blob_of_garbage_is_invalid)
{
    static uint8_t memory[1 << 16];
    const rtk_scene *s;
    cr_expect_eq(rtk_scene_from_blob("not a blob", 10, memory, sizeof memory, &s, NULL), RTK_ERR_INVALID);
}

Test(api, debug_json_is_the_commands, .init = cr_redirect_stderr)
{
    rtk_scene *s = open_small();
    char err[RTK_ERROR_SIZE];
    char *json = rtk_debug_pixel_json(s, 20, 15, RTK_ALL_SAMPLES, err, sizeof err);
    cr_assert(json, "%s", err);
    char *out = NULL;
    char *argv[] = {"debug", SCENE, "--width", "40", "--height", "30", "--pixel", "20,15", "--json", NULL};
    cr_assert_eq(capture_stdout(rtp_cmd_debug, 9, argv, &out), RTP_EXIT_OK);
    cr_expect_str_eq(json, out);
    free(out);
    free(json);
    cr_expect_null(rtk_debug_pixel_json(s, 40, 0, RTK_ALL_SAMPLES, err, sizeof err));
    cr_expect(strstr(err, "no pixel (40, 0)") != NULL, "%s", err);
    rtk_close(s);
}

Test(api, errors_are_values_with_one_line)
{
    char err[RTK_ERROR_SIZE];
    rtk_scene *s = (rtk_scene *)1;
    cr_expect_eq(rtk_open("no/such/scene.yaml", NULL, &s, err, sizeof err), RTK_ERR_INPUT);
    cr_expect(strstr(err, "no/such/scene.yaml") != NULL && !strchr(err, '\n'), "%s", err);
    cr_expect_eq(s, (rtk_scene *)1, "the output is left alone on failure");
    rtk_options opt = rtk_default_options();
    opt.depth = 65;
    cr_expect_eq(rtk_open(SCENE, &opt, &s, err, sizeof err), RTK_ERR_INVALID);
    opt = rtk_default_options();
    opt.max_memory = 1024;
    cr_expect_eq(rtk_open(SCENE, &opt, &s, err, sizeof err), RTK_ERR_NOMEM, "%s", err);
    /* That refusal is not the next open's: a missing file is still an input error. */
    cr_expect_eq(rtk_open("no/such/scene.yaml", NULL, &s, err, sizeof err), RTK_ERR_INPUT, "%s", err);
    cr_expect_eq(rtk_write_image("no/such/folder/out.png", (const uint8_t *)"\0\0\0", 1, 1, err, sizeof err),
                 RTK_ERR_OUTPUT);
    rtk_close(NULL);
}

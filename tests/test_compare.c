/* Image comparison: metrics on hand-made pairs, the heat map, and `rtk compare` exit codes. */
#include "cli/compare_cmd.h"
#include "cli/exit_codes.h"
#include "image/image_compare.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static char dir[64], path_a[128], path_b[128], path_small[128];

/* 4x4 test images: b equals a except pixel (2, 1), whose green is 3 higher. */
static uint8_t px_a[4 * 4 * 3], px_b[4 * 4 * 3];
static const rtp_image img_a = {.width = 4, .height = 4, .rgb = px_a};
static const rtp_image img_b = {.width = 4, .height = 4, .rgb = px_b};

static void setup(void)
{
    for (int i = 0; i < 4 * 4 * 3; i++) px_a[i] = px_b[i] = (uint8_t)(i * 5 + 20);
    px_b[3 * (1 * 4 + 2) + 1] += 3;

    cr_assert(tmpdir_make(dir, sizeof dir, "compare"), "cannot create a scratch folder");
    snprintf(path_a, sizeof path_a, "%s/a.ppm", dir);
    snprintf(path_b, sizeof path_b, "%s/b.png", dir);
    snprintf(path_small, sizeof path_small, "%s/small.ppm", dir);
    char err[256];
    rtp_image small = {.width = 2, .height = 2, .rgb = px_a};
    cr_assert(rtp_image_write(path_a, &img_a, err, sizeof err), "%s", err);
    cr_assert(rtp_image_write(path_b, &img_b, err, sizeof err), "%s", err);
    cr_assert(rtp_image_write(path_small, &small, err, sizeof err), "%s", err);
    cr_redirect_stdout();
    cr_redirect_stderr();
}

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(compare, .init = setup, .fini = teardown);

Test(compare, identical_images_have_infinite_psnr)
{
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&img_a, &img_a, &m));
    cr_expect(isinf(m.psnr) && m.psnr > 0, "PSNR %f", m.psnr);
    cr_expect_eq(m.max_diff, 0);
    cr_expect_eq(m.mean_diff, 0.0);
    cr_expect_eq(m.within0_pct, 100.0);
    cr_expect_eq(m.pixels_over2, 0);
    cr_expect(m.worst_x == 0 && m.worst_y == 0);
}

Test(compare, one_channel_off_by_three)
{
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&img_a, &img_b, &m));
    /* 48 channels, one squared error of 9: PSNR = 10 log10(255^2 * 48 / 9) = 10 log10(346800)
     * = 10 (5 + log10 3.468) = 55.40079088804...; the digits evaluated with python3's math.log10. */
    cr_expect_float_eq(m.psnr, 55.400790888041726, 1e-9, "PSNR %.15f", m.psnr);
    cr_expect_float_eq(m.mean_diff, 3.0 / 48, 1e-12);
    cr_expect_eq(m.max_diff, 3);
    cr_expect_float_eq(m.within0_pct, 100.0 * 47 / 48, 1e-9);
    cr_expect_float_eq(m.within2_pct, 100.0 * 47 / 48, 1e-9);
    cr_expect_eq(m.within8_pct, 100.0);
    cr_expect_eq(m.pixels_over2, 1);
    cr_expect_eq(m.worst_x, 2);
    cr_expect_eq(m.worst_y, 1);
    cr_expect_arr_eq(m.worst_a, px_a + 3 * 6, 3);
    cr_expect_arr_eq(m.worst_b, px_b + 3 * 6, 3);
}

Test(compare, worst_pixel_is_the_first_in_row_major_order)
{
    uint8_t pa[5 * 3 * 3] = {0}, pb[5 * 3 * 3] = {0};
    pb[3 * (0 * 5 + 0) + 0] = 5; /* (0, 0) off by 5: not the worst */
    pb[3 * (1 * 5 + 3) + 2] = 7; /* (3, 1) off by 7: first of the worst */
    pb[3 * (2 * 5 + 1) + 1] = 7; /* (1, 2) off by 7: a smaller x, but a later row */
    rtp_image a = {.width = 5, .height = 3, .rgb = pa}, b = {.width = 5, .height = 3, .rgb = pb};
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&a, &b, &m));
    cr_expect_eq(m.max_diff, 7);
    cr_expect_eq(m.worst_x, 3);
    cr_expect_eq(m.worst_y, 1);
    cr_expect_arr_eq(m.worst_b, ((uint8_t[]){0, 0, 7}), 3);
    cr_expect_eq(m.pixels_over2, 3);
    cr_expect_float_eq(m.mean_diff, 19.0 / 45, 1e-12);
}

Test(compare, within_shares_include_their_bound)
{
    uint8_t pa[2 * 3] = {100, 100, 100, 100, 100, 100}, pb[2 * 3] = {100, 101, 98, 103, 108, 91};
    rtp_image a = {.width = 2, .height = 1, .rgb = pa}, b = {.width = 2, .height = 1, .rgb = pb};
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&a, &b, &m)); /* differences 0 1 2 3 8 9 */
    cr_expect_float_eq(m.within0_pct, 100.0 / 6, 1e-9);
    cr_expect_float_eq(m.within1_pct, 200.0 / 6, 1e-9);
    cr_expect_float_eq(m.within2_pct, 300.0 / 6, 1e-9);
    cr_expect_float_eq(m.within8_pct, 500.0 / 6, 1e-9);
    cr_expect_eq(m.max_diff, 9);
    cr_expect(m.worst_x == 1 && m.worst_y == 0);
}

Test(compare, different_sizes_are_refused)
{
    rtp_image small = {.width = 2, .height = 8, .rgb = px_a};
    rtp_image_metrics m;
    cr_expect_not(rtp_image_compare(&img_a, &small, &m));
}

Test(compare, heat_map_ramp)
{
    static const uint8_t diffs[7] = {0, 1, 2, 4, 16, 64, 200};
    static const uint8_t want[7][3] = {
        {0, 0, 0}, {0, 0, 255}, {0, 85, 170}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}, {255, 0, 0},
    };
    uint8_t pa[7 * 3] = {0}, pb[7 * 3] = {0};
    for (int i = 0; i < 7; i++)
        pb[3 * i + i % 3] = diffs[i]; /* the largest channel difference may sit in any channel */
    rtp_image a = {.width = 7, .height = 1, .rgb = pa}, b = {.width = 7, .height = 1, .rgb = pb}, map;
    cr_assert(rtp_image_diff_map(&a, &b, &map));
    for (int i = 0; i < 7; i++) cr_expect_arr_eq(map.rgb + 3 * i, want[i], 3, "difference %d", diffs[i]);
    rtp_image_free(&map);
}

/* Runs `rtk compare` with the arguments up to NULL. */
static int cmd(const char *first, ...)
{
    char *argv[16] = {"compare", (char *)first};
    int argc = 2;
    va_list ap;
    va_start(ap, first);
    for (const char *s; argc < 15 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    va_end(ap);
    return rtp_cmd_compare(argc, argv);
}

Test(compare, thresholds_set_the_exit_code)
{
    cr_expect_eq(cmd(path_a, path_a, NULL), RTP_EXIT_OK);
    cr_expect_eq(cmd(path_a, path_b, NULL), RTP_EXIT_OK);
    cr_expect_eq(cmd(path_a, path_b, "--min-psnr", "55.4", NULL), RTP_EXIT_OK);
    cr_expect_eq(cmd(path_a, path_b, "--min-psnr", "55.41", NULL), RTP_EXIT_THRESHOLD);
    cr_expect_eq(cmd(path_a, path_a, "--min-psnr", "inf", NULL), RTP_EXIT_OK);
    cr_expect_eq(cmd(path_a, path_b, "--max-diff", "3", NULL), RTP_EXIT_OK);
    cr_expect_eq(cmd(path_a, path_b, "--max-diff", "2", NULL), RTP_EXIT_THRESHOLD);
    cr_expect_eq(cmd("--max-diff", "2", path_a, path_b, "--json", NULL), RTP_EXIT_THRESHOLD);
}

Test(compare, unreadable_or_mismatched_inputs)
{
    char missing[160];
    snprintf(missing, sizeof missing, "%s/none.png", dir);
    cr_expect_eq(cmd(path_a, path_small, NULL), RTP_EXIT_INPUT);
    cr_expect_eq(cmd(missing, path_a, NULL), RTP_EXIT_INPUT);
    cr_expect_eq(cmd(path_a, dir, NULL), RTP_EXIT_INPUT);
}

Test(compare, bad_arguments_are_usage_errors)
{
    cr_expect_eq(rtp_cmd_compare(1, (char *[]){"compare", NULL}), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, path_a, NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, "--bogus", NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, "--max-diff", NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, "--max-diff", "256", NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, "--max-diff", "2x", NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd(path_a, path_b, "--min-psnr", "nan", NULL), RTP_EXIT_USAGE);
    cr_expect_eq(cmd("--help", NULL), RTP_EXIT_OK);
}

Test(compare, writes_the_heat_map)
{
    char heat[160], bad[160], err[256];
    snprintf(heat, sizeof heat, "%s/heat.png", dir);
    snprintf(bad, sizeof bad, "%s/missing/heat.png", dir);
    cr_assert_eq(cmd(path_a, path_b, "--diff", heat, NULL), RTP_EXIT_OK);
    rtp_image map;
    cr_assert(rtp_image_read(heat, &map, err, sizeof err), "%s", err);
    cr_expect(map.width == 4 && map.height == 4);
    cr_expect_arr_eq(map.rgb, ((uint8_t[]){0, 0, 0}), 3);
    cr_expect_arr_eq(map.rgb + 3 * 6, ((uint8_t[]){0, 170, 85}), 3, "(2, 1) off by 3");
    rtp_image_free(&map);
    cr_expect_eq(cmd(path_a, path_b, "--diff", bad, NULL), RTP_EXIT_OUTPUT);
}

Test(compare, json_reports_inf_as_a_string)
{
    cr_assert_eq(cmd(path_a, path_a, "--json", NULL), RTP_EXIT_OK);
    fflush(stdout);
    char out[2048] = "";
    size_t n = fread(out, 1, sizeof out - 1, cr_get_redirected_stdout());
    out[n] = '\0';
    cr_expect(out[0] == '{' && n > 2 && out[n - 2] == '}' && out[n - 1] == '\n', "not one object: %s", out);
    cr_expect(strstr(out, "\"psnr\": \"inf\""), "%s", out);
    cr_expect(strstr(out, "\"worst\": {\"x\": 0, \"y\": 0"), "%s", out);
    cr_expect(strstr(out, "\"within_pct\": {\"0\": 100.000000"), "%s", out);
}

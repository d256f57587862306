/* Image I/O: PNG and PPM round trips, the solution images, hostile files, atomic writes. */
#include "image/file_write.h"
#include "image/image.h"
#include "reference.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

static char dir[64];

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "image"), "cannot create a scratch folder"); }

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(image, .init = setup, .fini = teardown);

static const char *in_dir(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", dir, name);
    return buf;
}

/* A solution image of the shared corpus (rt_test_trace_dir: ../shared or $RTK_SHARED). */
static const char *solution(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/solution/%s", rt_test_trace_dir(), name);
    return buf;
}

static void put_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot create %s", path);
    cr_assert_eq(fwrite(data, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
}

/* Returns the whole file (malloc'd) and its size. */
static unsigned char *get_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    unsigned char *buf = malloc(1 << 20);
    *size = fread(buf, 1, 1 << 20, f);
    fclose(f);
    return buf;
}

/* 7x5 with every channel different, so a swapped axis or channel shows. */
static rtp_image pattern(uint8_t storage[7 * 5 * 3])
{
    for (int i = 0; i < 7 * 5 * 3; i++) storage[i] = (uint8_t)(i * 37 + 11);
    return (rtp_image){.width = 7, .height = 5, .rgb = storage};
}

static void round_trip(const char *name)
{
    uint8_t px[7 * 5 * 3];
    rtp_image img = pattern(px), back;
    char path[128], err[256];
    in_dir(path, sizeof path, name);
    cr_assert(rtp_image_write(path, &img, err, sizeof err), "%s", err);
    cr_assert(rtp_image_read(path, &back, err, sizeof err), "%s", err);
    cr_assert_eq(back.width, 7);
    cr_assert_eq(back.height, 5);
    cr_assert_arr_eq(back.rgb, px, sizeof px);
    rtp_image_free(&back);
    cr_assert_null(back.rgb);
}

Test(image, png_round_trip_is_bit_identical) { round_trip("a.png"); }

Test(image, ppm_round_trip_is_bit_identical) { round_trip("a.ppm"); }

Test(image, png_chosen_by_extension_in_any_case)
{
    uint8_t px[7 * 5 * 3];
    rtp_image img = pattern(px);
    char path[128], err[256];
    size_t size;
    cr_assert(rtp_image_write(in_dir(path, sizeof path, "up.PNG"), &img, err, sizeof err), "%s", err);
    unsigned char *bytes = get_file(path, &size);
    cr_expect_arr_eq(bytes, "\x89PNG\r\n\x1a\n", 8);
    free(bytes);
    cr_assert(rtp_image_write(in_dir(path, sizeof path, "a.png.out"), &img, err, sizeof err), "%s", err);
    bytes = get_file(path, &size);
    cr_expect_arr_eq(bytes, "P6\n", 3);
    free(bytes);
}

/* The filter type of each of the PNG's rows (h of them): its IDAT chunks inflated. */
static void png_row_filters(const unsigned char *png, size_t size, uint32_t w, uint32_t h, uint8_t *filters)
{
    unsigned char *idat = malloc(size), *raw = malloc((size_t)h * (1 + w * 3));
    size_t idat_size = 0;
    for (size_t at = 8; at + 12 <= size;) {
        uint32_t len = (uint32_t)png[at] << 24 | (uint32_t)png[at + 1] << 16 | (uint32_t)png[at + 2] << 8 | png[at + 3];
        if (memcmp(png + at + 4, "IDAT", 4) == 0) memcpy(idat + idat_size, png + at + 8, len), idat_size += len;
        at += 12 + (size_t)len;
    }
    uLongf raw_size = (uLongf)h * (1 + w * 3);
    cr_assert_eq(uncompress(raw, &raw_size, idat, idat_size), Z_OK);
    cr_assert_eq(raw_size, (uLongf)h * (1 + w * 3));
    for (uint32_t y = 0; y < h; y++) filters[y] = raw[(size_t)y * (1 + w * 3)];
    free(idat);
    free(raw);
}

/* Writes img as PNG, reads it back (same pixels) and returns how many rows are filtered. */
static uint32_t filtered_rows(rtp_image img, const char *name)
{
    char path[128], err[256];
    cr_assert(rtp_image_write(in_dir(path, sizeof path, name), &img, err, sizeof err), "%s", err);
    rtp_image back;
    cr_assert(rtp_image_read(path, &back, err, sizeof err), "%s", err);
    cr_assert_arr_eq(back.rgb, img.rgb, (size_t)img.width * img.height * 3);
    rtp_image_free(&back);
    size_t size;
    unsigned char *png = get_file(path, &size);
    uint8_t filters[64];
    png_row_filters(png, size, img.width, img.height, filters);
    free(png);
    uint32_t count = 0;
    for (uint32_t y = 0; y < img.height; y++) count += filters[y] != 0;
    return count;
}

/* Flat images (most pixels repeat their left neighbour, as in a Whitted render) are
 * written unfiltered; varied ones with libspng's adaptive choice, which a gradient
 * makes filter every row. */
Test(image, png_rows_unfiltered_only_when_the_image_is_flat)
{
    static uint8_t px[64 * 64 * 3];
    for (uint32_t i = 0; i < sizeof px; i++) px[i] = (uint8_t)((i / 3) % 64 < 40 ? 200 : i % 7);
    cr_expect_eq(filtered_rows((rtp_image){.width = 64, .height = 64, .rgb = px}, "flat.png"), 0);
    for (uint32_t i = 0; i < sizeof px; i++) px[i] = (uint8_t)(i / 3 % 64 * 3 + i / 192);
    cr_expect_eq(filtered_rows((rtp_image){.width = 64, .height = 64, .rgb = px}, "gradient.png"), 64);
}

/* The render hash is defined on these exact bytes (core/sha256.h). */
Test(image, ppm_bytes_are_the_canonical_p6)
{
    uint8_t px[7 * 5 * 3];
    rtp_image img = pattern(px);
    char path[128], err[256];
    cr_assert(rtp_image_write(in_dir(path, sizeof path, "c.ppm"), &img, err, sizeof err), "%s", err);
    size_t size;
    unsigned char *bytes = get_file(path, &size);
    cr_assert_eq(size, 11 + sizeof px);
    cr_expect_arr_eq(bytes, "P6\n7 5\n255\n", 11);
    cr_expect_arr_eq(bytes + 11, px, sizeof px);
    free(bytes);
}

Test(image, ppm_header_comments_and_whitespace)
{
    static const char file[] = "P6 # made by hand\n# second comment\n2\t1\r\n255\n\x01\x02\x03\x04\x05\x06";
    char path[128], err[256];
    put_file(in_dir(path, sizeof path, "c.ppm"), file, sizeof file - 1);
    rtp_image img;
    cr_assert(rtp_image_read(path, &img, err, sizeof err), "%s", err);
    cr_expect_eq(img.width, 2);
    cr_expect_eq(img.height, 1);
    cr_expect_arr_eq(img.rgb, "\x01\x02\x03\x04\x05\x06", 6);
    rtp_image_free(&img);
}

/* Expected pixels were looked up once with python3 (tools/fidelity's read_png_rgb). */
static void expect_pixel(const char *name, uint32_t x, uint32_t y, int r, int g, int b)
{
    rtp_image img;
    char path[4096], err[4200];
    cr_assert(rtp_image_read(solution(path, sizeof path, name), &img, err, sizeof err), "%s", err);
    cr_expect_eq(img.width, 512);
    cr_expect_eq(img.height, 512);
    const uint8_t *p = img.rgb + 3 * ((size_t)y * img.width + x);
    cr_expect(p[0] == r && p[1] == g && p[2] == b, "%s (%u, %u) is (%d, %d, %d), want (%d, %d, %d)", name, x, y, p[0],
              p[1], p[2], r, g, b);
    rtp_image_free(&img);
}

Test(image, reads_rgb_solution_png)
{
    expect_pixel("texture_reflection_3.png", 69, 438, 99, 100, 101);
    expect_pixel("box_cyl_reflect_3.png", 511, 511, 160, 3, 3);
}

Test(image, reads_rgba_solution_png_dropping_alpha)
{
    expect_pixel("revolution_texture_3.png", 318, 198, 36, 50, 54);
    expect_pixel("box_3.png", 256, 256, 78, 0, 0);
}

static void expect_read_error(const char *path, const char *want)
{
    rtp_image img = {.width = 1, .height = 1, .rgb = (uint8_t *)"junk"};
    char err[256] = "";
    cr_assert_not(rtp_image_read(path, &img, err, sizeof err), "%s read without error", path);
    cr_expect_null(img.rgb, "a failed read leaves no pixels");
    cr_expect(strncmp(err, path, strlen(path)) == 0 && strncmp(err + strlen(path), ": ", 2) == 0,
              "error '%s' does not start with the path", err);
    cr_expect(strstr(err, want) != NULL, "error '%s' lacks '%s'", err, want);
}

static void expect_bad_file(const char *contents, size_t size, const char *want)
{
    char path[128];
    put_file(in_dir(path, sizeof path, "bad"), contents, size);
    expect_read_error(path, want);
}

#define BAD(literal, want) expect_bad_file(literal, sizeof literal - 1, want)

Test(image, hostile_ppm_files_fail_cleanly)
{
    BAD("", "empty file");
    BAD("hello, world", "unrecognised signature");
    BAD("P3\n1 1\n255\n1 2 3\n", "only binary P6");
    BAD("P6\n2 2\n65535\n", "maxval 65535");
    BAD("P6\n2 2\n255\nabc", "truncated PPM");
    BAD("P6\n2 2\n255", "whitespace after maxval");
    BAD("P6\n99999 2\n255\n", "exceeds the 16384x16384 limit");
    BAD("P6\n0 2\n255\n", "zero width or height");
    BAD("P6\nx", "expected the width");
    BAD("P6\n99999999999 1\n255\n", "expected the width");
    BAD("P6\n# only a comment", "expected the width");
}

/* A PNG signature and IHDR claiming w x h, CRC included, and no image data. */
static void put_png_header(const char *path, uint32_t w, uint32_t h)
{
    unsigned char f[33] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (int i = 0; i < 4; i++) {
        f[16 + i] = (unsigned char)(w >> (24 - 8 * i));
        f[20 + i] = (unsigned char)(h >> (24 - 8 * i));
    }
    f[24] = 8;                  /* bit depth */
    f[25] = 2;                  /* RGB */
    uint32_t crc = 0xffffffffu; /* CRC-32 over type and data, as PNG specifies */
    for (int i = 12; i < 29; i++) {
        crc ^= f[i];
        for (int k = 0; k < 8; k++) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1)));
    }
    crc = ~crc;
    for (int i = 0; i < 4; i++) f[29 + i] = (unsigned char)(crc >> (24 - 8 * i));
    put_file(path, f, sizeof f);
}

Test(image, hostile_png_files_fail_cleanly)
{
    char path[128], box[4096];
    in_dir(path, sizeof path, "bad.png");
    BAD("\x89PNG\r\n\x1a\nthis is not a png, just text", "invalid PNG");

    put_png_header(path, 100000, 100000);
    expect_read_error(path, "exceeds the 16384x16384 image limit");
    put_png_header(path, 64, 64);
    expect_read_error(path, "truncated PNG");

    size_t size;
    unsigned char *png = get_file(solution(box, sizeof box, "box_3.png"), &size);
    cr_assert_gt(size, 3000);
    put_file(path, png, 3000);
    expect_read_error(path, "truncated PNG");
    png[30] ^= 0xff; /* inside the IHDR CRC, which no longer matches */
    put_file(path, png, size);
    expect_read_error(path, "invalid PNG");
    free(png);
}

Test(image, missing_file_and_directory_fail)
{
    char path[128];
    expect_read_error(in_dir(path, sizeof path, "none.png"), "No such file");
    expect_read_error(dir, "is a directory");
}

Test(image, atomic_write_into_missing_folder_leaves_nothing)
{
    char path[128], err[256] = "";
    in_dir(path, sizeof path, "missing/out.ppm");
    cr_assert_not(rtp_file_write(path, "x", 1, err, sizeof err));
    cr_expect(strstr(err, path) == err && strstr(err, "directory does not exist"), "error: %s", err);
    cr_expect_eq(tmpdir_count(dir), 0);
}

Test(image, atomic_write_over_a_directory_leaves_nothing)
{
    char path[128], err[256] = "";
    in_dir(path, sizeof path, "sub");
    cr_assert_eq(mkdir(path, 0777), 0);
    cr_assert_not(rtp_file_write(path, "x", 1, err, sizeof err));
    cr_expect(strstr(err, "is a directory"), "error: %s", err);
    cr_expect_eq(tmpdir_count(dir), 1, "a temporary file was left behind");
    cr_expect_eq(tmpdir_count(path), 0);
}

Test(image, atomic_write_replaces_existing_file)
{
    char path[128], err[256];
    in_dir(path, sizeof path, "f.txt");
    put_file(path, "old contents, longer than the new", 33);
    cr_assert(rtp_file_write(path, "new", 3, err, sizeof err), "%s", err);
    size_t size;
    unsigned char *bytes = get_file(path, &size);
    cr_expect_eq(size, 3);
    cr_expect_arr_eq(bytes, "new", 3);
    free(bytes);
    cr_expect_eq(tmpdir_count(dir), 1);
}

/* Unlike a mkstemp file (0600), the output gets the usual 0666 minus the umask. */
Test(image, atomic_write_honours_umask)
{
    char path[128], err[256];
    mode_t old = umask(027);
    bool ok = rtp_file_write(in_dir(path, sizeof path, "m"), "x", 1, err, sizeof err);
    umask(old);
    cr_assert(ok, "%s", err);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    cr_expect_eq(st.st_mode & 0777, 0640);
}

Test(image, writing_nothing_fails)
{
    char path[128], err[256] = "";
    rtp_image none = {.width = 2, .height = 2, .rgb = NULL};
    cr_expect_not(rtp_image_write(in_dir(path, sizeof path, "n.ppm"), &none, err, sizeof err));
    cr_expect(strstr(err, "no pixels"), "error: %s", err);
    uint8_t px[3] = {0};
    rtp_image empty = {.width = 0, .height = 1, .rgb = px};
    cr_expect_not(rtp_image_write(path, &empty, err, sizeof err));
    cr_expect(strstr(err, "zero width"), "error: %s", err);
    cr_expect_eq(tmpdir_count(dir), 0);
}

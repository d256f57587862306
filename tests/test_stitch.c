/* Distributed renders: parts (`rtk render --part / --region`) stitch to the bytes of the
 * whole frame; the cut; every refusal of `rtk stitch` (one line naming the part and the
 * problem, exit 3, nothing written); --check and --missing; argument errors. */
#include "capture.h"
#include "cli/exit_codes.h"
#include "cli/render_cmd.h"
#include "cli/stitch_cmd.h"
#include "cli/version.h"
#include "image/image.h"
#include "load/scene_open.h"
#include "part/part_cut.h"
#include "part/part_file.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define WIDTH 32
#define HEIGHT 24

static char dir[64], scene[128], texture[128];

/* A textured ball in the bottom half of a 32x24 frame under three point lights, so the
 * bottom rows cost more rays than the top ones. */
static const char scene_text[] =
    "Textures:\n"
    "    Checks: {Path: assets/checks.png}\n"
    "Materials:\n"
    "    Painted:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 1, G: 1, B: 1}, Use Texture: true, Color Map: Checks}\n"
    "Root:\n"
    "    Name: Root\n"
    "    Children:\n"
    "        - Name: Camera\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 0, Z: 4}}\n"
    "              Camera: {Render Width (px): 32, Render Height (px): 24}\n"
    "        - Name: Ball\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: -0.9, Z: 0}, Scale: {X: 0.6, Y: 0.6, Z: 0.6}}\n"
    "              Sphere: {Material: Painted}\n"
    "        - {Name: A, Components: {Transform: {Translation: {X: 2, Y: 3, Z: 4}}, PointLight: {}}}\n"
    "        - {Name: B, Components: {Transform: {Translation: {X: -2, Y: 3, Z: 4}}, PointLight: {}}}\n"
    "        - {Name: C, Components: {Transform: {Translation: {X: 0, Y: -3, Z: 4}}, PointLight: {}}}\n";

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "%s", path);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

/* The 2x2 texture, its first texel `shade` grey. */
static void write_texture(uint8_t shade)
{
    uint8_t rgb[2 * 2 * 3] = {shade, shade, shade, 0, 0, 0, 0, 0, 0, 255, 255, 255};
    rtp_image img = {2, 2, rgb};
    char err[256];
    cr_assert(rtp_image_write(texture, &img, err, sizeof err), "%s", err);
}

static void setup(void)
{
    cr_assert(tmpdir_make(dir, sizeof dir, "stitch"), "cannot create a scratch folder");
    char path[160];
    snprintf(path, sizeof path, "%s/assets", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    snprintf(texture, sizeof texture, "%s/assets/checks.png", dir);
    write_texture(200);
    snprintf(scene, sizeof scene, "%s/scene.yaml", dir);
    write_text(scene, scene_text);
}

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(stitch, .init = setup, .fini = teardown);

/* ---- running rtk in-process ---- */

static int (*inner_cmd)(int, char **);
static char *inner_err;

static int with_stderr(int argc, char **argv) { return capture_stderr(inner_cmd, argc, argv, &inner_err); }

/* Runs cmd (argv[0] = name) with first, if not NULL, and the arguments in ap up to NULL;
 * *out and *err get what it printed (malloc'd). */
static int run(int (*cmd)(int, char **), const char *name, const char *first, va_list ap, char **out, char **err)
{
    char *argv[64] = {(char *)name, (char *)first};
    int argc = first ? 2 : 1;
    for (const char *s; argc < 63 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    inner_cmd = cmd;
    inner_err = NULL;
    int rc = capture_stdout(with_stderr, argc, argv, out);
    *err = inner_err;
    cr_assert(*out && *err, "output not captured");
    return rc;
}

/* `rtk render ...`; fails the test on anything but exit 0 with nothing on stderr. */
static void render(const char *first, ...)
{
    va_list ap;
    va_start(ap, first);
    char *out, *err;
    int rc = run(rtp_cmd_render, "render", first, ap, &out, &err);
    va_end(ap);
    cr_assert_eq(rc, RTP_EXIT_OK, "render failed: %s", err);
    free(out);
    free(err);
}

static int stitch_cmd(char **out, char **err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = run(rtp_cmd_stitch, "stitch", NULL, ap, out, err);
    va_end(ap);
    return rc;
}

static int render_cmd(char **out, char **err, ...)
{
    va_list ap;
    va_start(ap, err);
    int rc = run(rtp_cmd_render, "render", NULL, ap, out, err);
    va_end(ap);
    return rc;
}

/* The whole frame's render hash, as rtk render --hash prints it. */
static char *whole_hash(const char *scene_path, const char *opt, const char *value)
{
    char *out, *err;
    int rc = opt ? render_cmd(&out, &err, scene_path, "--hash", opt, value, NULL)
                 : render_cmd(&out, &err, scene_path, "--hash", NULL);
    cr_assert_eq(rc, RTP_EXIT_OK, "%s", err);
    cr_assert_eq(strlen(out), 65, "%s", out);
    free(err);
    return out;
}

/* dir/sub/part-I-of-N.png, with the folder made. */
static const char *part_path(const char *sub, uint32_t i, uint32_t n)
{
    static char path[16][256];
    static int next;
    char folder[160];
    snprintf(folder, sizeof folder, "%s/%s", dir, sub);
    mkdir(folder, 0777);
    char *p = path[next++ % 16];
    snprintf(p, 256, "%s/part-%u-of-%u.png", folder, i, n);
    return p;
}

static const char *file_in_dir(const char *name)
{
    static char path[8][256];
    static int next;
    char *p = path[next++ % 8];
    snprintf(p, 256, "%s/%s", dir, name);
    return p;
}

/* Renders parts 0..n-1 of scene_path into dir/sub with the extra option pair, if any. */
static void render_parts(const char *scene_path, const char *sub, uint32_t n, const char *opt, const char *value)
{
    for (uint32_t i = 0; i < n; i++) {
        char part[32], threads[8], tile[8];
        snprintf(part, sizeof part, "%u/%u", i, n);
        /* Thread count and tile size vary from part to part: the pixels must not care. */
        snprintf(threads, sizeof threads, "%u", 1 + i % 2);
        snprintf(tile, sizeof tile, "%u", 3 + i % 5);
        if (opt)
            render(scene_path, "--part", part, "-o", part_path(sub, i, n), "--threads", threads, "--tile", tile, opt,
                   value, NULL);
        else
            render(scene_path, "--part", part, "-o", part_path(sub, i, n), "--threads", threads, "--tile", tile, NULL);
    }
}

static void copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
    cr_assert(in && out);
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0) cr_assert_eq(fwrite(buf, 1, n, out), n);
    fclose(in);
    cr_assert_eq(fclose(out), 0);
}

static uint8_t *read_bytes(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s", path);
    fseek(f, 0, SEEK_END);
    *size = (size_t)ftell(f);
    rewind(f);
    uint8_t *bytes = malloc(*size);
    cr_assert_eq(fread(bytes, 1, *size, f), *size);
    fclose(f);
    return bytes;
}

static void write_bytes(const char *path, const uint8_t *bytes, size_t size)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(bytes, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
}

/* ---- stitched frames hash as whole frames ---- */

/* Stitches the N parts in dir/sub and returns the printed hash. */
static char *stitched_hash(const char *sub, uint32_t n)
{
    char *argv[40];
    uint32_t argc = 0;
    argv[argc++] = "stitch";
    for (uint32_t i = 0; i < n && argc < 36; i++) argv[argc++] = strdup(part_path(sub, i, n));
    argv[argc++] = "--hash";
    char *out;
    int rc = capture_stdout(rtp_cmd_stitch, (int)argc, argv, &out);
    for (uint32_t i = 1; i + 1 < argc; i++) free(argv[i]);
    cr_assert_eq(rc, RTP_EXIT_OK, "stitch of %u parts failed", n);
    return out;
}

Test(stitch, parts_hash_as_the_whole_frame)
{
    char *whole = whole_hash(scene, NULL, NULL);
    static const uint32_t counts[] = {1, 2, 3, 7, 24};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++) {
        char sub[16];
        snprintf(sub, sizeof sub, "n%u", counts[k]);
        render_parts(scene, sub, counts[k], NULL, NULL);
        char *got = stitched_hash(sub, counts[k]);
        cr_expect_str_eq(got, whole, "%u parts", counts[k]);
        free(got);
    }
    free(whole);
}

Test(stitch, parts_with_settings_hash_as_the_whole_frame)
{
    char *whole = whole_hash(scene, "--spp", "4");
    render_parts(scene, "spp", 5, "--spp", "4");
    char *got = stitched_hash("spp", 5);
    cr_expect_str_eq(got, whole);
    free(got);
    free(whole);
}

Test(stitch, regions_stitch_to_the_whole_frame_and_file)
{
    const char *a = file_in_dir("a.png"), *b = file_in_dir("b.png"), *c = file_in_dir("c.png");
    render(scene, "--region", "0,0,10,24", "-o", a, NULL);
    render(scene, "--region", "10,0,32,7", "-o", b, NULL);
    render(scene, "--region", "10,7,32,24", "-o", c, NULL);
    const char *ppm = file_in_dir("frame.ppm"), *whole_ppm = file_in_dir("whole.ppm");
    char *out, *err;
    cr_assert_eq(stitch_cmd(&out, &err, c, a, b, "-o", ppm, NULL), RTP_EXIT_OK, "%s", err);
    render(scene, "-o", whole_ppm, NULL);
    size_t n1, n2;
    uint8_t *got = read_bytes(ppm, &n1), *want = read_bytes(whole_ppm, &n2);
    cr_expect(n1 == n2 && !memcmp(got, want, n1), "the stitched PPM differs from the whole render's");
    free(got);
    free(want);
    free(out);
    free(err);
}

Test(stitch, parts_of_a_moved_copy_of_the_scene_fit)
{
    /* Digests are of bytes, not paths: a copy of the scene and its assets elsewhere (another
     * machine's mount point) renders parts that stitch with the original's. */
    char copy[160], path[200];
    snprintf(copy, sizeof copy, "%s/elsewhere", dir);
    cr_assert_eq(mkdir(copy, 0777), 0);
    snprintf(path, sizeof path, "%s/assets", copy);
    cr_assert_eq(mkdir(path, 0777), 0);
    snprintf(path, sizeof path, "%s/assets/checks.png", copy);
    copy_file(texture, path);
    snprintf(path, sizeof path, "%s/scene.yaml", copy);
    copy_file(scene, path);
    render_parts(scene, "moved", 2, NULL, NULL);
    render(path, "--part", "1/2", "-o", part_path("moved", 1, 2), NULL);
    char *got = stitched_hash("moved", 2), *whole = whole_hash(scene, NULL, NULL);
    cr_expect_str_eq(got, whole);
    free(got);
    free(whole);
}

/* ---- the cut ---- */

Test(stitch, cut_is_balanced_and_independent_of_threads)
{
    rtp_scene built;
    rtp_scene_options opt = rtp_scene_default_options();
    char err[RTP_ERR_SIZE];
    cr_assert_eq(rtp_scene_open(scene, &opt, &built, err, sizeof err), RTP_EXIT_OK, "%s", err);
    for (uint32_t n = 1; n <= HEIGHT; n++) {
        uint32_t one[HEIGHT + 1], two[HEIGHT + 1];
        cr_assert(rtp_part_cut(&built.scene, n, 1, one));
        cr_assert(rtp_part_cut(&built.scene, n, 2, two));
        cr_expect_arr_eq(one, two, (n + 1) * sizeof one[0], "%u parts: the cut depends on the thread count", n);
        cr_expect(one[0] == 0 && one[n] == HEIGHT);
        for (uint32_t i = 0; i < n; i++) cr_expect_lt(one[i], one[i + 1], "%u parts: band %u is empty", n, i);
    }
    /* The ball's rows (the bottom half) trace four rays a pixel, the sky's one: halving
     * the cost puts the cut below the middle row, where equal bands would cut. */
    uint32_t halves[3];
    cr_assert(rtp_part_cut(&built.scene, 2, 1, halves));
    cr_expect_gt(halves[1], HEIGHT / 2, "cut at row %u", halves[1]);
    rtp_scene_close(&built);
}

/* ---- refusals ---- */

/* Runs stitch over the parts up to NULL into dir/out.png and checks the refusal: exit 3,
 * one line on stderr holding `want`, no output and nothing else left in dir. */
static void expect_refusal(const char *want, ...)
{
    char *argv[40] = {"stitch"};
    int argc = 1;
    va_list ap;
    va_start(ap, want);
    for (const char *s; argc < 36 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    va_end(ap);
    const char *out_path = file_in_dir("out.png");
    argv[argc++] = "-o";
    argv[argc++] = (char *)out_path;
    int before = tmpdir_count(dir);
    inner_cmd = rtp_cmd_stitch;
    char *out;
    int rc = capture_stdout(with_stderr, argc, argv, &out);
    char *err = inner_err;
    cr_assert_not_null(err);
    cr_expect_eq(rc, RTP_EXIT_INPUT, "exit %d for '%s': %s", rc, want, err);
    cr_expect(strstr(err, want), "stderr lacks '%s': %s", want, err);
    char *newline = strchr(err, '\n');
    cr_expect(newline && newline[1] == '\0', "not one line: %s", err);
    cr_expect(strncmp(err, "rtk stitch: ", 12) == 0, "%s", err);
    cr_expect_neq(access(out_path, F_OK), 0, "an output was written");
    cr_expect_eq(tmpdir_count(dir), before, "something was left in the folder");
    free(out);
    free(err);
}

static void good_parts(void) { render_parts(scene, "good", 4, NULL, NULL); }

#define P(i) part_path("good", i, 4)

Test(stitch, refuses_a_missing_part)
{
    good_parts();
    expect_refusal("part 2/4 is missing: no part covers pixel (0, ", P(0), P(1), P(3), NULL);
}

Test(stitch, refuses_a_gap_between_regions)
{
    const char *a = file_in_dir("a.png"), *b = file_in_dir("b.png");
    render(scene, "--region", "0,0,32,10", "-o", a, NULL);
    render(scene, "--region", "0,10,31,24", "-o", b, NULL);
    expect_refusal("a gap: no part covers pixel (31, 10) of the 32x24 frame", a, b, NULL);
}

Test(stitch, refuses_an_overlap)
{
    good_parts();
    const char *r = file_in_dir("r.png");
    render(scene, "--region", "5,0,6,24", "-o", r, NULL);
    expect_refusal("r.png: overlaps ", P(0), P(1), P(2), P(3), r, NULL);
}

Test(stitch, refuses_a_duplicated_part)
{
    good_parts();
    const char *dup = file_in_dir("dup.png");
    copy_file(P(1), dup);
    expect_refusal("dup.png: a duplicate: ", P(0), P(1), P(2), P(3), dup, NULL);
    expect_refusal("part-1-of-4.png: given twice", P(0), P(1), P(1), P(2), P(3), NULL);
}

Test(stitch, refuses_a_part_of_another_scene)
{
    good_parts();
    char other[160];
    snprintf(other, sizeof other, "%s/other.yaml", dir);
    write_text(other, scene_text);
    FILE *f = fopen(other, "ab");
    fputs("# one more byte than scene.yaml\n", f);
    fclose(f);
    render(other, "--part", "2/4", "-o", part_path("other", 2, 4), NULL);
    expect_refusal("part-2-of-4.png: other scene file than ", P(0), P(1), part_path("other", 2, 4), P(3), NULL);
}

Test(stitch, refuses_a_part_with_other_assets)
{
    good_parts();
    write_texture(201); /* one level brighter: the same scene file, another texture */
    render(scene, "--part", "2/4", "-o", part_path("assets", 2, 4), NULL);
    expect_refusal("other asset files than ", P(0), P(1), part_path("assets", 2, 4), P(3), NULL);
}

Test(stitch, refuses_a_part_with_other_settings)
{
    good_parts();
    render(scene, "--part", "2/4", "--depth", "1", "-o", part_path("depth", 2, 4), NULL);
    expect_refusal("other settings than ", P(0), P(1), part_path("depth", 2, 4), P(3), NULL);
    render(scene, "--part", "2/4", "--spp", "4", "-o", part_path("spp", 2, 4), NULL);
    expect_refusal("other settings than ", P(0), P(1), part_path("spp", 2, 4), P(3), NULL);
    render(scene, "--part", "2/4", "--width", "31", "-o", part_path("width", 2, 4), NULL);
    expect_refusal("other frame size than ", P(0), P(1), part_path("width", 2, 4), P(3), NULL);
}

/* Rewrites a part with one field changed (a valid part, as another rtk would write it). */
static void forge(const char *from, const char *to, rtp_part_field field, const char *value, bool flip_pixel)
{
    rtp_part p;
    uint8_t *rgb;
    char err[RTP_ERR_SIZE];
    cr_assert(rtp_part_read(from, &p, &rgb, err, sizeof err), "%s", err);
    if (value) cr_assert(rtp_part_set(&p, field, value));
    rgb[0] ^= flip_pixel;
    cr_assert(rtp_part_write(to, &p, rgb, err, sizeof err), "%s", err);
    rtp_part_free(&p);
    free(rgb);
}

Test(stitch, refuses_a_part_of_another_build_or_version)
{
    good_parts();
    const char *fixed = file_in_dir("fixed.png"), *old = file_in_dir("old.png");
    forge(P(2), fixed, RTP_PART_BUILD, "fixed", false);
    expect_refusal("fixed.png: other build than ", P(0), P(1), fixed, P(3), NULL);
    forge(P(2), old, RTP_PART_VERSION, "rtk 0.4.0 (double build; gcc 12.2.0; commit 000000000000)", false);
    expect_refusal("old.png: other rtk version than ", P(0), P(1), old, P(3), NULL);
}

/* The version line as this rtk prints it with the compiler (or the commit) replaced. */
static char *other_version(const char *compiler, const char *commit)
{
    const char *line = rtp_version_line(), *semi = strchr(line, ';'), *at = strstr(line, "; commit ");
    cr_assert(semi && at && at > semi, "unexpected version line '%s'", line);
    static char out[256];
    snprintf(out, sizeof out, "%.*s; %s; commit %s", (int)(semi - line), line, compiler,
             commit ? commit : at + strlen("; commit "));
    return out;
}

Test(stitch, the_compiler_alone_does_not_make_another_render)
{
    good_parts();
    const char *clang = file_in_dir("clang.png"), *commit = file_in_dir("commit.png");
    forge(P(2), clang, RTP_PART_VERSION, other_version("clang 14.0.6", NULL), false);
    char *out, *err;
    cr_expect_eq(stitch_cmd(&out, &err, P(0), P(1), clang, P(3), "--hash", NULL), RTP_EXIT_OK, "%s", err);
    free(out);
    free(err);
    forge(P(2), commit, RTP_PART_VERSION, other_version("clang 14.0.6", "0123456789ab)"), false);
    expect_refusal("commit.png: other rtk version than ", P(0), P(1), commit, P(3), NULL);
}

Test(stitch, refuses_a_truncated_part)
{
    good_parts();
    size_t size;
    uint8_t *bytes = read_bytes(P(2), &size);
    const char *half = file_in_dir("half.png"), *no_end = file_in_dir("no_end.png");
    write_bytes(half, bytes, size / 2);
    write_bytes(no_end, bytes, size - 12); /* all but the IEND chunk */
    free(bytes);
    expect_refusal("half.png: truncated", P(0), P(1), half, P(3), NULL);
    expect_refusal("no_end.png: truncated", P(0), P(1), no_end, P(3), NULL);
}

/* The offset of the tEXt chunk with keyword key (its length field), or 0. */
static size_t text_chunk(const uint8_t *png, size_t size, const char *key)
{
    for (size_t p = 8; p + 12 <= size;) {
        size_t len = (size_t)png[p] << 24 | png[p + 1] << 16 | png[p + 2] << 8 | png[p + 3];
        if (!memcmp(png + p + 4, "tEXt", 4) && !strcmp((const char *)png + p + 8, key)) return p;
        p += 12 + len;
    }
    return 0;
}

Test(stitch, refuses_a_corrupt_part)
{
    good_parts();
    size_t size;
    uint8_t *bytes = read_bytes(P(2), &size);
    const char *flipped = file_in_dir("flipped.png");
    bytes[size - 30] ^= 0x10; /* in the image data: its chunk's CRC no longer matches */
    write_bytes(flipped, bytes, size);
    expect_refusal("flipped.png: corrupt PNG", P(0), P(1), flipped, P(3), NULL);

    /* Pixels changed and the PNG rewritten whole, but the old pixel digest kept. */
    const char *tampered = file_in_dir("tampered.png");
    forge(P(2), tampered, RTP_PART_PIXELS, NULL, true);
    bytes[size - 30] ^= 0x10;
    size_t forged_size;
    uint8_t *forged = read_bytes(tampered, &forged_size);
    size_t a = text_chunk(bytes, size, "rtk pixels"), b = text_chunk(forged, forged_size, "rtk pixels");
    cr_assert(a && b);
    memcpy(forged + b, bytes + a, 12 + 11 + 64);
    write_bytes(tampered, forged, forged_size);
    expect_refusal("tampered.png: corrupt: its pixels do not match their digest", P(0), P(1), tampered, P(3), NULL);
    free(forged);
    free(bytes);
}

Test(stitch, refuses_what_is_not_a_part)
{
    good_parts();
    const char *plain = file_in_dir("plain.png"), *text = file_in_dir("text.png"), *none = file_in_dir("none.png");
    render(scene, "-o", plain, NULL);
    write_text(text, "not a PNG at all\n");
    expect_refusal("plain.png: not an rtk part: no 'rtk build' text chunk", plain, NULL);
    expect_refusal("text.png: not an rtk part (not a PNG file)", P(0), text, NULL);
    write_text(text, "");
    expect_refusal("text.png: empty file", P(0), text, NULL);
    expect_refusal("none.png: cannot open: No such file or directory", P(0), P(1), P(2), P(3), none, NULL);
}

/* ---- --check and --missing ---- */

Test(stitch, check_accepts_whole_parts_and_names_broken_ones)
{
    good_parts();
    char *out, *err;
    cr_expect_eq(stitch_cmd(&out, &err, "--check", P(0), P(1), P(2), P(3), NULL), RTP_EXIT_OK);
    cr_expect_str_empty(err);
    cr_expect_str_empty(out);
    free(out);
    free(err);
    size_t size;
    uint8_t *bytes = read_bytes(P(2), &size);
    write_bytes(P(2), bytes, size - 1);
    free(bytes);
    cr_expect_eq(stitch_cmd(&out, &err, "--check", P(0), P(1), P(2), P(3), NULL), RTP_EXIT_INPUT);
    cr_expect(strstr(err, "part-2-of-4.png: truncated") && !strchr(strchr(err, '\n') + 1, '\n'), "%s", err);
    free(out);
    free(err);
}

/* `rtk stitch --missing dir/good scene --tiles 4 [opt value]`'s output. */
static char *missing(const char *opt, const char *value, char **err)
{
    char folder[160], *out;
    snprintf(folder, sizeof folder, "%s/good", dir);
    int rc = opt ? stitch_cmd(&out, err, "--missing", folder, scene, "--tiles", "4", opt, value, NULL)
                 : stitch_cmd(&out, err, "--missing", folder, scene, "--tiles", "4", NULL);
    cr_assert_eq(rc, RTP_EXIT_OK, "%s", *err);
    return out;
}

Test(stitch, missing_lists_absent_and_invalid_parts)
{
    char *err, *out = missing(NULL, NULL, &err);
    cr_expect_str_eq(out, "0\n1\n2\n3\n");
    cr_expect_str_empty(err);
    free(out);
    free(err);
    good_parts();
    out = missing(NULL, NULL, &err);
    cr_expect_str_empty(out);
    cr_expect_str_empty(err);
    free(out);
    free(err);
    /* The same folder holds no part of the render with --depth 1. */
    out = missing("--depth", "1", &err);
    cr_expect_str_eq(out, "0\n1\n2\n3\n");
    cr_expect(strstr(err, "part-0-of-4.png: other settings than "), "%s", err);
    free(out);
    free(err);
    unlink(P(1));
    render(scene, "--part", "2/4", "--depth", "1", "-o", P(2), NULL);
    copy_file(P(0), P(3)); /* part 0 under part 3's name */
    out = missing(NULL, NULL, &err);
    cr_expect_str_eq(out, "1\n2\n3\n");
    cr_expect(strstr(err, "part-2-of-4.png: other settings than "), "%s", err);
    cr_expect(strstr(err, "part-3-of-4.png: holds part 0/4"), "%s", err);
    free(out);
    free(err);
}

/* ---- argument errors ---- */

static void expect_usage(int (*cmd)(int, char **), const char *name, const char *want, ...)
{
    char *argv[32] = {(char *)name};
    int argc = 1;
    va_list ap;
    va_start(ap, want);
    for (const char *s; argc < 31 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    va_end(ap);
    int before = tmpdir_count(dir);
    inner_cmd = cmd;
    char *out;
    int rc = capture_stdout(with_stderr, argc, argv, &out);
    cr_expect_eq(rc, RTP_EXIT_USAGE, "exit %d for '%s': %s", rc, want, inner_err);
    cr_expect(inner_err && strstr(inner_err, want), "stderr lacks '%s': %s", want, inner_err);
    cr_expect_eq(tmpdir_count(dir), before, "something was written");
    free(out);
    free(inner_err);
}

Test(stitch, part_and_region_argument_errors)
{
    const char *o = file_in_dir("p.png");
    expect_usage(rtp_cmd_render, "render", "expected I/N with 0 <= I < N <= 16384 after '--part'", scene, "--part",
                 "4/4", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "--part", "0/0", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "--part", "1", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "--part", "-1/4", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "--part", "1/4x", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "--part", "0/16385", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--part'", scene, "-o", o, "--part", NULL);
    expect_usage(rtp_cmd_render, "render", "--part 0/25: more parts than the frame's 24 rows", scene, "--part", "0/25",
                 "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "expected X0,Y0,X1,Y1 with X0 < X1 and Y0 < Y1 after '--region'", scene,
                 "--region", "5,0,5,9", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--region'", scene, "--region", "0,9,5,3", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--region'", scene, "--region", "1,2,3", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--region'", scene, "--region", "1,2,3,4,5", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "after '--region'", scene, "--region", "0,0,99999999999,1", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "--region 0,0,33,24 lies outside the 32x24 frame", scene, "--region",
                 "0,0,33,24", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "give one --region or --part, not two", scene, "--region", "0,0,1,1",
                 "--part", "0/2", "-o", o, NULL);
    expect_usage(rtp_cmd_render, "render", "a part is a PNG file: expected -o NAME.png", scene, "--part", "0/2", "-o",
                 file_in_dir("p.ppm"), NULL);
    expect_usage(rtp_cmd_render, "render", "--hash is the whole frame's", scene, "--part", "0/2", "-o", o, "--hash",
                 NULL);
}

Test(stitch, stitch_argument_errors)
{
    good_parts();
    char folder[160];
    snprintf(folder, sizeof folder, "%s/good", dir);
    expect_usage(rtp_cmd_stitch, "stitch", "no part files given", "-o", file_in_dir("x.png"), NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "nothing to do: give -o FILE and/or --hash", P(0), NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "unknown option '--bogus'", P(0), "--bogus", "--hash", NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "--check writes no image", "--check", P(0), "--hash", NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "--tiles is for --missing", P(0), "--tiles", "4", "--hash", NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "--missing needs the part count: --tiles N", "--missing", folder, scene,
                 NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "--missing takes one scene file", "--missing", folder, "--tiles", "4", NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "expected 1..16384 after '--parts'", "--missing", folder, scene, "--parts",
                 "0", NULL);
    expect_usage(rtp_cmd_stitch, "stitch", "--tiles 25: more parts than the frame's 24 rows", "--missing", folder,
                 scene, "--tiles", "25", NULL);
}

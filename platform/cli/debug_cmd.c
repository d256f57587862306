/* `rtk debug`: every ray behind one pixel, and why its colour came out as it did. */
#include "cli/debug_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "debug/debug_output.h"
#include "thread/threads.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Rays (and light records) logged per run: far more than a Whitted tree of one pixel
 * needs at the default settings; deep, many-light or heavily sampled pixels are cut
 * short with a note, and their colour stays exact. */

static const char usage[] =
    "usage: rtk debug SCENE.yaml --pixel X,Y [options]\n"
    "\n"
    "Traces one pixel and prints every ray behind it: kind, depth, origin, direction,\n"
    "what it hit (node, primitive, triangle, t, point, normals, uv, material), the terms\n"
    "of every light, and the colour each ray brings back; then the pixel's colour and\n"
    "its 8-bit value, which equal the rendered image's pixel.\n"
    "\n"
    "  --pixel X,Y         the pixel: column X, row Y, (0,0) at the top left of the image\n"
    "  --sample K          trace only sample K (0 .. samples per pixel - 1)\n"
    "  --json              print the ray tree as one JSON document instead of text\n"
    "  --svg FILE          also draw it: the image with the pixel marked, and the rays\n"
    "                      projected on the Z-Y (side) and X-Z (top) planes\n" RTP_CLI_SCENE_OPTIONS_HELP "\n"
    "Exit codes: 0 ok, 2 bad arguments (including a pixel outside the image), 3 bad or\n"
    "missing input file, 4 SVG not writable, 5 over the memory cap.\n";

typedef struct {
    const char *scene, *pixel, *svg;
    rtp_scene_options build;
    uint32_t x, y, sample;
    bool json;
} debug_args;

/* "X,Y" as two whole numbers below the given bounds. */
static bool parse_pixel(const char *s, uint32_t width, uint32_t height, uint32_t *x, uint32_t *y)
{
    char buf[64];
    const char *comma = strchr(s, ',');
    if (!comma || strlen(s) >= sizeof buf) return false;
    memcpy(buf, s, (size_t)(comma - s));
    buf[comma - s] = '\0';
    return width > 0 && height > 0 && rtp_cli_parse_u32(buf, 0, width - 1, x) &&
           rtp_cli_parse_u32(comma + 1, 0, height - 1, y);
}

static int parse_args(int argc, char **argv, debug_args *a)
{
    memset(a, 0, sizeof *a);
    a->build = rtp_scene_default_options();
    a->sample = RTP_PIXEL_ALL_SAMPLES;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        uint32_t n;
        int common = rtp_cli_common_option("debug", usage, argc, argv, &i, &a->build);
        if (common < 0) return -common;
        if (common > 0) continue;
        if (!strcmp(arg, "--pixel")) {
            if (!val) return rtp_cli_usage_error("debug", "missing X,Y after", arg);
            a->pixel = val, i++;
        } else if (!strcmp(arg, "--sample")) {
            if (!rtp_cli_parse_u32(val, 0, UINT32_MAX - 1, &n))
                return rtp_cli_usage_error("debug", "expected a number after", arg);
            a->sample = n, i++;
        } else if (!strcmp(arg, "--svg")) {
            if (!val) return rtp_cli_usage_error("debug", "missing file after", arg);
            a->svg = val, i++;
        } else if (!strcmp(arg, "--json")) {
            a->json = true;
        } else {
            int rc = rtp_cli_scene_argument("debug", arg, &a->scene);
            if (rc != RTP_EXIT_OK) return rc;
        }
    }
    if (!a->scene) return rtp_cli_usage_error("debug", "no scene file given", NULL);
    if (!a->pixel) return rtp_cli_usage_error("debug", "no pixel given: add --pixel X,Y", NULL);
    return RTP_EXIT_OK;
}

/* The pixel and sample exist only once the scene (and its image size) is known. */
static int check_pixel(debug_args *a, const rt_camera *cam)
{
    char what[96];
    if (!parse_pixel(a->pixel, cam->width, cam->height, &a->x, &a->y)) {
        snprintf(what, sizeof what, "expected X,Y with X in 0..%u and Y in 0..%u for --pixel, got", cam->width - 1,
                 cam->height - 1);
        return rtp_cli_usage_error("debug", what, a->pixel);
    }
    uint32_t samples = rt_camera_samples(cam);
    if (a->sample != RTP_PIXEL_ALL_SAMPLES && a->sample >= samples) {
        snprintf(what, sizeof what, "the scene has %u sample%s per pixel; no --sample", samples,
                 samples == 1 ? "" : "s");
        char k[16];
        snprintf(k, sizeof k, "%u", a->sample);
        return rtp_cli_usage_error("debug", what, k);
    }
    return RTP_EXIT_OK;
}

static int write_svg(const debug_args *a, const rtp_pixel_trace *pt)
{
    const rt_scene *scene = &pt->built->scene;
    const rt_camera *cam = &scene->camera;
    rtp_image img = {cam->width, cam->height, calloc((size_t)cam->width * cam->height, 3)};
    if (!img.rgb) {
        fprintf(stderr, "rtk debug: %s: no memory for a %ux%u image\n", a->scene, img.width, img.height);
        return RTP_EXIT_MEMORY;
    }
    rt_tracer tracer = {.scene = scene, .use_bvh = true};
    rtp_threads_options popt = {0, 0, isatty(STDERR_FILENO) != 0, NULL};
    int rc = RTP_EXIT_OK;
    char err[RTP_ERR_SIZE];
    if (!rtp_threads_render(&tracer, &popt, img.rgb)) {
        fprintf(stderr, "rtk debug: %s: the render for the SVG failed\n", a->scene);
        rc = RTP_EXIT_MEMORY;
    } else if (!rtp_debug_write_svg(a->svg, pt, &img, err, sizeof err)) {
        fprintf(stderr, "rtk debug: %s\n", err);
        rc = RTP_EXIT_OUTPUT;
    }
    rtp_image_free(&img);
    return rc;
}

int rtp_cmd_debug(int argc, char **argv)
{
    debug_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc != RTP_EXIT_OK) return rc;
    rtp_scene built;
    rc = rtp_cli_open_scene("debug", a.scene, &a.build, &built);
    if (rc != RTP_EXIT_OK) return rc;
    rtp_pixel_trace pt;
    rc = check_pixel(&a, &built.scene.camera);
    if (rc == RTP_EXIT_OK && !rtp_pixel_trace_run(&pt, &built, a.x, a.y, a.sample, RTP_PIXEL_TRACE_CAPACITY)) {
        fprintf(stderr, "rtk debug: no memory for the ray log\n");
        rc = RTP_EXIT_MEMORY;
    }
    if (rc != RTP_EXIT_OK) {
        rtp_scene_close(&built);
        return rc;
    }
    if (pt.log.overflow)
        fprintf(stderr, "rtk debug: the ray log is full: only the first %u rays are shown\n", RTP_PIXEL_TRACE_CAPACITY);
    if (a.json)
        rtp_debug_print_json(stdout, &pt);
    else
        rtp_debug_print_text(stdout, &pt);
    if (a.svg) rc = write_svg(&a, &pt);
    rtp_pixel_trace_free(&pt);
    rtp_scene_close(&built);
    return rc;
}

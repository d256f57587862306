/* The browser's entry points into rtk (a WASI reactor; web/app/rtk.js calls them). A thin
 * wrapper: scenes are opened by the native loader (platform/load/scene_open.c) from the page's
 * WASI file system, the JSON of debug and compare is printed on stdout by the native
 * code, and errors reach stderr as the native one-line messages. One scene is open at a
 * time per instance; each Web Worker has its own instance. */
#include "rtk_wasm.h"
#include "blob.h"
#include "cli/cli.h"
#include "cli/compare_cmd.h"
#include "cli/exit_codes.h"
#include "debug/debug_output.h"
#include "image/image_compare.h"
#include "sha256.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXPORT(name) __attribute__((export_name(#name)))

/* As `rtk debug`: rays logged for one pixel. */
#define LOG_CAPACITY (1u << 16)

static rtp_scene built;
static bool is_open;
static uint8_t *image; /* a worker's width * height * 3 bytes, for rtk_render_region */
static uint8_t *blob;  /* rtk_pack's bytes, or a worker's blob scene's arena */
static size_t blob_size;

const rtp_scene *rtk_wasm_scene(void) { return &built; }

EXPORT(rtk_alloc) void *rtk_alloc(size_t size) { return malloc(size); }
EXPORT(rtk_free) void rtk_free(void *p) { free(p); }

EXPORT(rtk_close) void rtk_close(void)
{
    if (is_open) rtp_scene_close(&built);
    free(image);
    free(blob);
    image = blob = NULL;
    blob_size = 0;
    is_open = false;
}

static int allocate_image(const char *what)
{
    const rt_camera *cam = &built.scene.camera;
    image = calloc((size_t)cam->width * cam->height, 3);
    if (image) return RTP_EXIT_OK;
    fprintf(stderr, "rtk render: %s: no memory for a %ux%u image\n", what, cam->width, cam->height);
    rtk_close();
    return RTP_EXIT_MEMORY;
}

/* The page's way in (it renders in workers, from rtk_pack's blob): path with --width/--height (0 keeps the file's), --depth/--aa
 * (-1 keeps the file's) and --max-memory in MiB. Returns an RTP_EXIT_* code; on failure
 * the native message is on stderr. */
EXPORT(rtk_open)
int rtk_open(const char *path, uint32_t width, uint32_t height, int32_t depth, int32_t aa, uint32_t max_memory_mib)
{
    rtk_close();
    rtp_scene_options opt = rtp_scene_default_options();
    opt.width = width;
    opt.height = height;
    opt.depth = depth;
    opt.aa = aa;
    opt.max_memory = (size_t)max_memory_mib << 20;
    int rc = rtp_cli_open_scene("render", path, &opt, &built);
    fflush(stderr);
    is_open = rc == RTP_EXIT_OK;
    return rc;
}

EXPORT(rtk_width) uint32_t rtk_width(void) { return built.scene.camera.width; }
EXPORT(rtk_height) uint32_t rtk_height(void) { return built.scene.camera.height; }
EXPORT(rtk_samples) uint32_t rtk_samples(void) { return rt_camera_samples(&built.scene.camera); }
EXPORT(rtk_image) uint8_t *rtk_image(void) { return image; }

/* The open scene as `rtk pack` writes it (overrides applied); rtk_blob_size bytes at the
 * returned address, NULL when out of memory. */
EXPORT(rtk_pack) uint8_t *rtk_pack(void)
{
    free(blob);
    blob_size = rt_blob_size(&built.loaded.desc);
    blob = malloc(blob_size);
    if (blob && rt_blob_write(&built.loaded.desc, blob, blob_size) != blob_size) {
        free(blob);
        blob = NULL;
    }
    return blob;
}
EXPORT(rtk_blob_size) size_t rtk_blob_size(void) { return blob_size; }

/* A worker's way in: builds the scene of a blob (from rtk_pack), growing the arena up to
 * max_memory_mib as rtp_scene_open does. Returns an RTP_EXIT_* code. */
EXPORT(rtk_open_blob) int rtk_open_blob(const uint8_t *bytes, size_t size, uint32_t max_memory_mib)
{
    rtk_close();
    size_t cap = (size_t)max_memory_mib << 20, arena_size = (size_t)64 << 20;
    for (;;) {
        if (arena_size > cap) arena_size = cap;
        if (!(blob = malloc(arena_size))) break;
        rt_arena arena;
        rt_arena_init(&arena, blob, arena_size);
        rt_scene_desc desc;
        rt_build_error be;
        rt_status st = rt_blob_read(bytes, size, &arena, &desc);
        if (st == RT_OK) st = rt_scene_build(&desc, &arena, NULL, &built.scene, &be);
        if (st == RT_OK) return allocate_image("scene blob");
        free(blob);
        blob = NULL;
        if (st != RT_ERR_NOMEM) {
            fprintf(stderr, "rtk render: scene blob: not a scene blob of this build\n");
            return RTP_EXIT_INPUT;
        }
        if (arena_size >= cap) break;
        arena_size = arena.wanted > arena_size ? 2 * arena.wanted : 2 * arena_size;
    }
    fprintf(stderr, "rtk render: scene blob: the scene needs more than %u MiB\n", max_memory_mib);
    return RTP_EXIT_MEMORY;
}

/* Renders columns [x0, x1) of rows [y0, y1) into rtk_image(). */
EXPORT(rtk_render_region) void rtk_render_region(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1)
{
    rt_tracer tracer = {.scene = &built.scene, .use_bvh = true};
    rt_render_region(&tracer, x0, y0, x1, y1, image);
}

/* The render hash (`rtk render --hash`) of width * height * 3 bytes, into digest[32]. */
EXPORT(rtk_hash) void rtk_hash(const uint8_t *rgb, uint32_t width, uint32_t height, uint8_t *digest)
{
    rt_sha256_ppm(rgb, width, height, digest);
}

/* `rtk debug --json --pixel X,Y [--sample K]` on the open scene (sample UINT32_MAX: all),
 * printed on stdout. Returns an RTP_EXIT_* code. */
EXPORT(rtk_debug) int rtk_debug(uint32_t x, uint32_t y, uint32_t sample)
{
    const rt_camera *cam = &built.scene.camera;
    int rc = RTP_EXIT_OK;
    rtp_pixel_trace pt;
    if (!is_open || x >= cam->width || y >= cam->height ||
        (sample != RTP_PIXEL_ALL_SAMPLES && sample >= rtk_samples())) {
        fprintf(stderr, "rtk debug: no such pixel or sample\n");
        rc = RTP_EXIT_USAGE;
    } else if (!rtp_pixel_trace_run(&pt, &built, x, y, sample, LOG_CAPACITY)) {
        fprintf(stderr, "rtk debug: no memory for the ray log\n");
        rc = RTP_EXIT_MEMORY;
    } else {
        if (pt.log.overflow)
            fprintf(stderr, "rtk debug: the ray log is full: only the first %u rays are shown\n", LOG_CAPACITY);
        rtp_debug_print_json(stdout, &pt);
        rtp_pixel_trace_free(&pt);
    }
    fflush(stdout);
    fflush(stderr);
    return rc;
}

/* `rtk compare A B --json`: the JSON on stdout, errors on stderr; the exit code. */
EXPORT(rtk_compare) int rtk_compare(const char *a, const char *b)
{
    char *argv[] = {"compare", (char *)a, (char *)b, "--json", NULL};
    int rc = rtp_cmd_compare(4, argv);
    fflush(stdout);
    fflush(stderr);
    return rc;
}

/* The heat map `rtk compare --diff` writes, of two image files: width * height * 3 bytes
 * (malloc'd, for rtk_free), or NULL when they cannot be read or differ in size. */
EXPORT(rtk_diff_map) uint8_t *rtk_diff_map(const char *a, const char *b)
{
    rtp_image ia = {0}, ib = {0}, map = {0};
    char err[RTP_ERR_SIZE];
    bool ok = rtp_image_read(a, &ia, err, sizeof err) && rtp_image_read(b, &ib, err, sizeof err) &&
              ia.width == ib.width && ia.height == ib.height && rtp_image_diff_map(&ia, &ib, &map);
    rtp_image_free(&ia);
    rtp_image_free(&ib);
    return ok ? map.rgb : NULL;
}

/* An image file's pixels (PNG or PPM, as rtk compare reads them): width * height * 3 bytes
 * (malloc'd, for rtk_free), or NULL with the native message on stderr. */
EXPORT(rtk_read_image) uint8_t *rtk_read_image(const char *path)
{
    rtp_image img = {0};
    char err[RTP_ERR_SIZE];
    if (rtp_image_read(path, &img, err, sizeof err)) return img.rgb;
    fprintf(stderr, "rtk compare: %s\n", err);
    return NULL;
}

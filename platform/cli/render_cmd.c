/* `rtk render`: scene file in, image file (and/or render hash) out. */
#include "cli/render_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "cli/message.h"
#include "cli/render_part.h"
#include "cli/signals.h"
#include "image/image.h"
#include "load/input_file.h"
#include "load/scene_open.h"
#include "mem/mem.h"
#include "part/part_file.h"
#include "sha256.h"
#include "thread/threads.h"
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static const char usage[] = "usage: rtk render SCENE.yaml [-o OUT.png|OUT.ppm] [options]\n"
                            "\n"
                            "Renders a CSE457 scene file ('-': read from standard input). The output format\n"
                            "follows the file name (.png, else binary PPM); the file is written atomically, or\n"
                            "not at all on error.\n"
                            "\n"
                            "  -o, --output FILE   image to write (optional with --hash); '-' writes binary PPM\n"
                            "                      to standard output\n" RTP_CLI_SCENE_OPTIONS_HELP
                            "  --threads N         worker threads for the BVH build and the render (default: all\n"
                            "                      cores); the image does not depend on it\n"
                            "  --tile N            tile side in pixels (default 32); the image does not depend on it\n"
                            "  --hash              print the render hash (SHA-256 of the P6 PPM bytes) on stdout\n"
                            "  --no-bvh            test every primitive for every ray (slow; the image is identical)\n"
                            "  --region X0,Y0,X1,Y1  render only columns X0..X1-1 of rows Y0..Y1-1 of the frame, as\n"
                            "                      a part for rtk stitch (-o PART.png)\n"
                            "  --part I/N          render part I of N (I counts from 0: 0..N-1), a band of rows;\n"
                            "                      the cut is the same on every machine (docs/distributed.md)\n"
                            "  --quiet             no progress bar\n"
                            "  --progress          progress bar even when stderr is not a terminal\n"
                            "\n"
                            "Exit codes: 0 ok, 2 bad arguments, 3 bad or missing input file, 4 output not\n"
                            "writable, 5 over the memory cap, 6 interrupted.\n";

typedef struct {
    const char *scene, *output;
    rtp_scene_options build;
    rtp_threads_options parallel;
    rtp_part_request part;
    bool hash, use_bvh, quiet, force_progress;
} render_args;

static bool ends_with_png(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && !strcasecmp(path + n - 4, ".png");
}

static int parse_args(int argc, char **argv, render_args *a)
{
    memset(a, 0, sizeof *a);
    a->build = rtp_scene_default_options();
    a->use_bvh = true;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        uint32_t n;
        int common = rtp_cli_common_option("render", usage, argc, argv, &i, &a->build);
        if (common < 0) return -common;
        if (common > 0) continue;
        int part = rtp_part_request_option("render", argc, argv, &i, &a->part);
        if (part < 0) return -part;
        if (part > 0) continue;
        if (!strcmp(arg, "-o") || !strcmp(arg, "--output")) {
            if (!val) return rtp_cli_usage_error("render", "missing file after", arg);
            a->output = val, i++;
        } else if (!strcmp(arg, "--threads")) {
            if (!rtp_cli_parse_u32(val, 1, 1024, &n))
                return rtp_cli_usage_error("render", "expected 1..1024 after", arg);
            a->parallel.threads = a->build.threads = n, i++;
        } else if (!strcmp(arg, "--tile")) {
            if (!rtp_cli_parse_u32(val, 1, 4096, &n))
                return rtp_cli_usage_error("render", "expected 1..4096 after", arg);
            a->parallel.tile_size = n, i++;
        } else if (!strcmp(arg, "--hash")) {
            a->hash = true;
        } else if (!strcmp(arg, "--no-bvh")) {
            a->use_bvh = false;
        } else if (!strcmp(arg, "--quiet")) {
            a->quiet = true;
        } else if (!strcmp(arg, "--progress")) {
            a->force_progress = true;
        } else {
            int rc = rtp_cli_scene_argument("render", arg, &a->scene);
            if (rc != RTP_EXIT_OK) return rc;
        }
    }
    if (!a->scene) return rtp_cli_usage_error("render", "no scene file given", NULL);
    if (!a->output && !a->hash) return rtp_cli_usage_error("render", "nothing to do: give -o FILE and/or --hash", NULL);
    if (a->hash && a->output && !strcmp(a->output, "-"))
        return rtp_cli_usage_error("render", "--hash and -o - would both write to standard output", NULL);
    if (a->part.wanted && a->hash)
        return rtp_cli_usage_error("render", "--hash is the whole frame's: rtk stitch --hash gives it for parts", NULL);
    if (a->part.wanted && !strcmp(a->scene, "-")) /* parts carry the scene file's digest, read after loading */
        return rtp_cli_usage_error("render", "a part digests the scene file: give its path, not", a->scene);
    if (a->part.wanted && !ends_with_png(a->output))
        return rtp_cli_usage_error("render", "a part is a PNG file: expected -o NAME.png, not", a->output);
    return RTP_EXIT_OK;
}

static void print_hash(const rtp_image *img)
{
    uint8_t digest[32];
    rt_sha256_ppm(img->rgb, img->width, img->height, digest);
    for (int i = 0; i < 32; i++) printf("%02x", digest[i]);
    printf("\n");
}

int rtp_cmd_render(int argc, char **argv)
{
    render_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc != RTP_EXIT_OK) return rc;
    const char *scene = rtp_cli_scene_name(a.scene);
    rtp_signals_install("render", scene);
    if (a.output) rtp_input_forbid(a.output);
    rtp_scene built;
    /* A frame's image is allocated under the cap before the arena; a part's, only its
     * rectangle, once the plan has cut it. */
    a.build.with_image = !a.part.wanted;
    rc = rtp_cli_open_scene("render", a.scene, &a.build, &built);
    if (rc != RTP_EXIT_OK) return rc;
    const rt_camera *cam = &built.scene.camera;
    rtp_part part = {.region = {0, 0, cam->width, cam->height}};
    if (a.part.wanted) rc = rtp_part_plan("render", a.scene, &built, &a.part, a.build.threads, &part);
    if (rc != RTP_EXIT_OK) {
        rtp_scene_close(&built);
        return rc;
    }
    rtp_image img = built.image;
    built.image = (rtp_image){0};
    if (a.part.wanted &&
        !rtp_image_alloc(&img, part.region.x1 - part.region.x0, part.region.y1 - part.region.y0, "the part's image")) {
        rtp_message("render", "%s: %s", scene, rtp_mem_refusal());
        rtp_scene_close(&built);
        rtp_part_free(&part);
        return RTP_EXIT_MEMORY;
    }
    rt_tracer tracer = {.scene = &built.scene, .use_bvh = a.use_bvh};
    a.parallel.progress = !a.quiet && (a.force_progress || isatty(STDERR_FILENO));
    a.parallel.cancel = rtp_signals_defer(); /* stop between tiles, and free what the render holds */
    bool complete = rtp_threads_render_region(&tracer, &a.parallel, part.region, img.rgb), stopped = *a.parallel.cancel;
    rtp_scene_close(&built);
    if (!complete || stopped) {
        rtp_image_free(&img);
        rtp_part_free(&part);
        if (stopped) return rtp_signals_stopped();
        rtp_message("render", "%s: no memory for the render's threads", scene);
        return RTP_EXIT_MEMORY;
    }
    rtp_signals_immediate();
    char err[RTP_ERR_SIZE];
    bool written = !a.output || (a.part.wanted ? rtp_part_write(a.output, &part, img.rgb, err, sizeof err)
                                               : rtp_image_write(a.output, &img, err, sizeof err));
    rtp_part_free(&part);
    if (!written) {
        rtp_message("render", "%s", err);
        rc = RTP_EXIT_OUTPUT;
    }
    if (rc == RTP_EXIT_OK && a.hash) {
        print_hash(&img);
        rc = rtp_cli_flush_stdout("render");
    }
    rtp_image_free(&img);
    return rc;
}

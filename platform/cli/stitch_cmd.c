/* `rtk stitch`: parts of a distributed render (rtk render --part / --region) into the
 * frame, after checking they are one render covering the frame exactly once; --check
 * checks parts one by one, --missing lists the parts a folder still lacks. */
#include "cli/stitch_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "cli/message.h"
#include "cli/signals.h"
#include "cli/version.h"
#include "image/image.h"
#include "load/input_file.h"
#include "mem/mem.h"
#include "part/part_cut.h"
#include "part/part_file.h"
#include "part/part_identity.h"
#include "part/part_stitch.h"
#include "sha256.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char usage[] =
    "usage: rtk stitch PART.png... -o OUT.png|OUT.ppm [--hash]\n"
    "       rtk stitch --check PART.png...\n"
    "       rtk stitch --missing PARTS_DIR SCENE.yaml --tiles N [scene options]\n"
    "\n"
    "Joins the parts of one frame (rtk render --part I/N or --region) into the whole\n"
    "image, written atomically. It first checks that every part is whole (not truncated,\n"
    "its pixels matching their digest), that all come from one render (the same rtk\n"
    "version and build, scene file, asset files, settings and frame size) and that they\n"
    "cover the frame exactly once; else it prints one line naming the part and the\n"
    "problem, exits with 3 and writes nothing.\n"
    "\n"
    "  -o, --output FILE   the frame to write (.png, else binary PPM; optional with --hash)\n"
    "  --hash              print the frame's render hash, as rtk render --hash does\n"
    "  --check             only check each part on its own (whole, pixels match their\n"
    "                      digest); prints nothing when all are, exits 3 when one is not\n"
    "  --missing DIR SCENE list, one index a line, the parts I of N not yet in DIR as\n"
    "                      DIR/part-I-of-N.png or not valid there (broken, or from another\n"
    "                      render: the problem goes to stderr); for re-rendering\n"
    "  --tiles N, --parts N  the part count N for --missing (as in --part I/N)\n"
    "  --threads N         threads for --missing's cut estimate (default: all cores)\n"
    "  --max-memory SIZE   in every mode: the cap on all the memory rtk allocates (default 4G)\n"
    "With --missing, the scene options give the render's settings, as for rtk render\n"
    "(without it they are refused: the parts hold the settings):\n" RTP_CLI_SCENE_OPTIONS_HELP "\n"
    "Parts and the scene must be regular files ('-' is not one: a part digests its scene\n"
    "file). Exit codes: 0 ok, 2 bad arguments (also -o naming one of the parts), 3 a part\n"
    "or scene is missing, unreadable, invalid or does not fit the others, 4 output or\n"
    "standard output not writable, 5 over the memory cap, 6 interrupted.\n";

typedef enum { MODE_STITCH, MODE_CHECK, MODE_MISSING } stitch_mode;

typedef struct {
    stitch_mode mode;
    const char *output, *dir, *scene;
    const char **parts;
    uint32_t part_count, tiles, threads;
    bool hash;
    rtp_scene_options build;
    const char *scene_option; /* the first render setting given; only --missing reads one */
} stitch_args;

static int parse_args(int argc, char **argv, stitch_args *a)
{
    memset(a, 0, sizeof *a);
    a->build = rtp_scene_default_options();
    a->parts = calloc((size_t)argc, sizeof *a->parts);
    if (!a->parts) return rtp_message("stitch", "out of memory"), RTP_EXIT_MEMORY;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int common = rtp_cli_common_option("stitch", usage, argc, argv, &i, &a->build);
        if (common < 0) return -common;
        if (common > 0) {
            if (!a->scene_option && strcmp(arg, "--max-memory")) a->scene_option = arg;
            continue;
        }
        if (!strcmp(arg, "-o") || !strcmp(arg, "--output")) {
            if (!val) return rtp_cli_usage_error("stitch", "missing file after", arg);
            a->output = val, i++;
        } else if (!strcmp(arg, "--hash")) {
            a->hash = true;
        } else if (!strcmp(arg, "--check")) {
            a->mode = MODE_CHECK;
        } else if (!strcmp(arg, "--missing")) {
            if (!val) return rtp_cli_usage_error("stitch", "missing folder after", arg);
            a->mode = MODE_MISSING, a->dir = val, i++;
        } else if (!strcmp(arg, "--tiles") || !strcmp(arg, "--parts")) {
            if (!rtp_cli_parse_u32(val, 1, RT_MAX_IMAGE_SIDE, &a->tiles))
                return rtp_cli_usage_error("stitch", "expected 1..16384 after", arg);
            i++;
        } else if (!strcmp(arg, "--threads")) {
            if (!rtp_cli_parse_u32(val, 1, 1024, &a->threads))
                return rtp_cli_usage_error("stitch", "expected 1..1024 after", arg);
            a->build.threads = a->threads, i++;
        } else if (arg[0] == '-' && arg[1]) {
            return rtp_cli_usage_error("stitch", "unknown option", arg);
        } else {
            a->parts[a->part_count++] = arg;
        }
    }
    if (a->mode == MODE_MISSING) {
        if (a->part_count != 1) return rtp_cli_usage_error("stitch", "--missing takes one scene file", NULL);
        if (!a->tiles) return rtp_cli_usage_error("stitch", "--missing needs the part count: --tiles N", NULL);
        if (a->output || a->hash) return rtp_cli_usage_error("stitch", "--missing writes no image", NULL);
        a->scene = a->parts[0];
        if (!strcmp(a->scene, "-"))
            return rtp_cli_usage_error("stitch", "--missing digests the scene file: give its path, not", a->scene);
        return RTP_EXIT_OK;
    }
    if (a->part_count == 0) return rtp_cli_usage_error("stitch", "no part files given", NULL);
    if (a->tiles) return rtp_cli_usage_error("stitch", "--tiles is for --missing", NULL);
    /* The parts carry their settings; an option that would change them changes nothing. */
    if (a->scene_option)
        return rtp_cli_usage_error("stitch",
                                   "the parts hold the render's settings; this is for --missing:", a->scene_option);
    if (a->mode == MODE_CHECK && (a->output || a->hash))
        return rtp_cli_usage_error("stitch", "--check writes no image", NULL);
    if (a->mode == MODE_STITCH && !a->output && !a->hash)
        return rtp_cli_usage_error("stitch", "nothing to do: give -o FILE and/or --hash", NULL);
    if (a->hash && a->output && !strcmp(a->output, "-"))
        return rtp_cli_usage_error("stitch", "--hash and -o - would both write to standard output", NULL);
    return RTP_EXIT_OK;
}

/* Reads one part; on failure prints "rtk stitch: NAME: problem" and gives the exit code. */
static int read_part(const char *name, rtp_part *p, uint8_t **rgb)
{
    char err[RTP_ERR_SIZE];
    if (rtp_part_read(name, p, rgb, err, sizeof err)) return RTP_EXIT_OK;
    rtp_message("stitch", "%s: %s", name, err);
    return rtp_load_failure_code();
}

static void blit(uint8_t *frame, const rtp_part *p, const uint8_t *rgb)
{
    size_t row = (size_t)(p->region.x1 - p->region.x0) * 3;
    for (uint32_t y = p->region.y0; y < p->region.y1; y++)
        memcpy(frame + ((size_t)y * p->width + p->region.x0) * 3, rgb + (y - p->region.y0) * row, row);
}

/* Reads every part into the frame, checking each against the first; then the cover. */
static int gather(const stitch_args *a, rtp_part *parts, rtp_image *frame)
{
    char err[RTP_ERR_SIZE];
    for (uint32_t i = 0; i < a->part_count; i++) {
        uint8_t *rgb = NULL;
        int rc = read_part(a->parts[i], &parts[i], &rgb);
        if (rc != RTP_EXIT_OK) return rc;
        if (i > 0 && !rtp_stitch_same_render(&parts[i], a->parts[i], &parts[0], a->parts[0], err, sizeof err)) {
            rtp_mem_free(rgb);
            rtp_message("stitch", "%s", err);
            return RTP_EXIT_INPUT;
        }
        if (i == 0 && !rtp_image_alloc(frame, parts[0].width, parts[0].height, "the frame")) {
            rtp_mem_free(rgb);
            rtp_message("stitch", "%s: %s", a->parts[0], rtp_mem_refusal());
            return RTP_EXIT_MEMORY;
        }
        blit(frame->rgb, &parts[i], rgb);
        rtp_mem_free(rgb);
    }
    if (rtp_stitch_coverage(parts, a->parts, a->part_count, err, sizeof err)) return RTP_EXIT_OK;
    rtp_message("stitch", "%s", err);
    return RTP_EXIT_INPUT;
}

static int stitch(const stitch_args *a)
{
    rtp_part *parts = rtp_mem_calloc(a->part_count, sizeof *parts, "the parts' descriptions");
    if (!parts) {
        rtp_message("stitch", "%s", rtp_mem_refusal());
        return RTP_EXIT_MEMORY;
    }
    rtp_image frame = {0};
    int rc = gather(a, parts, &frame);
    char err[RTP_ERR_SIZE];
    if (rc == RTP_EXIT_OK && a->output && !rtp_image_write(a->output, &frame, err, sizeof err)) {
        rtp_message("stitch", "%s", err);
        rc = rtp_mem_refused() ? RTP_EXIT_MEMORY : RTP_EXIT_OUTPUT;
    }
    if (rc == RTP_EXIT_OK && a->hash) {
        uint8_t digest[32];
        char hex[65];
        rt_sha256_ppm(frame.rgb, frame.width, frame.height, digest);
        rtp_part_hex(digest, hex);
        puts(hex);
        rc = rtp_cli_flush_stdout("stitch");
    }
    for (uint32_t i = 0; i < a->part_count; i++) rtp_part_free(&parts[i]);
    rtp_mem_free(parts);
    rtp_image_free(&frame);
    return rc;
}

static int check(const stitch_args *a)
{
    int rc = RTP_EXIT_OK;
    for (uint32_t i = 0; i < a->part_count; i++) {
        rtp_part p;
        int code = read_part(a->parts[i], &p, NULL);
        if (code == RTP_EXIT_OK)
            rtp_part_free(&p);
        else if (rc == RTP_EXIT_OK)
            rc = code;
    }
    return rc;
}

/* Whether the file for part `index` holds that part of the render `want` describes;
 * prints why not to stderr when it is there but not valid. */
static bool part_present(const char *name, const rtp_part *want, const char *scene)
{
    if (access(name, F_OK) != 0 && errno == ENOENT) return false;
    rtp_part p;
    char err[RTP_ERR_SIZE];
    if (!rtp_part_read(name, &p, NULL, err, sizeof err)) {
        rtp_message("stitch", "%s: %s; to render again", name, err);
        return false;
    }
    bool ok = rtp_stitch_same_render(&p, name, want, scene, err, sizeof err);
    if (!ok) {
        rtp_message("stitch", "%s; to render again", err);
    } else if (strcmp(p.text[RTP_PART_REGION], want->text[RTP_PART_REGION]) ||
               strcmp(p.text[RTP_PART_INDEX], want->text[RTP_PART_INDEX])) {
        rtp_message("stitch", "%s: holds part %s, region %s, not part %s, region %s; to render again", name,
                    p.text[RTP_PART_INDEX], p.text[RTP_PART_REGION], want->text[RTP_PART_INDEX],
                    want->text[RTP_PART_REGION]);
        ok = false;
    }
    rtp_part_free(&p);
    return ok;
}

/* Prints the index of every part of want's render whose file is missing or not valid. */
static int list_missing(const stitch_args *a, const rtp_scene *built, rtp_part *want)
{
    uint32_t *starts = rtp_mem_calloc((size_t)a->tiles + 1, sizeof *starts, "the cut");
    if (!starts || !rtp_part_cut(&built->scene, a->tiles, a->threads, starts)) {
        rtp_mem_free(starts);
        rtp_message("stitch", "cutting the frame into %u parts: %s", a->tiles, rtp_mem_refusal());
        return RTP_EXIT_MEMORY;
    }
    char reference[RTP_ERR_SIZE];
    snprintf(reference, sizeof reference, "%s as given", a->scene);
    int rc = RTP_EXIT_OK;
    for (uint32_t i = 0; rc == RTP_EXIT_OK && i < a->tiles; i++) {
        want->region = rtp_part_band(&built->scene, starts, i);
        want->index = i;
        want->count = a->tiles;
        char *name = rtp_part_file_name(a->dir, i, a->tiles);
        if (!name || !rtp_part_format_place(want)) {
            rtp_message("stitch", "%s", name ? rtp_mem_refusal() : "out of memory");
            rc = RTP_EXIT_MEMORY;
        } else if (!part_present(name, want, reference)) {
            printf("%u\n", i);
        }
        free(name);
    }
    rtp_mem_free(starts);
    return rc == RTP_EXIT_OK ? rtp_cli_flush_stdout("stitch") : rc;
}

static int missing(const stitch_args *a)
{
    rtp_scene built;
    int rc = rtp_cli_open_scene("stitch", a->scene, &a->build, &built);
    if (rc != RTP_EXIT_OK) return rc;
    if (a->tiles > built.scene.camera.height) {
        char msg[160];
        snprintf(msg, sizeof msg, "--tiles %u: more parts than the frame's %u rows", a->tiles,
                 built.scene.camera.height);
        rc = rtp_cli_usage_error("stitch", msg, NULL);
    }
    rtp_part want = {0};
    char err[RTP_ERR_SIZE];
    if (rc == RTP_EXIT_OK &&
        (rc = rtp_part_identify(a->scene, rtp_version_line(), &built, &want, err, sizeof err)) != RTP_EXIT_OK)
        rtp_message("stitch", "%s", err);
    if (rc == RTP_EXIT_OK) rc = list_missing(a, &built, &want);
    rtp_part_free(&want);
    rtp_scene_close(&built);
    return rc;
}

int rtp_cmd_stitch(int argc, char **argv)
{
    stitch_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc == RTP_EXIT_OK) {
        rtp_signals_install("stitch", a.scene);
        rtp_mem_set_cap(a.build.max_memory);
        if (a.output) rtp_input_forbid(a.output); /* before any part is read */
        rc = a.mode == MODE_STITCH ? stitch(&a) : a.mode == MODE_CHECK ? check(&a) : missing(&a);
    }
    free(a.parts);
    return rc;
}

/* `rtk compare`: PSNR and difference statistics of two images, a heat map, thresholds. */
#include "cli/compare_cmd.h"

#include "cli/exit_codes.h"
#include "debug/json_out.h"
#include "image/image_compare.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage_line[] = "usage: rtk compare A B [--diff OUT.png] [--min-psnr DB] [--max-diff N] [--json]\n";
static const char help_text[] =
    "\n"
    "Compares two images of the same size (PNG or binary PPM, read as 8-bit RGB) and prints\n"
    "PSNR over the RGB channels (\"inf\" when identical), the mean and largest absolute\n"
    "difference, the share of channels within 0/1/2/8 levels, the number of pixels off by\n"
    "more than 2, and the first worst pixel (x, y from the top left) with both colours.\n"
    "\n"
    "  --diff OUT      write a heat map of each pixel's largest channel difference\n"
    "                  (PNG if OUT ends in .png, else PPM): black = identical, then\n"
    "                  blue (1 level), green (4), yellow (16), red (64 or more)\n"
    "  --min-psnr DB   exit 1 when PSNR is below DB\n"
    "  --max-diff N    exit 1 when some channel differs by more than N levels (0-255)\n"
    "  --json          print one JSON object instead; PSNR of identical images is \"inf\"\n"
    "  --help          show this help\n"
    "\n"
    "Exit status: 0 thresholds met, 1 a threshold missed, 2 bad arguments,\n"
    "3 an image is unreadable or the sizes differ, 4 the --diff image could not be written.\n";

typedef struct {
    const char *a, *b, *diff;
    double min_psnr;   /* -INFINITY: no PSNR threshold */
    unsigned max_diff; /* 255: no difference threshold */
    bool json;
} compare_options;

static int usage_error(const char *fmt, const char *arg)
{
    fputs("rtk compare: ", stderr);
    fprintf(stderr, fmt, arg);
    fputs(" (see rtk compare --help)\n", stderr);
    return RTP_EXIT_USAGE;
}

/* Returns -1 when the command should run, else the exit code to return at once. */
static int parse_options(int argc, char **argv, compare_options *o)
{
    *o = (compare_options){.min_psnr = -INFINITY, .max_diff = 255};
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            fputs(usage_line, stdout);
            fputs(help_text, stdout);
            return RTP_EXIT_OK;
        }
        if (strcmp(arg, "--json") == 0) {
            o->json = true;
            continue;
        }
        bool diff = strcmp(arg, "--diff") == 0, psnr = strcmp(arg, "--min-psnr") == 0,
             max = strcmp(arg, "--max-diff") == 0;
        if (diff || psnr || max) {
            if (i + 1 >= argc) return usage_error("%s needs a value", arg);
            const char *value = argv[++i];
            char *end;
            errno = 0;
            if (diff) {
                o->diff = value;
            } else if (psnr) {
                o->min_psnr = strtod(value, &end);
                if (end == value || *end || errno || isnan(o->min_psnr))
                    return usage_error("--min-psnr wants a number of dB, not '%s'", value);
            } else {
                long n = strtol(value, &end, 10);
                if (end == value || *end || errno || n < 0 || n > 255)
                    return usage_error("--max-diff wants a whole number of levels 0-255, not '%s'", value);
                o->max_diff = (unsigned)n;
            }
        } else if (arg[0] == '-' && arg[1] != '\0') {
            return usage_error("unknown option '%s'", arg);
        } else if (!o->a) {
            o->a = arg;
        } else if (!o->b) {
            o->b = arg;
        } else {
            return usage_error("one image too many: '%s'", arg);
        }
    }
    if (!o->b) return usage_error("%s", "needs two images, A and B");
    return -1;
}

/* One object; "psnr" is the string "inf" for identical images (JSON has no infinity). */
static void print_json(const compare_options *o, const rtp_image_metrics *m)
{
    fputs("{\"a\": ", stdout);
    rtp_json_string(stdout, o->a);
    fputs(", \"b\": ", stdout);
    rtp_json_string(stdout, o->b);
    printf(", \"width\": %u, \"height\": %u, \"psnr\": ", m->width, m->height);
    if (isinf(m->psnr))
        fputs("\"inf\"", stdout);
    else
        printf("%.6f", m->psnr);
    printf(", \"mean_diff\": %.6f, \"max_diff\": %u, "
           "\"within_pct\": {\"0\": %.6f, \"1\": %.6f, \"2\": %.6f, \"8\": %.6f}, "
           "\"pixels_over_2\": %llu, "
           "\"worst\": {\"x\": %u, \"y\": %u, \"a\": [%u, %u, %u], \"b\": [%u, %u, %u]}}\n",
           m->mean_diff, m->max_diff, m->within0_pct, m->within1_pct, m->within2_pct, m->within8_pct,
           (unsigned long long)m->pixels_over2, m->worst_x, m->worst_y, m->worst_a[0], m->worst_a[1], m->worst_a[2],
           m->worst_b[0], m->worst_b[1], m->worst_b[2]);
}

static void print_text(const compare_options *o, const rtp_image_metrics *m)
{
    printf("%s vs %s (%ux%u)\n", o->a, o->b, m->width, m->height);
    if (isinf(m->psnr))
        printf("PSNR           inf dB (identical)\n");
    else
        printf("PSNR           %.3f dB\n", m->psnr);
    printf("mean diff      %.4f levels\n", m->mean_diff);
    printf("max diff       %u levels\n", m->max_diff);
    printf("within 0/1/2/8 %.3f%%  %.3f%%  %.3f%%  %.3f%% of channels\n", m->within0_pct, m->within1_pct,
           m->within2_pct, m->within8_pct);
    printf("pixels > 2     %llu\n", (unsigned long long)m->pixels_over2);
    printf("worst pixel    x %u, y %u: A (%u, %u, %u)  B (%u, %u, %u)\n", m->worst_x, m->worst_y, m->worst_a[0],
           m->worst_a[1], m->worst_a[2], m->worst_b[0], m->worst_b[1], m->worst_b[2]);
}

/* Reads, measures, reports and writes the heat map; returns the exit code. */
static int run(const compare_options *o, rtp_image *a, rtp_image *b)
{
    char err[512];
    if (!rtp_image_read(o->a, a, err, sizeof err) || !rtp_image_read(o->b, b, err, sizeof err)) {
        fprintf(stderr, "rtk compare: %s\n", err);
        return RTP_EXIT_INPUT;
    }
    rtp_image_metrics m;
    if (!rtp_image_compare(a, b, &m)) {
        fprintf(stderr, "rtk compare: %s is %ux%u but %s is %ux%u\n", o->a, a->width, a->height, o->b, b->width,
                b->height);
        return RTP_EXIT_INPUT;
    }
    if (o->json)
        print_json(o, &m);
    else
        print_text(o, &m);
    fflush(stdout);
    if (o->diff) {
        rtp_image map;
        bool ok = rtp_image_diff_map(a, b, &map);
        if (!ok)
            snprintf(err, sizeof err, "%s: out of memory", o->diff);
        else
            ok = rtp_image_write(o->diff, &map, err, sizeof err);
        rtp_image_free(&map);
        if (!ok) {
            fprintf(stderr, "rtk compare: %s\n", err);
            return RTP_EXIT_OUTPUT;
        }
    }
    int code = RTP_EXIT_OK;
    if (m.psnr < o->min_psnr) {
        fprintf(stderr, "rtk compare: PSNR %.3f dB is below --min-psnr %g\n", m.psnr, o->min_psnr);
        code = RTP_EXIT_THRESHOLD;
    }
    if (m.max_diff > o->max_diff) {
        fprintf(stderr, "rtk compare: max diff %u exceeds --max-diff %u\n", m.max_diff, o->max_diff);
        code = RTP_EXIT_THRESHOLD;
    }
    return code;
}

int rtp_cmd_compare(int argc, char **argv)
{
    compare_options o;
    int code = parse_options(argc, argv, &o);
    if (code >= 0) return code;
    rtp_image a = {0}, b = {0};
    code = run(&o, &a, &b);
    rtp_image_free(&a);
    rtp_image_free(&b);
    return code;
}

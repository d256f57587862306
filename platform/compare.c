/* `rtk compare`: PSNR and difference statistics of two images, a heat map, thresholds. */
#include "compare.h"

#include "exit_codes.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool rt_image_compare(const rt_image *a, const rt_image *b, rt_image_metrics *m)
{
    if (a->width != b->width || a->height != b->height || a->width == 0 || a->height == 0)
        return false;
    uint64_t pixels = (uint64_t)a->width * a->height, channels = pixels * 3;
    uint64_t sum = 0, sum_sq = 0, within[4] = {0}, over2 = 0, worst_at = 0;
    unsigned worst = 0;
    for (uint64_t p = 0; p < pixels; p++) {
        unsigned most = 0;
        for (int c = 0; c < 3; c++) {
            int s = (int)a->rgb[3 * p + c] - (int)b->rgb[3 * p + c];
            unsigned d = (unsigned)(s < 0 ? -s : s);
            sum += d;
            sum_sq += (uint64_t)d * d;
            within[0] += d == 0;
            within[1] += d <= 1;
            within[2] += d <= 2;
            within[3] += d <= 8;
            most = d > most ? d : most;
        }
        over2 += most > 2;
        if (most > worst) { /* strict: the first pixel in row-major order wins ties */
            worst = most;
            worst_at = p;
        }
    }
    *m = (rt_image_metrics){
        .width = a->width,
        .height = a->height,
        .psnr = sum_sq == 0 ? INFINITY : 10.0 * log10(255.0 * 255.0 * (double)channels / (double)sum_sq),
        .mean_diff = (double)sum / (double)channels,
        .max_diff = worst,
        .within0_pct = 100.0 * (double)within[0] / (double)channels,
        .within1_pct = 100.0 * (double)within[1] / (double)channels,
        .within2_pct = 100.0 * (double)within[2] / (double)channels,
        .within8_pct = 100.0 * (double)within[3] / (double)channels,
        .pixels_over2 = over2,
        .worst_x = (uint32_t)(worst_at % a->width),
        .worst_y = (uint32_t)(worst_at / a->width),
    };
    memcpy(m->worst_a, a->rgb + 3 * worst_at, 3);
    memcpy(m->worst_b, b->rgb + 3 * worst_at, 3);
    return true;
}

/* Heat-map ramp, by a pixel's largest channel difference d:
 *   d = 0 black; d = 1 blue (0,0,255); d = 4 green (0,255,0); d = 16 yellow (255,255,0);
 *   d >= 64 red (255,0,0); linear in d between stops.
 * Stops grow by 4x, so the ramp is roughly logarithmic: a single level already shows
 * as clear blue, and hue tells 1-level noise from real errors at a glance. */
static void heat(unsigned d, uint8_t rgb[3])
{
    static const unsigned at[4] = {1, 4, 16, 64};
    static const uint8_t colour[4][3] = {{0, 0, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
    if (d == 0) {
        memset(rgb, 0, 3);
        return;
    }
    if (d >= at[3]) {
        memcpy(rgb, colour[3], 3);
        return;
    }
    int i = 0;
    while (d >= at[i + 1])
        i++;
    unsigned t = (d - at[i]) * 255 / (at[i + 1] - at[i]); /* 0..255 along the segment */
    for (int c = 0; c < 3; c++)
        rgb[c] = (uint8_t)((colour[i][c] * (255 - t) + colour[i + 1][c] * t) / 255);
}

bool rt_image_diff_map(const rt_image *a, const rt_image *b, rt_image *out)
{
    size_t pixels = (size_t)a->width * a->height;
    *out = (rt_image){.width = a->width, .height = a->height, .rgb = malloc(pixels * 3)};
    if (!out->rgb)
        return false;
    for (size_t p = 0; p < pixels; p++) {
        unsigned most = 0;
        for (int c = 0; c < 3; c++) {
            int s = (int)a->rgb[3 * p + c] - (int)b->rgb[3 * p + c];
            unsigned d = (unsigned)(s < 0 ? -s : s);
            most = d > most ? d : most;
        }
        heat(most, out->rgb + 3 * p);
    }
    return true;
}

static const char usage_line[] =
    "usage: rtk compare A B [--diff OUT.png] [--min-psnr DB] [--max-diff N] [--json]\n";
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
    double min_psnr; /* -INFINITY: no PSNR threshold */
    unsigned max_diff; /* 255: no difference threshold */
    bool json;
} compare_options;

static int usage_error(const char *fmt, const char *arg)
{
    fputs("rtk compare: ", stderr);
    fprintf(stderr, fmt, arg);
    fputs(" (see rtk compare --help)\n", stderr);
    return RT_EXIT_USAGE;
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
            return RT_EXIT_OK;
        }
        if (strcmp(arg, "--json") == 0) {
            o->json = true;
            continue;
        }
        bool diff = strcmp(arg, "--diff") == 0, psnr = strcmp(arg, "--min-psnr") == 0,
             max = strcmp(arg, "--max-diff") == 0;
        if (diff || psnr || max) {
            if (i + 1 >= argc)
                return usage_error("%s needs a value", arg);
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
    if (!o->b)
        return usage_error("%s", "needs two images, A and B");
    return -1;
}

static void json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

/* One object; "psnr" is the string "inf" for identical images (JSON has no infinity). */
static void print_json(const compare_options *o, const rt_image_metrics *m)
{
    fputs("{\"a\": ", stdout);
    json_string(o->a);
    fputs(", \"b\": ", stdout);
    json_string(o->b);
    printf(", \"width\": %u, \"height\": %u, \"psnr\": ", m->width, m->height);
    if (isinf(m->psnr))
        fputs("\"inf\"", stdout);
    else
        printf("%.6f", m->psnr);
    printf(", \"mean_diff\": %.6f, \"max_diff\": %u, "
           "\"within_pct\": {\"0\": %.6f, \"1\": %.6f, \"2\": %.6f, \"8\": %.6f}, "
           "\"pixels_over_2\": %llu, "
           "\"worst\": {\"x\": %u, \"y\": %u, \"a\": [%u, %u, %u], \"b\": [%u, %u, %u]}}\n",
           m->mean_diff, m->max_diff, m->within0_pct, m->within1_pct, m->within2_pct,
           m->within8_pct, (unsigned long long)m->pixels_over2, m->worst_x, m->worst_y,
           m->worst_a[0], m->worst_a[1], m->worst_a[2], m->worst_b[0], m->worst_b[1], m->worst_b[2]);
}

static void print_text(const compare_options *o, const rt_image_metrics *m)
{
    printf("%s vs %s (%ux%u)\n", o->a, o->b, m->width, m->height);
    if (isinf(m->psnr))
        printf("PSNR           inf dB (identical)\n");
    else
        printf("PSNR           %.3f dB\n", m->psnr);
    printf("mean diff      %.4f levels\n", m->mean_diff);
    printf("max diff       %u levels\n", m->max_diff);
    printf("within 0/1/2/8 %.3f%%  %.3f%%  %.3f%%  %.3f%% of channels\n", m->within0_pct,
           m->within1_pct, m->within2_pct, m->within8_pct);
    printf("pixels > 2     %llu\n", (unsigned long long)m->pixels_over2);
    printf("worst pixel    x %u, y %u: A (%u, %u, %u)  B (%u, %u, %u)\n", m->worst_x, m->worst_y,
           m->worst_a[0], m->worst_a[1], m->worst_a[2], m->worst_b[0], m->worst_b[1], m->worst_b[2]);
}

/* Reads, measures, reports and writes the heat map; returns the exit code. */
static int run(const compare_options *o, rt_image *a, rt_image *b)
{
    char err[512];
    if (!rt_image_read(o->a, a, err, sizeof err) || !rt_image_read(o->b, b, err, sizeof err)) {
        fprintf(stderr, "rtk compare: %s\n", err);
        return RT_EXIT_INPUT;
    }
    rt_image_metrics m;
    if (!rt_image_compare(a, b, &m)) {
        fprintf(stderr, "rtk compare: %s is %ux%u but %s is %ux%u\n", o->a, a->width, a->height,
                o->b, b->width, b->height);
        return RT_EXIT_INPUT;
    }
    if (o->json)
        print_json(o, &m);
    else
        print_text(o, &m);
    fflush(stdout);
    if (o->diff) {
        rt_image map;
        bool ok = rt_image_diff_map(a, b, &map);
        if (!ok)
            snprintf(err, sizeof err, "%s: out of memory", o->diff);
        else
            ok = rt_image_write(o->diff, &map, err, sizeof err);
        rt_image_free(&map);
        if (!ok) {
            fprintf(stderr, "rtk compare: %s\n", err);
            return RT_EXIT_OUTPUT;
        }
    }
    int code = RT_EXIT_OK;
    if (m.psnr < o->min_psnr) {
        fprintf(stderr, "rtk compare: PSNR %.3f dB is below --min-psnr %g\n", m.psnr, o->min_psnr);
        code = RT_EXIT_THRESHOLD;
    }
    if (m.max_diff > o->max_diff) {
        fprintf(stderr, "rtk compare: max diff %u exceeds --max-diff %u\n", m.max_diff, o->max_diff);
        code = RT_EXIT_THRESHOLD;
    }
    return code;
}

int rt_cmd_compare(int argc, char **argv)
{
    compare_options o;
    int code = parse_options(argc, argv, &o);
    if (code >= 0)
        return code;
    rt_image a = {0}, b = {0};
    code = run(&o, &a, &b);
    rt_image_free(&a);
    rt_image_free(&b);
    return code;
}

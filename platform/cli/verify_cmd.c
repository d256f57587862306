/* `rtk verify`: render hashes as a CI check, in the shape of `sha256sum -c`. */
#include "cli/verify_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "image/file_write.h"
#include "render.h"
#include "rtk.h"
#include "thread/threads.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char usage[] =
    "usage: rtk verify MANIFEST [--junit FILE] [--threads N]\n"
    "       rtk verify --write MANIFEST SCENE... [scene options]\n"
    "\n"
    "Renders every scene a manifest names and checks its render hash (SHA-256 of the\n"
    "image's binary PPM bytes, as `rtk render --hash` prints it). A manifest line is\n"
    "\n"
    "    HASH  SCENE [scene options]\n"
    "\n"
    "the shape of sha256sum's output, but HASH is the hash of the rendered image, not of\n"
    "the file, so `sha256sum -c` cannot check it. SCENE is relative to the current folder\n"
    "(as sha256sum reads it); write it in double quotes if it holds spaces. The options are\n"
    "the ones below that change pixels. Blank lines and lines starting with # are skipped.\n"
    "Prints \"SCENE: OK\" or \"SCENE: FAILED (got HASH)\" for each line.\n"
    "\n"
    "  --junit FILE        also write the results as JUnit XML, for CI systems\n"
    "  --threads N         render threads (default: all cores); hashes do not depend on it\n"
    "  --write MANIFEST    render each SCENE with the options given and write a manifest\n" RTP_CLI_SCENE_OPTIONS_HELP
    "\n"
    "Exit codes: 0 every hash matches, 1 a hash differs or a scene cannot be rendered,\n"
    "2 bad arguments, 3 the manifest is unreadable or malformed, 4 a file cannot be\n"
    "written, 5 out of memory.\n";

#define MAX_TOKENS 32

/* One manifest line, split into words. */
typedef struct {
    unsigned line;
    char hash[RTK_HASH_SIZE];
    char *words[MAX_TOKENS]; /* the scene, then its options */
    int count;
    char *text; /* the scene and options as written, for the report */
} entry;

typedef struct {
    entry item;
    bool ok, rendered;
    char got[RTK_HASH_SIZE];
    char error[RTP_ERR_SIZE];
    double seconds;
} result;

/* Splits s in place into words separated by blanks; "..." keeps blanks. False when a
 * quote is not closed or there are too many words. */
static bool split_words(char *s, char **words, int *count)
{
    *count = 0;
    while (*s) {
        while (*s == ' ' || *s == '\t') s++;
        if (!*s) break;
        if (*count == MAX_TOKENS) return false;
        char *out = s;
        words[(*count)++] = out;
        bool quoted = false;
        for (; *s && (quoted || (*s != ' ' && *s != '\t')); s++) {
            if (*s == '"')
                quoted = !quoted;
            else
                *out++ = *s;
        }
        if (quoted) return false;
        if (*s) s++;
        *out = '\0';
    }
    return true;
}

static bool is_hash(const char *s)
{
    for (int i = 0; i < 64; i++)
        if (!((s[i] >= '0' && s[i] <= '9') || (s[i] >= 'a' && s[i] <= 'f'))) return false;
    return true;
}

/* Renders the scene words[0] with the options words[1..], into hash; false with one line in err. */
static bool render_hash(char **words, int count, uint32_t threads, char hash[RTK_HASH_SIZE], char *err, size_t err_size)
{
    rtp_scene_options opt = rtp_scene_default_options();
    opt.threads = threads;
    for (int i = 1; i < count; i++) {
        const char *problem = "unknown option";
        if (rtp_cli_parse_scene_option(count, words, &i, &opt, &problem) <= 0) {
            snprintf(err, err_size, "%s '%s'", problem, words[i]);
            return false;
        }
    }
    rtp_scene built;
    if (rtp_scene_open(words[0], &opt, &built, err, err_size) != RTP_EXIT_OK) return false;
    const rt_camera *cam = &built.scene.camera;
    uint8_t *rgb = malloc((size_t)cam->width * cam->height * 3);
    rt_tracer tracer = {.scene = &built.scene, .use_bvh = true};
    rtp_threads_options popt = {.threads = threads};
    bool ok = rgb && rtp_threads_render(&tracer, &popt, rgb);
    if (ok)
        rtk_render_hash(rgb, cam->width, cam->height, hash);
    else
        snprintf(err, err_size, "%s: out of memory for a %ux%u image", words[0], cam->width, cam->height);
    free(rgb);
    rtp_scene_close(&built);
    return ok;
}

/* Reads the manifest whole; entries point into *text. Exit code and one line on stderr on failure. */
static int read_manifest(const char *path, char **text, entry **entries, int *count)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "rtk verify: cannot read '%s'\n", path);
        return RTP_EXIT_INPUT;
    }
    size_t size = 0, cap = 4096;
    char *buf = malloc(cap);
    size_t n;
    while (buf && (n = fread(buf + size, 1, cap - size - 1, f)) > 0) {
        size += n;
        if (cap - size - 1 == 0) buf = realloc(buf, cap *= 2);
    }
    fclose(f);
    if (!buf) return fprintf(stderr, "rtk verify: %s: out of memory\n", path), RTP_EXIT_MEMORY;
    buf[size] = '\0';
    *text = buf;
    *entries = NULL;
    *count = 0;
    unsigned line = 0;
    for (char *s = buf; s && *s; line++) {
        char *end = strchr(s, '\n');
        if (end) *end = '\0';
        size_t len = strlen(s);
        if (len && s[len - 1] == '\r') s[len - 1] = '\0';
        char *next = end ? end + 1 : NULL;
        if (*s && *s != '#') {
            entry e = {.line = line + 1};
            if (strlen(s) < 67 || !is_hash(s) || s[64] != ' ' || s[65] != ' ') {
                fprintf(stderr, "rtk verify: %s:%u: expected 64 hex digits, two spaces and a scene\n", path, e.line);
                return RTP_EXIT_INPUT;
            }
            memcpy(e.hash, s, 64);
            e.hash[64] = '\0';
            e.text = s + 66;
            char *words = strdup(e.text);
            if (!words || !split_words(words, e.words, &e.count) || e.count == 0) {
                fprintf(stderr, "rtk verify: %s:%u: expected a scene and at most %d options (quotes closed)\n", path,
                        e.line, MAX_TOKENS - 1);
                free(words);
                return RTP_EXIT_INPUT;
            }
            entry *grown = realloc(*entries, (size_t)(*count + 1) * sizeof *grown);
            if (!grown) return fprintf(stderr, "rtk verify: %s: out of memory\n", path), RTP_EXIT_MEMORY;
            *entries = grown;
            (*entries)[(*count)++] = e;
        }
        s = next;
    }
    return RTP_EXIT_OK;
}

static void xml_text(FILE *out, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        default:
            if ((unsigned char)*s >= 0x20 || *s == '\t') fputc(*s, out);
        }
    }
}

/* The results as JUnit XML (one testsuite, a testcase per manifest line), written atomically. */
static bool write_junit(const char *path, const char *manifest, const result *r, int count, double total)
{
    char *xml = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&xml, &size);
    if (!out) return false;
    int failures = 0, errors = 0;
    for (int i = 0; i < count; i++) failures += r[i].rendered && !r[i].ok, errors += !r[i].rendered;
    fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(out, "<testsuites name=\"rtk verify\" tests=\"%d\" failures=\"%d\" errors=\"%d\" time=\"%.3f\">\n", count,
            failures, errors, total);
    fprintf(out, "  <testsuite name=\"");
    xml_text(out, manifest);
    fprintf(out, "\" tests=\"%d\" failures=\"%d\" errors=\"%d\" time=\"%.3f\">\n", count, failures, errors, total);
    for (int i = 0; i < count; i++) {
        fprintf(out, "    <testcase classname=\"rtk.verify\" name=\"");
        xml_text(out, r[i].item.text);
        fprintf(out, "\" time=\"%.3f\">", r[i].seconds);
        if (!r[i].rendered) {
            fprintf(out, "\n      <error message=\"");
            xml_text(out, r[i].error);
            fprintf(out, "\"/>\n    ");
        } else if (!r[i].ok) {
            fprintf(out, "\n      <failure message=\"render hash differs\">expected %s, got %s</failure>\n    ",
                    r[i].item.hash, r[i].got);
        }
        fprintf(out, "</testcase>\n");
    }
    fprintf(out, "  </testsuite>\n</testsuites>\n");
    bool ok = fclose(out) == 0;
    char err[RTP_ERR_SIZE];
    if (ok && !rtp_file_write_atomic(path, xml, size, err, sizeof err)) {
        fprintf(stderr, "rtk verify: %s\n", err);
        ok = false;
    }
    free(xml);
    return ok;
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int check(const char *manifest, const char *junit, uint32_t threads)
{
    char *text = NULL;
    entry *entries = NULL;
    int count = 0;
    int rc = read_manifest(manifest, &text, &entries, &count);
    result *results = rc == RTP_EXIT_OK ? calloc((size_t)count + 1, sizeof *results) : NULL;
    if (rc == RTP_EXIT_OK && !results) rc = RTP_EXIT_MEMORY, fprintf(stderr, "rtk verify: out of memory\n");
    double start = seconds_now();
    int failed = 0;
    for (int i = 0; rc == RTP_EXIT_OK && i < count; i++) {
        result *r = &results[i];
        r->item = entries[i];
        double t0 = seconds_now();
        r->rendered = render_hash(r->item.words, r->item.count, threads, r->got, r->error, sizeof r->error);
        r->seconds = seconds_now() - t0;
        r->ok = r->rendered && strcmp(r->got, r->item.hash) == 0;
        failed += !r->ok;
        if (r->ok)
            printf("%s: OK\n", r->item.words[0]);
        else if (r->rendered)
            printf("%s: FAILED (got %s)\n", r->item.words[0], r->got);
        else
            printf("%s: FAILED (%s)\n", r->item.words[0], r->error);
        fflush(stdout);
    }
    if (rc == RTP_EXIT_OK && junit && !write_junit(junit, manifest, results, count, seconds_now() - start))
        rc = RTP_EXIT_OUTPUT;
    if (rc == RTP_EXIT_OK && failed) {
        fprintf(stderr, "rtk verify: WARNING: %d of %d render hash%s did NOT match\n", failed, count,
                count == 1 ? "" : "es");
        rc = RTP_EXIT_THRESHOLD;
    }
    for (int i = 0; entries && i < count; i++) free(entries[i].words[0]);
    free(entries);
    free(results);
    free(text);
    return rc;
}

/* Writes "HASH  SCENE OPTIONS" for each scene, rendered with the options. */
static int write_manifest(const char *manifest, char **scenes, int scene_count, char **options, int option_count,
                          uint32_t threads)
{
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    if (!out) return fprintf(stderr, "rtk verify: out of memory\n"), RTP_EXIT_MEMORY;
    int rc = RTP_EXIT_OK;
    for (int s = 0; rc == RTP_EXIT_OK && s < scene_count; s++) {
        char *words[MAX_TOKENS];
        int count = 0;
        words[count++] = scenes[s];
        for (int o = 0; o < option_count && count < MAX_TOKENS; o++) words[count++] = options[o];
        char hash[RTK_HASH_SIZE], err[RTP_ERR_SIZE];
        if (!render_hash(words, count, threads, hash, err, sizeof err)) {
            fprintf(stderr, "rtk verify: %s\n", err);
            rc = RTP_EXIT_INPUT;
            break;
        }
        fprintf(out, "%s  %s%s%s", hash, strchr(scenes[s], ' ') ? "\"" : "", scenes[s],
                strchr(scenes[s], ' ') ? "\"" : "");
        for (int o = 0; o < option_count; o++) fprintf(out, " %s", options[o]);
        fputc('\n', out);
    }
    bool closed = fclose(out) == 0;
    char err[RTP_ERR_SIZE];
    if (rc == RTP_EXIT_OK && (!closed || !rtp_file_write_atomic(manifest, text, size, err, sizeof err))) {
        fprintf(stderr, "rtk verify: %s\n", closed ? err : "out of memory");
        rc = closed ? RTP_EXIT_OUTPUT : RTP_EXIT_MEMORY;
    }
    free(text);
    return rc;
}

int rtp_cmd_verify(int argc, char **argv)
{
    const char *manifest = NULL, *junit = NULL, *write = NULL;
    uint32_t threads = 0;
    char **scenes = calloc((size_t)argc, sizeof *scenes), **options = calloc((size_t)argc, sizeof *options);
    int scene_count = 0, option_count = 0, rc = RTP_EXIT_OK;
    if (!scenes || !options) rc = RTP_EXIT_MEMORY, fprintf(stderr, "rtk verify: out of memory\n");
    rtp_scene_options ignored = rtp_scene_default_options();
    for (int i = 1; rc == RTP_EXIT_OK && i < argc; i++) {
        const char *arg = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int first = i, parsed;
        const char *problem;
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            fputs(usage, stdout);
            rc = -1;
        } else if (!strcmp(arg, "--junit") || !strcmp(arg, "--write")) {
            if (!val) rc = rtp_cli_usage_error("verify", "missing file after", arg);
            *(arg[2] == 'j' ? &junit : &write) = val, i++;
        } else if (!strcmp(arg, "--threads")) {
            if (!rtp_cli_parse_u32(val, 1, 1024, &threads))
                rc = rtp_cli_usage_error("verify", "expected 1..1024 after", arg);
            i++;
        } else if ((parsed = rtp_cli_parse_scene_option(argc, argv, &i, &ignored, &problem)) < 0) {
            rc = rtp_cli_usage_error("verify", problem, arg);
        } else if (parsed > 0) {
            options[option_count++] = argv[first], options[option_count++] = argv[first + 1];
        } else if (arg[0] == '-' && arg[1]) {
            rc = rtp_cli_usage_error("verify", "unknown option", arg);
        } else {
            scenes[scene_count++] = argv[i];
        }
    }
    if (rc == RTP_EXIT_OK && write) {
        if (!scene_count) rc = rtp_cli_usage_error("verify", "--write needs at least one scene", NULL);
        if (junit) rc = rtp_cli_usage_error("verify", "--junit goes with checking, not with", "--write");
        if (rc == RTP_EXIT_OK) rc = write_manifest(write, scenes, scene_count, options, option_count, threads);
    } else if (rc == RTP_EXIT_OK) {
        manifest = scene_count == 1 ? scenes[0] : NULL;
        if (!manifest || option_count)
            rc = rtp_cli_usage_error("verify", "give one MANIFEST (scene options go in it, or with --write)", NULL);
        else
            rc = check(manifest, junit, threads);
    }
    free(scenes);
    free(options);
    return rc < 0 ? RTP_EXIT_OK : rc;
}

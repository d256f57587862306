/* `rtk verify`: render hashes as a CI check, in the shape of `sha256sum -c`. */
#include "cli/verify_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "cli/message.h"
#include "cli/signals.h"
#include "image/file_write.h"
#include "load/input_file.h"
#include "mem/mem.h"
#include "mem/mem_stream.h"
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
    "the ones below that change pixels, and --max-memory, which caps all rtk holds while\n"
    "that line renders. Blank lines and lines starting with # are skipped. MANIFEST '-'\n"
    "is standard input; scenes must be files. Prints \"SCENE: OK\" or \"SCENE: FAILED\n"
    "(got HASH)\" for each line.\n"
    "\n"
    "  --junit FILE        also write the results as JUnit XML, for CI systems\n"
    "  --threads N         render threads (default: all cores); hashes do not depend on it\n"
    "  --write MANIFEST    render each SCENE with the options given and write a manifest\n" RTP_CLI_SCENE_OPTIONS_HELP
    "\n"
    "Exit codes: 0 every hash matches, 1 a hash differs or a scene cannot be rendered,\n"
    "2 bad arguments (also --junit or --write naming one of the inputs), 3 the manifest\n"
    "(or, with --write, a scene) is unreadable or malformed, 4 a file or standard output\n"
    "cannot be written, 5 over the memory cap, 6 interrupted.\n";

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
    bool ok, rendered;
    char got[RTK_HASH_SIZE];
    char *error; /* why it was not rendered (rtp_mem's) */
    double seconds;
} result;

/* A manifest in memory: its bytes (lines cut at their ends), and a copy in which each
 * entry's words are split at the same offsets; all rtp_mem's. */
typedef struct {
    char *text, *words;
    entry *entries;
    int count;
} manifest;

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

/* Renders the scene words[0] with the options words[1..], under their --max-memory, into
 * hash. Returns RTP_EXIT_OK, or the exit code `rtk render` would give, with one line in err. */
static int render_hash(char **words, int count, uint32_t threads, char hash[RTK_HASH_SIZE], char *err, size_t err_size)
{
    rtp_scene_options opt = rtp_scene_default_options();
    opt.threads = threads;
    opt.with_image = true;
    if (!strcmp(words[0], "-")) {
        snprintf(err, err_size, "'-': a manifest names scene files, not standard input");
        return RTP_EXIT_USAGE;
    }
    for (int i = 1; i < count; i++) {
        const char *problem = "unknown option";
        if (rtp_cli_parse_scene_option(count, words, &i, &opt, &problem) <= 0) {
            snprintf(err, err_size, "%s '%s'", problem, words[i]);
            return RTP_EXIT_USAGE;
        }
    }
    size_t process_cap = rtp_mem_cap();
    rtp_mem_set_cap(opt.max_memory);
    rtp_scene built;
    int rc = rtp_scene_open(words[0], &opt, &built, err, err_size);
    if (rc == RTP_EXIT_OK) {
        const rt_camera *cam = &built.scene.camera;
        rt_tracer tracer = {.scene = &built.scene, .use_bvh = true};
        rtp_threads_options popt = {.threads = threads};
        if (rtp_threads_render(&tracer, &popt, built.image.rgb))
            rtk_render_hash(built.image.rgb, cam->width, cam->height, hash);
        else
            rc = RTP_EXIT_MEMORY, snprintf(err, err_size, "%s: no memory for the render's threads", words[0]);
        rtp_scene_close(&built);
    }
    rtp_mem_set_cap(process_cap);
    return rc;
}

static void manifest_free(manifest *m)
{
    rtp_mem_free(m->text);
    rtp_mem_free(m->words);
    rtp_mem_free(m->entries);
    *m = (manifest){0};
}

/* Checks and splits one line (cut, at offset `at` of the text) into *e. Exit code. */
static int parse_line(const char *name, manifest *m, size_t at, unsigned line, entry *e)
{
    char *s = m->text + at;
    *e = (entry){.line = line};
    if (strlen(s) < 67 || !is_hash(s) || s[64] != ' ' || s[65] != ' ') {
        rtp_message("verify", "%s:%u: expected 64 hex digits, two spaces and a scene", name, line);
        return RTP_EXIT_INPUT;
    }
    memcpy(e->hash, s, 64);
    e->hash[64] = '\0';
    e->text = s + 66;
    char *words = m->words + at + 66;
    memcpy(words, e->text, strlen(e->text) + 1);
    if (!split_words(words, e->words, &e->count) || e->count == 0) {
        rtp_message("verify", "%s:%u: expected a scene and at most %d options (quotes closed)", name, line,
                    MAX_TOKENS - 1);
        return RTP_EXIT_INPUT;
    }
    return RTP_EXIT_OK;
}

/* Adds a zeroed entry at the end of m->entries; NULL when it does not fit. */
static entry *new_entry(manifest *m, int *capacity)
{
    if (m->count == *capacity) {
        int grown = *capacity ? 2 * *capacity : 16;
        entry *more = rtp_mem_realloc(m->entries, (size_t)grown * sizeof *more, "the manifest's entries");
        if (!more) return NULL;
        m->entries = more;
        *capacity = grown;
    }
    return &m->entries[m->count++];
}

/* Reads the manifest whole, by the input rules ('-': standard input), into *m. Exit code,
 * with one line on stderr on failure. */
static int read_manifest(const char *path, manifest *m)
{
    const char *name = rtp_cli_scene_name(path);
    rtp_input in;
    char why[RTP_ERR_SIZE];
    uint8_t *data = NULL;
    size_t size = 0;
    *m = (manifest){0};
    if (!rtp_input_open(&in, path, true, why, sizeof why) ||
        !rtp_input_read(&in, 0, "a manifest", &data, &size, why, sizeof why)) {
        rtp_message("verify", "%s: %s%s", name, in.open_failed ? "cannot read: " : "", why);
        return rtp_load_failure_code();
    }
    m->text = rtp_mem_realloc(data, size + 1, "the manifest");
    m->words = m->text ? rtp_mem_alloc(size + 1, "the manifest") : NULL;
    if (!m->words) {
        if (!m->text) rtp_mem_free(data);
        manifest_free(m);
        rtp_message("verify", "%s: %s", name, rtp_mem_refusal());
        return RTP_EXIT_MEMORY;
    }
    m->text[size] = '\0';
    int rc = RTP_EXIT_OK, capacity = 0;
    unsigned line = 0;
    for (size_t at = 0; rc == RTP_EXIT_OK && at < size;) {
        char *s = m->text + at, *end = memchr(s, '\n', size - at);
        size_t len = end ? (size_t)(end - s) : size - at;
        line++;
        if (memchr(s, '\0', len)) {
            rtp_message("verify", "%s:%u: a NUL byte: not a manifest", name, line);
            rc = RTP_EXIT_INPUT;
            break;
        }
        s[len] = '\0';
        if (len && s[len - 1] == '\r') s[len - 1] = '\0';
        if (*s && *s != '#') {
            entry *e = new_entry(m, &capacity);
            if (!e) {
                rtp_message("verify", "%s: %s", name, rtp_mem_refusal());
                rc = RTP_EXIT_MEMORY;
            } else {
                rc = parse_line(name, m, at, line, e);
            }
        }
        at += len + 1;
    }
    if (rc != RTP_EXIT_OK) manifest_free(m);
    return rc;
}

/* s as XML character data: markup characters as entities, control characters and bytes
 * that are not UTF-8 shown escaped as in rtk's messages, so the report stays well-formed. */
static void xml_text(FILE *out, const char *s)
{
    while (*s) {
        char piece[8];
        size_t step, n = rtp_message_escape_char(s, piece, &step);
        switch (*s) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fwrite(piece, 1, n, out);
        }
        s += step;
    }
}

/* The results as JUnit XML (one testsuite, a testcase per manifest line), written by
 * rtp_file_write's rules. Exit code, with one line on stderr on failure. */
static int write_junit(const char *path, const char *name, const manifest *m, const result *r, double total)
{
    rtp_mem_buffer xml = {.what = "the JUnit report"};
    FILE *out = rtp_mem_stream_open(&xml);
    if (!out) {
        rtp_message("verify", "%s: cannot compose the JUnit report", path);
        return RTP_EXIT_MEMORY;
    }
    int failures = 0, errors = 0;
    for (int i = 0; i < m->count; i++) failures += r[i].rendered && !r[i].ok, errors += !r[i].rendered;
    fprintf(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(out, "<testsuites name=\"rtk verify\" tests=\"%d\" failures=\"%d\" errors=\"%d\" time=\"%.3f\">\n",
            m->count, failures, errors, total);
    fprintf(out, "  <testsuite name=\"");
    xml_text(out, name);
    fprintf(out, "\" tests=\"%d\" failures=\"%d\" errors=\"%d\" time=\"%.3f\">\n", m->count, failures, errors, total);
    for (int i = 0; i < m->count; i++) {
        fprintf(out, "    <testcase classname=\"rtk.verify\" name=\"");
        xml_text(out, m->entries[i].text);
        fprintf(out, "\" time=\"%.3f\">", r[i].seconds);
        if (!r[i].rendered) {
            fprintf(out, "\n      <error message=\"");
            xml_text(out, r[i].error);
            fprintf(out, "\"/>\n    ");
        } else if (!r[i].ok) {
            fprintf(out, "\n      <failure message=\"render hash differs\">expected %s, got %s</failure>\n    ",
                    m->entries[i].hash, r[i].got);
        }
        fprintf(out, "</testcase>\n");
    }
    fprintf(out, "  </testsuite>\n</testsuites>\n");
    int rc = RTP_EXIT_OK;
    char err[RTP_ERR_SIZE];
    if (fclose(out) != 0) {
        rtp_message("verify", "%s: %s", path, rtp_mem_refusal());
        rc = RTP_EXIT_MEMORY;
    } else if (!rtp_file_write(path, xml.data, xml.size, err, sizeof err)) {
        rtp_message("verify", "%s", err);
        rc = RTP_EXIT_OUTPUT;
    }
    rtp_mem_buffer_free(&xml);
    return rc;
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* Renders one entry into r and prints its line (control characters escaped). Returns
 * RTP_EXIT_OK, or the exit code that ends the whole run: 2 when its scene is the --junit
 * file, 4 when standard output cannot be written, 5 when its result does not fit. */
static int check_entry(entry *e, result *r, uint32_t threads)
{
    char err[RTP_ERR_SIZE], scene[RTP_ERR_SIZE], shown[4 * RTP_ERR_SIZE];
    double t0 = seconds_now();
    r->rendered = render_hash(e->words, e->count, threads, r->got, err, sizeof err) == RTP_EXIT_OK;
    r->seconds = seconds_now() - t0;
    r->ok = r->rendered && strcmp(r->got, e->hash) == 0;
    if (rtp_input_was_output()) {
        rtp_message("verify", "%s", err);
        return RTP_EXIT_USAGE;
    }
    if (!r->rendered && !(r->error = rtp_mem_strdup(err, "the results"))) {
        rtp_message("verify", "%s", rtp_mem_refusal());
        return RTP_EXIT_MEMORY;
    }
    rtp_message_escape(e->words[0], scene, sizeof scene);
    if (r->ok)
        printf("%s: OK\n", scene);
    else if (r->rendered)
        printf("%s: FAILED (got %s)\n", scene, r->got);
    else
        rtp_message_escape(err, shown, sizeof shown), printf("%s: FAILED (%s)\n", scene, shown);
    return rtp_cli_flush_stdout("verify");
}

static int check(const char *path, const char *junit, uint32_t threads)
{
    manifest m;
    int rc = read_manifest(path, &m);
    if (rc != RTP_EXIT_OK) return rc;
    result *results = rtp_mem_calloc((size_t)m.count + 1, sizeof *results, "the results");
    if (!results) rc = RTP_EXIT_MEMORY, rtp_message("verify", "%s", rtp_mem_refusal());
    double start = seconds_now();
    int failed = 0;
    for (int i = 0; rc == RTP_EXIT_OK && i < m.count; i++) {
        rc = check_entry(&m.entries[i], &results[i], threads);
        failed += !results[i].ok;
    }
    if (rc == RTP_EXIT_OK && junit)
        rc = write_junit(junit, rtp_cli_scene_name(path), &m, results, seconds_now() - start);
    if (rc == RTP_EXIT_OK && failed) {
        rtp_message("verify", "WARNING: %d of %d render hash%s did NOT match", failed, m.count,
                    m.count == 1 ? "" : "es");
        rc = RTP_EXIT_THRESHOLD;
    }
    for (int i = 0; results && i < m.count; i++) rtp_mem_free(results[i].error);
    rtp_mem_free(results);
    manifest_free(&m);
    return rc;
}

/* Writes "HASH  SCENE OPTIONS" for each scene, rendered with the options. */
static int write_manifest(const char *path, char **scenes, int scene_count, char **options, int option_count,
                          uint32_t threads)
{
    rtp_mem_buffer text = {.what = "the manifest"};
    FILE *out = rtp_mem_stream_open(&text);
    if (!out) return rtp_message("verify", "%s: cannot compose the manifest", path), RTP_EXIT_MEMORY;
    int rc = RTP_EXIT_OK;
    for (int s = 0; rc == RTP_EXIT_OK && s < scene_count; s++) {
        char *words[MAX_TOKENS];
        int count = 0;
        words[count++] = scenes[s];
        for (int o = 0; o < option_count && count < MAX_TOKENS; o++) words[count++] = options[o];
        char hash[RTK_HASH_SIZE], err[RTP_ERR_SIZE];
        rc = render_hash(words, count, threads, hash, err, sizeof err);
        if (rc != RTP_EXIT_OK) {
            rtp_message("verify", "%s", err);
            break;
        }
        fprintf(out, "%s  %s%s%s", hash, strchr(scenes[s], ' ') ? "\"" : "", scenes[s],
                strchr(scenes[s], ' ') ? "\"" : "");
        for (int o = 0; o < option_count; o++) fprintf(out, " %s", options[o]);
        fputc('\n', out);
    }
    bool closed = fclose(out) == 0;
    char err[RTP_ERR_SIZE];
    if (rc == RTP_EXIT_OK && !closed) {
        rtp_message("verify", "%s: %s", path, rtp_mem_refusal());
        rc = RTP_EXIT_MEMORY;
    } else if (rc == RTP_EXIT_OK && !rtp_file_write(path, text.data, text.size, err, sizeof err)) {
        rtp_message("verify", "%s", err);
        rc = RTP_EXIT_OUTPUT;
    }
    rtp_mem_buffer_free(&text);
    return rc;
}

int rtp_cmd_verify(int argc, char **argv)
{
    const char *manifest_path = NULL, *junit = NULL, *write = NULL;
    uint32_t threads = 0;
    char **scenes = calloc((size_t)argc, sizeof *scenes), **options = calloc((size_t)argc, sizeof *options);
    int scene_count = 0, option_count = 0, rc = RTP_EXIT_OK;
    if (!scenes || !options) rc = RTP_EXIT_MEMORY, rtp_message("verify", "out of memory");
    rtp_scene_options ignored = rtp_scene_default_options();
    for (int i = 1; rc == RTP_EXIT_OK && i < argc; i++) {
        const char *arg = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int first = i, parsed;
        const char *problem;
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            fputs(usage, stdout);
            rc = rtp_cli_flush_stdout("verify");
            if (rc == RTP_EXIT_OK) rc = -1;
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
        for (int s = 0; rc == RTP_EXIT_OK && s < scene_count; s++)
            if (!strcmp(scenes[s], "-"))
                rc = rtp_cli_usage_error("verify", "a manifest names scene files: give a path, not", scenes[s]);
        if (rc == RTP_EXIT_OK) {
            rtp_signals_install("verify", write);
            rtp_input_forbid(write); /* before any scene is read */
            rc = write_manifest(write, scenes, scene_count, options, option_count, threads);
        }
    } else if (rc == RTP_EXIT_OK) {
        manifest_path = scene_count == 1 ? scenes[0] : NULL;
        if (!manifest_path || option_count) {
            rc = rtp_cli_usage_error("verify", "give one MANIFEST (scene options go in it, or with --write)", NULL);
        } else {
            rtp_signals_install("verify", rtp_cli_scene_name(manifest_path));
            if (junit) rtp_input_forbid(junit); /* before the manifest is read */
            rc = check(manifest_path, junit, threads);
        }
    }
    free(scenes);
    free(options);
    return rc < 0 ? RTP_EXIT_OK : rc;
}

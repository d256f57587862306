/* Typed reading of a libyaml document with one-line error reports (see yaml_read.h). */
#include "load/yaml_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool is_null(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE) return false;
    if (n->tag && strcmp((const char *)n->tag, YAML_NULL_TAG) == 0) return true;
    if (n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE) return false;
    const char *s = (const char *)n->data.scalar.value;
    return !*s || !strcmp(s, "~") || !strcmp(s, "null") || !strcmp(s, "Null") || !strcmp(s, "NULL");
}

/* Turns anything that would break the one-line message (newlines, controls) into '?'. */
static void one_line(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) *s = '?';
}

/* Rejects nodes reachable twice: an alias may even point at its own ancestor. */
static bool check_tree(rtp_yaml *y)
{
    size_t count = (size_t)(y->doc.nodes.top - y->doc.nodes.start);
    unsigned char *refs = calloc(count + 1, 1);
    if (!refs) return rtp_yaml_fail(y, NULL, NULL, "out of memory");
    for (yaml_node_t *n = y->doc.nodes.start; n < y->doc.nodes.top; n++) {
        if (n->type == YAML_MAPPING_NODE) {
            for (yaml_node_pair_t *p = n->data.mapping.pairs.start; p < n->data.mapping.pairs.top; p++) {
                refs[p->key] = (unsigned char)(refs[p->key] < 2 ? refs[p->key] + 1 : 2);
                refs[p->value] = (unsigned char)(refs[p->value] < 2 ? refs[p->value] + 1 : 2);
            }
        } else if (n->type == YAML_SEQUENCE_NODE) {
            for (yaml_node_item_t *i = n->data.sequence.items.start; i < n->data.sequence.items.top; i++)
                refs[*i] = (unsigned char)(refs[*i] < 2 ? refs[*i] + 1 : 2);
        }
    }
    for (size_t i = 1; i <= count; i++) {
        if (refs[i] > (i == 1 ? 0 : 1)) {
            free(refs);
            return rtp_yaml_fail(y, yaml_document_get_node(&y->doc, (int)i), NULL,
                                 "this node is reused through an alias; aliases are not supported");
        }
    }
    free(refs);
    return true;
}

static bool parse_error(rtp_yaml *y, const yaml_parser_t *p)
{
    if (p->error == YAML_MEMORY_ERROR) {
        snprintf(y->err, y->err_size, "%s: out of memory", y->file);
    } else if (p->error == YAML_READER_ERROR) {
        snprintf(y->err, y->err_size, "%s: byte %zu: invalid YAML: %s", y->file, p->problem_offset,
                 p->problem ? p->problem : "unreadable input");
    } else {
        snprintf(y->err, y->err_size, "%s:%zu:%zu: invalid YAML: %s%s%s", y->file, p->problem_mark.line + 1,
                 p->problem_mark.column + 1, p->problem ? p->problem : "syntax error", p->context ? " " : "",
                 p->context ? p->context : "");
    }
    one_line(y->err);
    return false;
}

/* libyaml 0.2.5 scans in time quadratic in the nesting depth (a 100 KB file of '['
 * takes minutes), so a first pass over the events refuses deep documents before
 * yaml_parser_load reads them. Only the first document is looked at, as the load does. */
static bool check_depth(rtp_yaml *y, FILE *f)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) return rtp_yaml_fail(y, NULL, NULL, "out of memory");
    yaml_parser_set_input_file(&parser, f);
    bool ok = true, done = false;
    unsigned depth = 0;
    while (ok && !done) {
        yaml_event_t event;
        if (!yaml_parser_parse(&parser, &event)) {
            ok = parse_error(y, &parser);
            break;
        }
        if (event.type == YAML_SEQUENCE_START_EVENT || event.type == YAML_MAPPING_START_EVENT) {
            if (++depth > RTP_YAML_MAX_DEPTH) {
                snprintf(y->err, y->err_size, "%s:%zu:%zu: invalid YAML: nested more than %d levels deep", y->file,
                         event.start_mark.line + 1, event.start_mark.column + 1, RTP_YAML_MAX_DEPTH);
                ok = false;
            }
        } else if (event.type == YAML_SEQUENCE_END_EVENT || event.type == YAML_MAPPING_END_EVENT) {
            depth--;
        }
        done = event.type == YAML_DOCUMENT_END_EVENT || event.type == YAML_STREAM_END_EVENT;
        yaml_event_delete(&event);
    }
    yaml_parser_delete(&parser);
    return ok;
}

bool rtp_yaml_open(rtp_yaml *y, const char *file, char *err, size_t err_size)
{
    memset(y, 0, sizeof *y);
    y->file = file;
    y->err = err;
    y->err_size = err_size;
    FILE *f = fopen(file, "rb");
    if (!f) {
        snprintf(err, err_size, "%s: cannot open: %s", file, strerror(errno));
        return false;
    }
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        snprintf(err, err_size, "%s: is a directory", file);
        return false;
    }
    if (!check_depth(y, f)) {
        fclose(f);
        return false;
    }
    rewind(f);
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) {
        fclose(f);
        return rtp_yaml_fail(y, NULL, NULL, "out of memory");
    }
    yaml_parser_set_input_file(&parser, f);
    bool loaded = yaml_parser_load(&parser, &y->doc);
    if (!loaded) parse_error(y, &parser);
    yaml_parser_delete(&parser);
    fclose(f);
    if (!loaded) return false;
    if (!rtp_yaml_root(y)) {
        yaml_document_delete(&y->doc);
        snprintf(err, err_size, "%s:1:1: expected a scene (a YAML map), got an empty file", file);
        return false;
    }
    if (!check_tree(y)) {
        yaml_document_delete(&y->doc);
        return false;
    }
    return true;
}

void rtp_yaml_close(rtp_yaml *y) { yaml_document_delete(&y->doc); }

yaml_node_t *rtp_yaml_root(rtp_yaml *y) { return yaml_document_get_root_node(&y->doc); }

size_t rtp_yaml_push(rtp_yaml *y, const char *segment)
{
    size_t mark = y->path_len;
    int n = snprintf(y->path + mark, sizeof y->path - mark, "%s%s", mark ? "/" : "", segment);
    if (n > 0) y->path_len = mark + (size_t)n < sizeof y->path ? mark + (size_t)n : sizeof y->path - 1;
    return mark;
}

void rtp_yaml_pop(rtp_yaml *y, size_t mark)
{
    y->path_len = mark;
    y->path[mark] = '\0';
}

bool rtp_yaml_fail(rtp_yaml *y, const yaml_node_t *at, const char *key, const char *fmt, ...)
{
    size_t len = 0;
    int n =
        at ? snprintf(y->err, y->err_size, "%s:%zu:%zu: ", y->file, at->start_mark.line + 1, at->start_mark.column + 1)
           : snprintf(y->err, y->err_size, "%s: ", y->file);
    if (n > 0) len = (size_t)n;
    if (len < y->err_size && (y->path_len || key)) {
        n = snprintf(y->err + len, y->err_size - len, "%s%s%s: ", y->path, y->path_len && key ? "/" : "",
                     key ? key : "");
        if (n > 0) len += (size_t)n;
    }
    if (len < y->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(y->err + len, y->err_size - len, fmt, ap);
        va_end(ap);
    }
    one_line(y->err);
    return false;
}

bool rtp_yaml_expected(rtp_yaml *y, const yaml_node_t *at, const char *key, const char *what)
{
    if (!at) return rtp_yaml_fail(y, at, key, "expected %s, got nothing", what);
    if (at->type == YAML_MAPPING_NODE) return rtp_yaml_fail(y, at, key, "expected %s, got a map", what);
    if (at->type == YAML_SEQUENCE_NODE) return rtp_yaml_fail(y, at, key, "expected %s, got a list", what);
    const char *text = rtp_yaml_text(at);
    if (!*text) return rtp_yaml_fail(y, at, key, "expected %s, got an empty value", what);
    int shown = strlen(text) > 40 ? 40 : (int)strlen(text);
    return rtp_yaml_fail(y, at, key, "expected %s, got '%.*s%s'", what, shown, text, text[shown] ? "..." : "");
}

const char *rtp_yaml_text(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

size_t rtp_yaml_count(const yaml_node_t *n)
{
    if (!n) return 0;
    if (n->type == YAML_MAPPING_NODE) return (size_t)(n->data.mapping.pairs.top - n->data.mapping.pairs.start);
    if (n->type == YAML_SEQUENCE_NODE) return (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
    return 0;
}

yaml_node_t *rtp_yaml_pair(rtp_yaml *y, const yaml_node_t *map, size_t i, yaml_node_t **value)
{
    const yaml_node_pair_t *p = &map->data.mapping.pairs.start[i];
    yaml_node_t *v = yaml_document_get_node(&y->doc, p->value);
    *value = v && !is_null(v) ? v : NULL;
    return yaml_document_get_node(&y->doc, p->key);
}

yaml_node_t *rtp_yaml_item(rtp_yaml *y, const yaml_node_t *seq, size_t i)
{
    return yaml_document_get_node(&y->doc, seq->data.sequence.items.start[i]);
}

yaml_node_t *rtp_yaml_get(rtp_yaml *y, const yaml_node_t *map, const char *key)
{
    if (!map || map->type != YAML_MAPPING_NODE) return NULL;
    for (size_t i = 0; i < rtp_yaml_count(map); i++) {
        yaml_node_t *value;
        const char *k = rtp_yaml_text(rtp_yaml_pair(y, map, i, &value));
        if (k && !strcmp(k, key)) return value;
    }
    return NULL;
}

bool rtp_yaml_want_map(rtp_yaml *y, const yaml_node_t *n, const char *key)
{
    return !n || n->type == YAML_MAPPING_NODE || rtp_yaml_expected(y, n, key, "a map");
}

bool rtp_yaml_map(rtp_yaml *y, const yaml_node_t *map, const char *key, bool required, yaml_node_t **out)
{
    *out = rtp_yaml_get(y, map, key);
    if (!*out && required) return rtp_yaml_fail(y, map, key, "missing, expected a map");
    return rtp_yaml_want_map(y, *out, key);
}

bool rtp_yaml_seq(rtp_yaml *y, const yaml_node_t *map, const char *key, bool required, yaml_node_t **out)
{
    *out = rtp_yaml_get(y, map, key);
    if (!*out) return !required || rtp_yaml_fail(y, map, key, "missing, expected a list");
    return (*out)->type == YAML_SEQUENCE_NODE || rtp_yaml_expected(y, *out, key, "a list");
}

bool rtp_yaml_string(rtp_yaml *y, const yaml_node_t *map, const char *key, const char *def, const char **out)
{
    yaml_node_t *n = rtp_yaml_get(y, map, key);
    if (!n) {
        *out = def;
        return def || rtp_yaml_fail(y, map, key, "missing, expected a string");
    }
    *out = rtp_yaml_text(n);
    return *out || rtp_yaml_expected(y, n, key, "a string");
}

bool rtp_yaml_bool(rtp_yaml *y, const yaml_node_t *map, const char *key, bool def, bool *out)
{
    yaml_node_t *n = rtp_yaml_get(y, map, key);
    const char *s = rtp_yaml_text(n);
    *out = def;
    if (!n) return true;
    if (s && (!strcmp(s, "true") || !strcmp(s, "True") || !strcmp(s, "TRUE")))
        *out = true;
    else if (s && (!strcmp(s, "false") || !strcmp(s, "False") || !strcmp(s, "FALSE")))
        *out = false;
    else
        return rtp_yaml_expected(y, n, key, "true or false");
    return true;
}

bool rtp_yaml_real(rtp_yaml *y, const yaml_node_t *map, const char *key, double def, double *out)
{
    yaml_node_t *n = rtp_yaml_get(y, map, key);
    *out = def;
    if (!n) return true;
    if (n->type == YAML_MAPPING_NODE) {
        yaml_node_t *frames = rtp_yaml_get(y, n, "FrameValues");
        if (frames && frames->type == YAML_SEQUENCE_NODE && rtp_yaml_count(frames) > 0) n = rtp_yaml_item(y, frames, 0);
    }
    const char *s = rtp_yaml_text(n);
    char *end = NULL;
    double v = s && *s ? strtod(s, &end) : 0.0;
    if (!end || *end || !isfinite(v)) return rtp_yaml_expected(y, n, key, "a finite number");
    *out = v;
    return true;
}

bool rtp_yaml_uint(rtp_yaml *y, const yaml_node_t *map, const char *key, uint32_t def, uint32_t lo, uint32_t hi,
                   uint32_t *out)
{
    double v;
    if (!rtp_yaml_real(y, map, key, def, &v)) return false;
    if (!(v >= lo && v <= hi) || (double)(uint32_t)v != v) {
        char what[64];
        snprintf(what, sizeof what, "an integer from %u to %u", (unsigned)lo, (unsigned)hi);
        return rtp_yaml_expected(y, rtp_yaml_get(y, map, key), key, what);
    }
    *out = (uint32_t)v;
    return true;
}

bool rtp_yaml_index(rtp_yaml *y, const yaml_node_t *map, const char *key, uint32_t def, uint32_t last, uint32_t *out)
{
    double v;
    if (!rtp_yaml_real(y, map, key, def, &v)) return false;
    if (v > last) { /* the skeleton clamps choice indices to the last choice */
        *out = last;
        return true;
    }
    return rtp_yaml_uint(y, map, key, def, 0, last, out);
}

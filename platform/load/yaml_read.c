/* Typed reading of a YAML tree with one-line error reports (see yaml_read.h). */
#include "load/yaml_read.h"

#include "load/input_file.h"
#include "mem/mem.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Named in messages for the scene read from standard input. */
static const char stdin_name[] = "<stdin>";

bool rtp_yaml_open(rtp_yaml *y, const char *file, char *err, size_t err_size)
{
    memset(y, 0, sizeof *y);
    bool from_stdin = !strcmp(file, "-");
    y->file = from_stdin ? stdin_name : file;
    y->err = err;
    y->err_size = err_size;
    rtp_input in;
    uint8_t *data;
    size_t size;
    char why[RTP_YAML_PATH_SIZE];
    if (!rtp_input_open(&in, file, true, why, sizeof why)) {
        snprintf(err, err_size, "%s: %s%s%s", y->file, in.open_failed ? "cannot open: " : "", why,
                 in.special ? " (give - to read the scene from standard input)" : "");
        return false;
    }
    if (!rtp_input_read(&in, 0, "a scene", &data, &size, why, sizeof why)) {
        snprintf(err, err_size, "%s: %s", y->file, why);
        return false;
    }
    bool ok = rtp_yaml_tree_parse(data, size, y->file, &y->tree, err, err_size);
    rtp_mem_free(data);
    if (ok && y->tree.node_count == 0) {
        snprintf(err, err_size, "%s:1:1: expected a scene (a YAML map), got an empty file", y->file);
        ok = false;
    }
    return ok;
}

void rtp_yaml_close(rtp_yaml *y) { rtp_yaml_tree_free(&y->tree); }

rtp_yaml_node *rtp_yaml_root(rtp_yaml *y) { return y->tree.node_count ? &y->tree.nodes[0] : NULL; }

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

bool rtp_yaml_fail(rtp_yaml *y, const rtp_yaml_node *at, const char *key, const char *fmt, ...)
{
    size_t len = 0;
    int n = at ? snprintf(y->err, y->err_size, "%s:%u:%u: ", y->file, at->line, at->column)
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
    return false;
}

bool rtp_yaml_expected(rtp_yaml *y, const rtp_yaml_node *at, const char *key, const char *what)
{
    if (!at) return rtp_yaml_fail(y, at, key, "expected %s, got nothing", what);
    if (at->kind == RTP_YAML_MAP) return rtp_yaml_fail(y, at, key, "expected %s, got a map", what);
    if (at->kind == RTP_YAML_SEQ) return rtp_yaml_fail(y, at, key, "expected %s, got a list", what);
    const char *text = rtp_yaml_text(at);
    if (!*text) return rtp_yaml_fail(y, at, key, "expected %s, got an empty value", what);
    int shown = strlen(text) > 40 ? 40 : (int)strlen(text);
    return rtp_yaml_fail(y, at, key, "expected %s, got '%.*s%s'", what, shown, text, text[shown] ? "..." : "");
}

const char *rtp_yaml_text(const rtp_yaml_node *n) { return n ? n->text : NULL; }

size_t rtp_yaml_count(const rtp_yaml_node *n) { return n && n->kind != RTP_YAML_SCALAR ? n->count : 0; }

rtp_yaml_node *rtp_yaml_pair(rtp_yaml *y, const rtp_yaml_node *map, size_t i, rtp_yaml_node **value)
{
    const uint32_t *pair = &y->tree.children[map->first + 2 * i];
    rtp_yaml_node *v = &y->tree.nodes[pair[1]];
    *value = v->is_null ? NULL : v;
    return &y->tree.nodes[pair[0]];
}

rtp_yaml_node *rtp_yaml_item(rtp_yaml *y, const rtp_yaml_node *seq, size_t i)
{
    return &y->tree.nodes[y->tree.children[seq->first + i]];
}

/* Linear in the map's size; the loader asks a fixed set of keys of each map, so reading
 * the whole file stays linear too. Keys are unique (yaml_tree.c refuses repeats). */
rtp_yaml_node *rtp_yaml_get(rtp_yaml *y, const rtp_yaml_node *map, const char *key)
{
    if (!map || map->kind != RTP_YAML_MAP) return NULL;
    for (size_t i = 0; i < map->count; i++) {
        rtp_yaml_node *value;
        const char *k = rtp_yaml_text(rtp_yaml_pair(y, map, i, &value));
        if (k && !strcmp(k, key)) return value;
    }
    return NULL;
}

bool rtp_yaml_want_map(rtp_yaml *y, const rtp_yaml_node *n, const char *key)
{
    return !n || n->kind == RTP_YAML_MAP || rtp_yaml_expected(y, n, key, "a map");
}

bool rtp_yaml_map(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool required, rtp_yaml_node **out)
{
    *out = rtp_yaml_get(y, map, key);
    if (!*out && required) return rtp_yaml_fail(y, map, key, "missing, expected a map");
    return rtp_yaml_want_map(y, *out, key);
}

bool rtp_yaml_seq(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool required, rtp_yaml_node **out)
{
    *out = rtp_yaml_get(y, map, key);
    if (!*out) return !required || rtp_yaml_fail(y, map, key, "missing, expected a list");
    return (*out)->kind == RTP_YAML_SEQ || rtp_yaml_expected(y, *out, key, "a list");
}

bool rtp_yaml_string(rtp_yaml *y, const rtp_yaml_node *map, const char *key, const char *def, const char **out)
{
    rtp_yaml_node *n = rtp_yaml_get(y, map, key);
    if (!n) {
        *out = def;
        return def || rtp_yaml_fail(y, map, key, "missing, expected a string");
    }
    *out = rtp_yaml_text(n);
    return *out || rtp_yaml_expected(y, n, key, "a string");
}

bool rtp_yaml_bool(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool def, bool *out)
{
    rtp_yaml_node *n = rtp_yaml_get(y, map, key);
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

bool rtp_yaml_real(rtp_yaml *y, const rtp_yaml_node *map, const char *key, double def, double *out)
{
    rtp_yaml_node *n = rtp_yaml_get(y, map, key);
    *out = def;
    if (!n) return true;
    if (n->kind == RTP_YAML_MAP) {
        rtp_yaml_node *frames = rtp_yaml_get(y, n, "FrameValues");
        if (frames && frames->kind == RTP_YAML_SEQ && rtp_yaml_count(frames) > 0) n = rtp_yaml_item(y, frames, 0);
    }
    const char *s = rtp_yaml_text(n);
    char *end = NULL;
    double v = s && *s ? strtod(s, &end) : 0.0;
    if (!end || *end || !isfinite(v)) return rtp_yaml_expected(y, n, key, "a finite number");
    *out = v;
    return true;
}

bool rtp_yaml_uint(rtp_yaml *y, const rtp_yaml_node *map, const char *key, uint32_t def, uint32_t lo, uint32_t hi,
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

bool rtp_yaml_index(rtp_yaml *y, const rtp_yaml_node *map, const char *key, uint32_t def, uint32_t last, uint32_t *out)
{
    double v;
    if (!rtp_yaml_real(y, map, key, def, &v)) return false;
    if (v > last) { /* the skeleton clamps choice indices to the last choice */
        *out = last;
        return true;
    }
    return rtp_yaml_uint(y, map, key, def, 0, last, out);
}

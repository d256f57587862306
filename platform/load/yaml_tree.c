/* Building a rtp_yaml_tree from libyaml's events in one pass (see yaml_tree.h). Nodes
 * are numbered in document order; a collection's children wait on a stack until its
 * end event, then move, contiguous, to the children array, so the work is linear. */
#include "load/yaml_tree.h"

#include "mem/mem.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <yaml.h>

#define PATH_SIZE 512

typedef struct {
    uint32_t node;       /* the collection's node */
    uint32_t self_at;    /* its own place on the pending stack (as its parent's child) */
    uint32_t pending_at; /* where its children start on the pending stack */
    bool flow;
} open_collection;

typedef struct {
    const char *file;
    char *err;
    size_t err_size;
    rtp_yaml_tree *t;
    uint32_t node_cap, child_count, child_cap;
    size_t text_len, text_cap;
    uint32_t *pending; /* children of the open collections, innermost last */
    uint32_t pending_count, pending_cap;
    open_collection *open;
    uint32_t depth, open_cap, flow_depth;
    uint64_t flow_work, flow_budget; /* the sum of the flow depths of the events so far, and its bound */
    uint32_t *slots;                 /* duplicate-key table, reused map to map */
    size_t slot_cap;
} builder;

static bool fail_at(builder *b, yaml_mark_t at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static bool fail_at(builder *b, yaml_mark_t at, const char *fmt, ...)
{
    int n = snprintf(b->err, b->err_size, "%s:%zu:%zu: ", b->file, at.line + 1, at.column + 1);
    if (n > 0 && (size_t)n < b->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(b->err + n, b->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

static bool out_of_memory(builder *b)
{
    return snprintf(b->err, b->err_size, "%s: %s", b->file, rtp_mem_refusal()), false;
}

/* Makes room for one more element of size bytes in *array of *cap elements. */
static bool grow(builder *b, void **array, size_t count, size_t *cap, size_t size, const char *what)
{
    if (count < *cap) return true;
    size_t want = *cap ? *cap * 2 : 64;
    void *grown = rtp_mem_realloc(*array, want * size, what);
    if (!grown) return out_of_memory(b);
    *array = grown;
    *cap = want;
    return true;
}

static bool grow32(builder *b, void **array, uint32_t count, uint32_t *cap, size_t size, const char *what)
{
    size_t c = *cap;
    if (count == UINT32_MAX) return snprintf(b->err, b->err_size, "%s: too many YAML nodes", b->file), false;
    if (!grow(b, array, count, &c, size, what)) return false;
    *cap = c > UINT32_MAX ? UINT32_MAX : (uint32_t)c;
    return true;
}

/* A new node, pushed as a child of the innermost open collection. */
static rtp_yaml_node *add_node(builder *b, rtp_yaml_kind kind, yaml_mark_t at)
{
    rtp_yaml_tree *t = b->t;
    if (!grow32(b, (void **)&t->nodes, t->node_count, &b->node_cap, sizeof *t->nodes, "the YAML tree") ||
        !grow32(b, (void **)&b->pending, b->pending_count, &b->pending_cap, sizeof *b->pending, "the YAML tree"))
        return NULL;
    b->pending[b->pending_count++] = t->node_count;
    rtp_yaml_node *n = &t->nodes[t->node_count++];
    *n = (rtp_yaml_node){.line = (uint32_t)at.line + 1, .column = (uint32_t)at.column + 1, .kind = (uint8_t)kind};
    return n;
}

/* Scalars keep the offset of their text until the pool stops moving. */
static const char *scalar_text(const builder *b, const rtp_yaml_node *n) { return b->t->text + (uintptr_t)n->text; }

static bool add_scalar(builder *b, const yaml_event_t *e)
{
    const char *value = (const char *)e->data.scalar.value, *tag = (const char *)e->data.scalar.tag;
    size_t length = e->data.scalar.length;
    rtp_yaml_node *n = add_node(b, RTP_YAML_SCALAR, e->start_mark);
    if (!n) return false;
    if (tag)
        n->is_null = !strcmp(tag, YAML_NULL_TAG);
    else if (e->data.scalar.style == YAML_PLAIN_SCALAR_STYLE)
        n->is_null = !*value || !strcmp(value, "~") || !strcmp(value, "null") || !strcmp(value, "Null") ||
                     !strcmp(value, "NULL");
    n->text = (const char *)(uintptr_t)b->text_len;
    while (b->text_len + length + 1 > b->text_cap) {
        size_t cap = b->text_cap;
        if (!grow(b, (void **)&b->t->text, b->text_cap, &cap, 1, "the YAML tree")) return false;
        b->text_cap = cap;
    }
    memcpy(b->t->text + b->text_len, value, length);
    b->t->text[b->text_len + length] = '\0';
    b->text_len += length + 1;
    return true;
}

static bool open_collection_at(builder *b, rtp_yaml_kind kind, bool flow, yaml_mark_t at)
{
    bool in_flow = flow || (b->depth > 0 && b->open[b->depth - 1].flow);
    if (b->depth >= RTP_YAML_MAX_DEPTH)
        return fail_at(b, at, "invalid YAML: nested more than %d levels deep", RTP_YAML_MAX_DEPTH);
    uint32_t self_at = b->pending_count;
    if (!add_node(b, kind, at) ||
        !grow32(b, (void **)&b->open, b->depth, &b->open_cap, sizeof *b->open, "the YAML tree"))
        return false;
    b->open[b->depth++] = (open_collection){b->t->node_count - 1, self_at, b->pending_count, in_flow};
    b->flow_depth += in_flow;
    return true;
}

/* "Root/Children[2]/Components" for the collections open below level depth. */
static void key_path(const builder *b, uint32_t depth, char *out, size_t size)
{
    size_t len = 0;
    out[0] = '\0';
    for (uint32_t i = 0; i + 1 < depth && len < size; i++) {
        uint32_t at = b->open[i + 1].self_at;
        const rtp_yaml_node *parent = &b->t->nodes[b->open[i].node];
        int n;
        if (parent->kind == RTP_YAML_SEQ) {
            n = snprintf(out + len, size - len, "[%u]", at - b->open[i].pending_at);
        } else {
            const rtp_yaml_node *key = &b->t->nodes[b->pending[at - 1]];
            n = snprintf(out + len, size - len, "%s%s", len ? "/" : "",
                         key->kind == RTP_YAML_SCALAR ? scalar_text(b, key) : "?");
        }
        if (n > 0) len += (size_t)n;
    }
}

static uint64_t hash_text(const char *s)
{
    uint64_t h = 14695981039346656037ull;
    for (; *s; s++) h = (h ^ (uint8_t)*s) * 1099511628211ull;
    return h;
}

static bool duplicate_key(builder *b, const rtp_yaml_node *first, const rtp_yaml_node *again)
{
    char path[PATH_SIZE];
    key_path(b, b->depth, path, sizeof path);
    yaml_mark_t at = {.line = again->line - 1, .column = again->column - 1};
    return fail_at(b, at, "%s%s%s: duplicate key, first at line %u, column %u", path, *path ? "/" : "",
                   scalar_text(b, again), first->line, first->column);
}

/* Refuses a map whose scalar keys repeat (pairs are pending[from], pending[from + 1]...):
 * an open-addressing table of twice the pairs, cleared per map, so this is linear. */
static bool check_keys(builder *b, uint32_t from, uint32_t pairs)
{
    size_t slots = 4;
    while (slots < (size_t)pairs * 2) slots <<= 1;
    if (slots > b->slot_cap) {
        uint32_t *grown = rtp_mem_realloc(b->slots, slots * sizeof *grown, "the YAML tree");
        if (!grown) return out_of_memory(b);
        b->slots = grown;
        b->slot_cap = slots;
    }
    memset(b->slots, 0, slots * sizeof *b->slots); /* entries: pair + 1, 0 = free */
    for (uint32_t p = 0; p < pairs; p++) {
        const rtp_yaml_node *key = &b->t->nodes[b->pending[from + 2 * p]];
        if (key->kind != RTP_YAML_SCALAR) continue;
        const char *text = scalar_text(b, key);
        size_t s = (size_t)hash_text(text) & (slots - 1);
        for (; b->slots[s]; s = (s + 1) & (slots - 1)) {
            const rtp_yaml_node *other = &b->t->nodes[b->pending[from + 2 * (b->slots[s] - 1)]];
            if (!strcmp(scalar_text(b, other), text)) return duplicate_key(b, other, key);
        }
        b->slots[s] = p + 1;
    }
    return true;
}

static bool close_collection(builder *b)
{
    open_collection *c = &b->open[b->depth - 1];
    rtp_yaml_tree *t = b->t;
    uint32_t count = b->pending_count - c->pending_at;
    rtp_yaml_node *n = &t->nodes[c->node];
    if (n->kind == RTP_YAML_MAP && !check_keys(b, c->pending_at, count / 2)) return false;
    size_t cap = b->child_cap;
    while (b->child_count + (size_t)count > cap)
        if (!grow(b, (void **)&t->children, cap, &cap, sizeof *t->children, "the YAML tree")) return false;
    b->child_cap = cap > UINT32_MAX ? UINT32_MAX : (uint32_t)cap;
    if (count) memcpy(t->children + b->child_count, b->pending + c->pending_at, count * sizeof *t->children);
    n = &t->nodes[c->node];
    n->first = b->child_count;
    n->count = n->kind == RTP_YAML_MAP ? count / 2 : count;
    b->child_count += count;
    b->pending_count = c->pending_at;
    b->flow_depth -= c->flow;
    b->depth--;
    return true;
}

static bool parse_error(builder *b, const yaml_parser_t *p)
{
    if (p->error == YAML_MEMORY_ERROR)
        snprintf(b->err, b->err_size, "%s: out of memory in the YAML parser", b->file);
    else if (p->error == YAML_READER_ERROR)
        snprintf(b->err, b->err_size, "%s: byte %zu: invalid YAML: %s", b->file, p->problem_offset,
                 p->problem ? p->problem : "unreadable input");
    else
        fail_at(b, p->problem_mark, "invalid YAML: %s%s%s", p->problem ? p->problem : "syntax error",
                p->context ? " " : "", p->context ? p->context : "");
    return false;
}

/* Feeds one event to the tree; *done once the first document (or the stream) ends. */
static bool take_event(builder *b, const yaml_event_t *e, bool *done)
{
    b->flow_work += b->flow_depth;
    if (b->flow_work > b->flow_budget)
        return fail_at(b, e->start_mark,
                       "invalid YAML: flow collections ([ ] and { }) nested too deeply for the file's size "
                       "(parsing would take time in proportion to depth times size); use block style");
    switch (e->type) {
    case YAML_SCALAR_EVENT: return add_scalar(b, e);
    case YAML_SEQUENCE_START_EVENT:
        return open_collection_at(b, RTP_YAML_SEQ, e->data.sequence_start.style == YAML_FLOW_SEQUENCE_STYLE,
                                  e->start_mark);
    case YAML_MAPPING_START_EVENT:
        return open_collection_at(b, RTP_YAML_MAP, e->data.mapping_start.style == YAML_FLOW_MAPPING_STYLE,
                                  e->start_mark);
    case YAML_SEQUENCE_END_EVENT:
    case YAML_MAPPING_END_EVENT: return close_collection(b);
    case YAML_ALIAS_EVENT: return fail_at(b, e->start_mark, "this alias reuses a node; aliases are not supported");
    case YAML_DOCUMENT_END_EVENT:
    case YAML_STREAM_END_EVENT: *done = true; return true;
    default: return true;
    }
}

bool rtp_yaml_tree_parse(const uint8_t *data, size_t size, const char *file, rtp_yaml_tree *out, char *err,
                         size_t err_size)
{
    memset(out, 0, sizeof *out);
    builder b = {.file = file, .err = err, .err_size = err_size, .t = out};
    b.flow_budget = (uint64_t)RTP_YAML_FLOW_WORK_PER_BYTE * size + RTP_YAML_FLOW_WORK_FREE;
    size_t held = size <= SIZE_MAX / 2 ? 2 * size : SIZE_MAX;
    if (!rtp_mem_hold(held, "the YAML parser's buffers (twice the file)")) return out_of_memory(&b);
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) {
        rtp_mem_unhold(held);
        return snprintf(err, err_size, "%s: out of memory", file), false;
    }
    yaml_parser_set_input_string(&parser, data, size);
    bool ok = true, done = false;
    while (ok && !done) {
        yaml_event_t event;
        if (!yaml_parser_parse(&parser, &event)) {
            ok = parse_error(&b, &parser);
            break;
        }
        ok = take_event(&b, &event, &done);
        yaml_event_delete(&event);
    }
    yaml_parser_delete(&parser);
    rtp_mem_unhold(held);
    rtp_mem_free(b.pending);
    rtp_mem_free(b.open);
    rtp_mem_free(b.slots);
    if (!ok) {
        rtp_yaml_tree_free(out);
        return false;
    }
    for (uint32_t i = 0; i < out->node_count; i++)
        if (out->nodes[i].kind == RTP_YAML_SCALAR) out->nodes[i].text = scalar_text(&b, &out->nodes[i]);
    return true;
}

void rtp_yaml_tree_free(rtp_yaml_tree *t)
{
    rtp_mem_free(t->nodes);
    rtp_mem_free(t->children);
    rtp_mem_free(t->text);
    memset(t, 0, sizeof *t);
}

/* PLY reader: file loading, header parsing, and the final mesh clean-up. The
 * element data itself is read by ply_body.c. */
#include "load/ply_reader.h"
#include "load/ply_weld.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Refused before reading: no mesh the tracer can hold comes close. */
#define PLY_MAX_FILE (1u << 30)
#define PLY_MAX_WORDS 8

bool ply_fail(ply_reader *r, const char *fmt, ...)
{
    if (r->err_size == 0) return false;
    int n = r->binary_body ? snprintf(r->err, r->err_size, "%s: byte %zu: ", r->path, r->pos)
                           : snprintf(r->err, r->err_size, "%s: line %lu: ", r->path, r->line);
    if (n >= 0 && (size_t)n < r->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(r->err + n, r->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

static bool fail_file(const char *path, char *err, size_t err_size, const char *why)
{
    if (err_size > 0) snprintf(err, err_size, "%s: %s", path, why);
    return false;
}

static bool read_whole_file(const char *path, uint8_t **data, size_t *size, char *err, size_t err_size)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        char why[160];
        snprintf(why, sizeof why, "cannot open: %s", strerror(errno));
        return fail_file(path, err, err_size, why);
    }
    struct stat st;
    const char *why = NULL;
    if (fstat(fd, &st) != 0)
        why = "cannot read the file's size";
    else if (S_ISDIR(st.st_mode))
        why = "is a directory";
    else if (!S_ISREG(st.st_mode))
        why = "not a regular file";
    else if (st.st_size > (off_t)PLY_MAX_FILE)
        why = "file too large for a mesh (over 1 GiB)";
    /* One spare byte so an empty file still gets a buffer. */
    uint8_t *buf = why ? NULL : malloc((size_t)st.st_size + 1);
    if (!why && !buf) why = "out of memory";
    size_t got = 0;
    while (!why && got < (size_t)st.st_size) {
        ssize_t n = read(fd, buf + got, (size_t)st.st_size - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            why = n < 0 ? strerror(errno) : "file shrank while reading";
        else
            got += (size_t)n;
    }
    close(fd);
    if (why) {
        free(buf);
        return fail_file(path, err, err_size, why);
    }
    *data = buf;
    *size = got;
    return true;
}

/* ---- header ---- */

typedef struct {
    const char *s;
    size_t n;
} ply_word;

static bool word_is(ply_word w, const char *s) { return strlen(s) == w.n && memcmp(w.s, s, w.n) == 0; }

/* Splits the line at r->pos into words and moves past its end; false at end of file. */
static bool next_header_line(ply_reader *r, ply_word *words, int *count)
{
    if (r->pos >= r->size) return false;
    const uint8_t *p = r->data + r->pos, *end = r->data + r->size;
    const uint8_t *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    *count = 0;
    while (p < eol) {
        while (p < eol && (*p == ' ' || *p == '\t' || *p == '\r')) p++;
        const uint8_t *start = p;
        while (p < eol && *p != ' ' && *p != '\t' && *p != '\r') p++;
        if (p > start && *count < PLY_MAX_WORDS)
            words[(*count)++] = (ply_word){(const char *)start, (size_t)(p - start)};
        else if (p > start)
            (*count)++;
    }
    r->pos = eol < end ? (size_t)(eol - r->data) + 1 : r->size;
    return true;
}

static bool parse_type(ply_word w, ply_type *t)
{
    static const char *const names[][2] = {
        {"char", "int8"}, {"uchar", "uint8"}, {"short", "int16"},   {"ushort", "uint16"},
        {"int", "int32"}, {"uint", "uint32"}, {"float", "float32"}, {"double", "float64"},
    };
    for (int i = 0; i < 8; i++)
        if (word_is(w, names[i][0]) || word_is(w, names[i][1])) {
            *t = (ply_type)i;
            return true;
        }
    return false;
}

/* A printable copy of w for messages and element names. */
static void printable(ply_word w, char *out, size_t size)
{
    size_t n = w.n < size - 1 ? w.n : size - 1;
    for (size_t i = 0; i < n; i++) out[i] = w.s[i] >= 0x20 && w.s[i] < 0x7f ? w.s[i] : '?';
    out[n] = 0;
}

static ply_role vertex_role(ply_word w)
{
    static const struct {
        const char *name;
        ply_role role;
    } roles[] = {
        {"x", PLY_X},         {"y", PLY_Y},         {"z", PLY_Z},  {"nx", PLY_NX}, {"ny", PLY_NY},
        {"nz", PLY_NZ},       {"u", PLY_U},         {"v", PLY_V},  {"s", PLY_U},   {"t", PLY_V},
        {"texture_u", PLY_U}, {"texture_v", PLY_V}, {"tx", PLY_U}, {"ty", PLY_V},
    };
    for (size_t i = 0; i < sizeof roles / sizeof roles[0]; i++)
        if (word_is(w, roles[i].name)) return roles[i].role;
    return PLY_SKIP;
}

static bool parse_element(ply_reader *r, const ply_word *w, int n)
{
    if (n != 3) return ply_fail(r, "expected 'element <name> <count>'");
    if (r->element_count == PLY_MAX_ELEMENTS) return ply_fail(r, "more than %d elements", PLY_MAX_ELEMENTS);
    uint64_t count = 0;
    for (size_t i = 0; i < w[2].n; i++) {
        unsigned d = (unsigned)(w[2].s[i] - '0');
        if (d > 9) return ply_fail(r, "element count is not a non-negative integer");
        if (count > (UINT64_MAX - d) / 10) return ply_fail(r, "element count too large");
        count = count * 10 + d;
    }
    ply_element *e = &r->elements[r->element_count];
    printable(w[1], e->name, sizeof e->name);
    for (uint32_t i = 0; i < r->element_count; i++)
        if (strcmp(r->elements[i].name, e->name) == 0) return ply_fail(r, "element %s declared twice", e->name);
    e->count = count;
    e->line = r->line;
    e->property_count = 0;
    r->element_count++;
    return true;
}

static bool parse_property(ply_reader *r, const ply_word *w, int n)
{
    if (r->element_count == 0) return ply_fail(r, "property before any element");
    ply_element *e = &r->elements[r->element_count - 1];
    if (e->property_count == PLY_MAX_PROPERTIES)
        return ply_fail(r, "element %s has more than %d properties", e->name, PLY_MAX_PROPERTIES);
    ply_property p = {.role = PLY_SKIP};
    ply_word name;
    if (n >= 2 && word_is(w[1], "list")) {
        if (n != 5) return ply_fail(r, "expected 'property list <count type> <index type> <name>'");
        if (!parse_type(w[2], &p.count_type) || !parse_type(w[3], &p.type)) return ply_fail(r, "unknown property type");
        if (p.count_type >= PLY_FLOAT32) return ply_fail(r, "list count type must be an integer type");
        p.is_list = true;
        name = w[4];
    } else {
        if (n != 3) return ply_fail(r, "expected 'property <type> <name>'");
        if (!parse_type(w[1], &p.type)) return ply_fail(r, "unknown property type");
        name = w[2];
    }
    if (strcmp(e->name, "vertex") == 0) p.role = vertex_role(name);
    if (strcmp(e->name, "face") == 0 && (word_is(name, "vertex_indices") || word_is(name, "vertex_index")))
        p.role = PLY_INDICES;
    if (p.role != PLY_SKIP) {
        char shown[PLY_NAME_SIZE];
        printable(name, shown, sizeof shown);
        if (r->has[p.role]) return ply_fail(r, "second property for %s", shown);
        if (p.is_list != (p.role == PLY_INDICES))
            return ply_fail(r, "property %s must be %s", shown, p.is_list ? "a scalar" : "a list");
        if (p.role == PLY_INDICES && p.type >= PLY_FLOAT32) return ply_fail(r, "vertex indices must be integers");
        r->has[p.role] = true;
    }
    e->properties[e->property_count++] = p;
    return true;
}

static bool parse_format(ply_reader *r, const ply_word *w, int n, bool *seen)
{
    if (*seen) return ply_fail(r, "second format line");
    if (n != 3 || !word_is(w[2], "1.0"))
        return ply_fail(r, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
    if (word_is(w[1], "ascii"))
        r->format = PLY_ASCII;
    else if (word_is(w[1], "binary_little_endian"))
        r->format = PLY_LITTLE_ENDIAN;
    else if (word_is(w[1], "binary_big_endian"))
        r->format = PLY_BIG_ENDIAN;
    else
        return ply_fail(r, "unknown format (expected ascii, binary_little_endian or binary_big_endian)");
    *seen = true;
    return true;
}

/* The smallest number of bytes one entry of e can occupy in the body. */
static uint64_t min_entry_bytes(const ply_reader *r, const ply_element *e)
{
    static const uint8_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    uint64_t bytes = 0;
    for (uint32_t i = 0; i < e->property_count; i++) {
        const ply_property *p = &e->properties[i];
        /* An ASCII value is at least one character; a binary list at least its count. */
        bytes += r->format == PLY_ASCII ? 1 : sizes[p->is_list ? p->count_type : p->type];
    }
    return bytes;
}

/* Counts that cannot fit in the rest of the file are refused before anything is allocated. */
static bool check_counts(ply_reader *r)
{
    uint64_t room = r->size - r->pos;
    for (uint32_t i = 0; i < r->element_count; i++) {
        const ply_element *e = &r->elements[i];
        uint64_t min = min_entry_bytes(r, e);
        if (min > 0 && e->count > room / min) {
            r->line = e->line;
            return ply_fail(r, "element %s declares %llu entries but the file has room for at most %llu", e->name,
                            (unsigned long long)e->count, (unsigned long long)(room / min));
        }
        room -= min * e->count;
    }
    return true;
}

static const ply_element *find_element(const ply_reader *r, const char *name)
{
    for (uint32_t i = 0; i < r->element_count; i++)
        if (strcmp(r->elements[i].name, name) == 0) return &r->elements[i];
    return NULL;
}

static bool parse_header(ply_reader *r)
{
    ply_word w[PLY_MAX_WORDS];
    int n;
    r->line = 1;
    if (!next_header_line(r, w, &n) || n != 1 || !word_is(w[0], "ply"))
        return ply_fail(r, "not a PLY file (the first line must be 'ply')");
    bool have_format = false;
    for (;;) {
        r->line++;
        if (!next_header_line(r, w, &n)) return ply_fail(r, "end of file before end_header");
        if (n == 0) continue;
        bool ok = true;
        if (word_is(w[0], "end_header")) break;
        if (word_is(w[0], "format"))
            ok = parse_format(r, w, n, &have_format);
        else if (!have_format && (word_is(w[0], "element") || word_is(w[0], "property")))
            ok = ply_fail(r, "%.*s before the format line", (int)w[0].n, w[0].s);
        else if (word_is(w[0], "element"))
            ok = parse_element(r, w, n);
        else if (word_is(w[0], "property"))
            ok = parse_property(r, w, n);
        /* comment, obj_info and unknown lines (some exporters write bare text) are skipped. */
        if (!ok) return false;
    }
    if (!have_format) return ply_fail(r, "end_header before the format line");
    const ply_element *vertex = find_element(r, "vertex");
    if (!vertex) return ply_fail(r, "no element vertex");
    for (ply_role role = PLY_X; role <= PLY_Z; role++)
        if (!r->has[role]) {
            r->line = vertex->line;
            return ply_fail(r, "element vertex has no property %c", "xyz"[role - PLY_X]);
        }
    if (!r->has[PLY_INDICES]) return ply_fail(r, "no element face with a vertex_indices list");
    if (vertex->count >= UINT32_MAX) {
        r->line = vertex->line;
        return ply_fail(r, "too many vertices");
    }
    r->line++; /* the body starts on the line after end_header */
    return check_counts(r);
}

/* ---- the mesh ---- */

static bool allocate_mesh(ply_reader *r)
{
    rtp_ply_mesh *m = r->mesh;
    const ply_element *vertex = find_element(r, "vertex"), *face = find_element(r, "face");
    m->vertex_count = (uint32_t)vertex->count;
    size_t v = m->vertex_count ? m->vertex_count : 1;
    r->triangle_capacity = face->count ? (size_t)face->count : 1;
    m->positions = malloc(v * sizeof *m->positions);
    bool normals = r->has[PLY_NX] && r->has[PLY_NY] && r->has[PLY_NZ];
    bool uvs = r->has[PLY_U] && r->has[PLY_V];
    /* A partial normal or uv set (nx without nz, u without v) is ignored. */
    r->has[PLY_NX] = r->has[PLY_NY] = r->has[PLY_NZ] = normals;
    r->has[PLY_U] = r->has[PLY_V] = uvs;
    if (normals) m->normals = malloc(v * sizeof *m->normals);
    if (uvs) m->uvs = malloc(v * sizeof *m->uvs);
    m->indices = malloc(r->triangle_capacity * 3 * sizeof *m->indices);
    if (!m->positions || (normals && !m->normals) || (uvs && !m->uvs) || !m->indices)
        return ply_fail(r, "out of memory for %u vertices", m->vertex_count);
    return true;
}

/* Drops triangles with a repeated index or a zero cross product (object space). */
static void drop_degenerate(rtp_ply_mesh *m)
{
    uint32_t kept = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *i = &m->indices[3 * t];
        if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2]) continue;
        rt_vec3 a = m->positions[i[0]], b = m->positions[i[1]], c = m->positions[i[2]];
        if (rt_v3_is_zero(rt_v3_cross(rt_v3_sub(b, a), rt_v3_sub(c, a)))) continue;
        memmove(&m->indices[3 * kept], i, 3 * sizeof *i);
        kept++;
    }
    m->triangle_count = kept;
}

bool rtp_ply_read(const char *path, rtp_ply_mesh *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (err_size > 0) err[0] = 0;
    uint8_t *data;
    size_t size;
    if (!read_whole_file(path, &data, &size, err, err_size)) return false;
    ply_reader r = {.path = path, .err = err, .err_size = err_size, .data = data, .size = size, .mesh = out};
    bool ok = parse_header(&r) && allocate_mesh(&r) && ply_read_body(&r);
    free(data);
    if (ok && !rtp_ply_weld(out)) ok = fail_file(path, err, err_size, "out of memory joining identical vertices");
    if (!ok) {
        rtp_ply_free(out);
        return false;
    }
    drop_degenerate(out);
    return true;
}

void rtp_ply_free(rtp_ply_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->uvs);
    free(mesh->indices);
    memset(mesh, 0, sizeof *mesh);
}

rt_mesh_desc rtp_ply_view(const rtp_ply_mesh *mesh)
{
    rt_mesh_desc d = {
        .positions = mesh->positions,
        .normals = mesh->normals,
        .uvs = mesh->uvs,
        .vertex_count = mesh->vertex_count,
        .indices = mesh->indices,
        .triangle_count = mesh->triangle_count,
    };
    return d;
}

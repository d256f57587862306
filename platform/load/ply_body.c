/* PLY reader: the body. Values are read one at a time, as text (one element per
 * line) or as little/big-endian binary, and fed to the mesh by their role. */
#include "load/ply_reader.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const uint8_t type_size[] = {1, 1, 2, 2, 4, 4, 4, 8};
static const char *const type_name[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
static const int64_t int_min[] = {INT8_MIN, 0, INT16_MIN, 0, INT32_MIN, 0};
static const int64_t int_max[] = {INT8_MAX, UINT8_MAX, INT16_MAX, UINT16_MAX, INT32_MAX, UINT32_MAX};

static bool fail_place(ply_reader *r, const char *what)
{
    return ply_fail(r, "%s %llu of %llu: %s", r->element->name, (unsigned long long)r->index,
                    (unsigned long long)r->element->count, what);
}

/* For a value that was read but is unusable: binary errors point at its first byte. */
static bool fail_value(ply_reader *r, const char *what)
{
    r->pos = r->value_at;
    return fail_place(r, what);
}

/* ---- ASCII: one element per line, values separated by blanks ---- */

static bool is_blank(uint8_t c) { return c == ' ' || c == '\t' || c == '\r'; }

/* Skips blank lines before an element; false at end of file. */
static bool ascii_begin(ply_reader *r)
{
    for (;;) {
        while (r->pos < r->size && is_blank(r->data[r->pos])) r->pos++;
        if (r->pos >= r->size) return false;
        if (r->data[r->pos] != '\n') return true;
        r->pos++;
        r->line++;
    }
}

static bool ascii_end(ply_reader *r)
{
    while (r->pos < r->size && is_blank(r->data[r->pos])) r->pos++;
    if (r->pos < r->size && r->data[r->pos] != '\n') return fail_place(r, "more values than the header declares");
    if (r->pos < r->size) {
        r->pos++;
        r->line++;
    }
    return true;
}

static bool ascii_value(ply_reader *r, ply_type t, double *out)
{
    while (r->pos < r->size && is_blank(r->data[r->pos])) r->pos++;
    size_t start = r->pos;
    while (r->pos < r->size && !is_blank(r->data[r->pos]) && r->data[r->pos] != '\n') r->pos++;
    size_t n = r->pos - start;
    if (n == 0) return fail_place(r, "fewer values than the header declares");
    char token[64];
    if (n >= sizeof token) return fail_place(r, "value too long to be a number");
    memcpy(token, r->data + start, n);
    token[n] = 0;
    char *end;
    errno = 0;
    if (t >= PLY_FLOAT32) {
        double d = strtod(token, &end);
        /* Rounded to float as a binary file would store it; beyond FLT_MAX is infinite. */
        if (t == PLY_FLOAT32) d = d > FLT_MAX ? (double)INFINITY : d < -FLT_MAX ? -(double)INFINITY : (double)(float)d;
        *out = d;
    } else {
        long long i = strtoll(token, &end, 10);
        if (*end == 0 && (errno == ERANGE || i < int_min[t] || i > int_max[t])) {
            for (char *c = token; *c; c++) *c = *c >= 0x20 && *c < 0x7f ? *c : '?';
            char what[128];
            snprintf(what, sizeof what, "%s out of range for %s", token, type_name[t]);
            return fail_place(r, what);
        }
        *out = (double)i;
    }
    if (end == token || *end != 0) {
        for (char *c = token; *c; c++) *c = *c >= 0x20 && *c < 0x7f ? *c : '?';
        char what[128];
        snprintf(what, sizeof what, "'%s' is not %s", token, t >= PLY_FLOAT32 ? "a number" : "an integer");
        return fail_place(r, what);
    }
    return true;
}

/* ---- binary ---- */

static bool binary_value(ply_reader *r, ply_type t, double *out)
{
    size_t n = type_size[t];
    if (r->size - r->pos < n) return fail_place(r, "unexpected end of file");
    const uint8_t *p = r->data + r->pos;
    uint64_t bits = 0;
    for (size_t i = 0; i < n; i++) {
        size_t b = r->format == PLY_LITTLE_ENDIAN ? n - 1 - i : i;
        bits = bits << 8 | p[b];
    }
    r->pos += n;
    switch (t) {
    case PLY_INT8: *out = (int8_t)bits; break;
    case PLY_INT16: *out = (int16_t)bits; break;
    case PLY_INT32: *out = (int32_t)bits; break;
    case PLY_UINT8:
    case PLY_UINT16:
    case PLY_UINT32: *out = (double)bits; break;
    case PLY_FLOAT32: {
        uint32_t b32 = (uint32_t)bits;
        float f;
        memcpy(&f, &b32, sizeof f);
        *out = f;
        break;
    }
    case PLY_FLOAT64: memcpy(out, &bits, sizeof *out); break;
    }
    return true;
}

static bool read_value(ply_reader *r, ply_type t, double *out)
{
    r->value_at = r->pos;
    return r->format == PLY_ASCII ? ascii_value(r, t, out) : binary_value(r, t, out);
}

/* ---- roles ---- */

static bool add_triangle(ply_reader *r, uint32_t a, uint32_t b, uint32_t c)
{
    rtp_ply_mesh *m = r->mesh;
    if (m->triangle_count == r->triangle_capacity) {
        /* Indices are uint32 downstream: 3 * count must fit. */
        if (r->triangle_capacity >= UINT32_MAX / 3) return fail_place(r, "too many triangles");
        size_t cap = r->triangle_capacity * 2 < UINT32_MAX / 3 ? r->triangle_capacity * 2 : UINT32_MAX / 3;
        uint32_t *grown = realloc(m->indices, cap * 3 * sizeof *grown);
        if (!grown) return fail_place(r, "out of memory for triangles");
        m->indices = grown;
        r->triangle_capacity = cap;
    }
    uint32_t *t = &m->indices[3 * (size_t)m->triangle_count++];
    t[0] = a;
    t[1] = b;
    t[2] = c;
    return true;
}

/* A polygon's indices, fan-triangulated as they arrive: (i0, i(k-1), ik). */
static bool read_polygon(ply_reader *r, const ply_property *p, uint64_t count)
{
    uint32_t first = 0, prev = 0;
    for (uint64_t k = 0; k < count; k++) {
        double d;
        if (!read_value(r, p->type, &d)) return false;
        if (d < 0 || d >= r->mesh->vertex_count) {
            char what[96];
            snprintf(what, sizeof what, "vertex index %.0f out of range (%u vertices)", d, r->mesh->vertex_count);
            return fail_value(r, what);
        }
        uint32_t i = (uint32_t)d;
        if (k >= 2 && !add_triangle(r, first, prev, i)) return false;
        if (k == 0) first = i;
        prev = i;
    }
    return true;
}

static bool skip_list(ply_reader *r, const ply_property *p, uint64_t count)
{
    if (r->format != PLY_ASCII) {
        if (count > (r->size - r->pos) / type_size[p->type]) return fail_place(r, "unexpected end of file");
        r->pos += count * type_size[p->type];
        return true;
    }
    double d;
    for (uint64_t k = 0; k < count; k++)
        if (!read_value(r, p->type, &d)) return false;
    return true;
}

static bool store_scalar(ply_reader *r, ply_role role, double d)
{
    if (role == PLY_SKIP || !r->has[role]) return true;
    static const char *const names[] = {"", "x", "y", "z", "nx", "ny", "nz", "u", "v"};
    if (!(d - d == 0)) {
        char what[64];
        snprintf(what, sizeof what, "%s is not a finite number", names[role]);
        return fail_value(r, what);
    }
    rtp_ply_mesh *m = r->mesh;
    uint32_t v = (uint32_t)r->index;
    rt_real x = rt_from_double(d);
    switch (role) {
    case PLY_X: m->positions[v].x = x; break;
    case PLY_Y: m->positions[v].y = x; break;
    case PLY_Z: m->positions[v].z = x; break;
    case PLY_NX: m->normals[v].x = x; break;
    case PLY_NY: m->normals[v].y = x; break;
    case PLY_NZ: m->normals[v].z = x; break;
    case PLY_U: m->uvs[v].u = x; break;
    case PLY_V: m->uvs[v].v = x; break;
    default: break;
    }
    return true;
}

static bool read_entry(ply_reader *r, const ply_element *e)
{
    if (r->format == PLY_ASCII && !ascii_begin(r)) return fail_place(r, "unexpected end of file");
    for (uint32_t i = 0; i < e->property_count; i++) {
        const ply_property *p = &e->properties[i];
        double d;
        if (!read_value(r, p->is_list ? p->count_type : p->type, &d)) return false;
        if (p->is_list && d < 0) return fail_value(r, "negative list count");
        bool ok = !p->is_list              ? store_scalar(r, p->role, d)
                  : p->role == PLY_INDICES ? read_polygon(r, p, (uint64_t)d)
                                           : skip_list(r, p, (uint64_t)d);
        if (!ok) return false;
    }
    return r->format != PLY_ASCII || ascii_end(r);
}

bool ply_read_body(ply_reader *r)
{
    r->binary_body = r->format != PLY_ASCII;
    for (uint32_t i = 0; i < r->element_count; i++) {
        const ply_element *e = &r->elements[i];
        r->element = e;
        /* An element without properties occupies no bytes, whatever its count. */
        if (e->property_count == 0) continue;
        for (r->index = 0; r->index < e->count; r->index++)
            if (!read_entry(r, e)) return false;
    }
    if (r->format == PLY_ASCII) {
        while (r->pos < r->size && (is_blank(r->data[r->pos]) || r->data[r->pos] == '\n'))
            if (r->data[r->pos++] == '\n') r->line++;
        if (r->pos < r->size) return ply_fail(r, "data after the last element (do the header's counts lie?)");
    } else if (r->pos < r->size) {
        return ply_fail(r, "%zu bytes after the last element (do the header's counts lie?)", r->size - r->pos);
    }
    return true;
}

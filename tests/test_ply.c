/* PLY reader: the corpus meshes, the three encodings of one mesh, header variants,
 * fan triangulation, degenerate triangles, and a catalogue of hostile files. */
#include "load/ply.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Tests run from the repository root (make check), which sits next to ../shared. */
#define TRACE "../shared/cse457/assets/trace/"

static char dir[64];

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "ply"), "cannot create a scratch folder"); }

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(ply, .init = setup, .fini = teardown);

static const char *in_dir(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", dir, name);
    return buf;
}

static const char *put_file(const char *name, const void *data, size_t size)
{
    static char path[128];
    in_dir(path, sizeof path, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot create %s", path);
    cr_assert_eq(fwrite(data, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
    return path;
}

static const char *put_text(const char *name, const char *text) { return put_file(name, text, strlen(text)); }

/* ---- a small writer for all three encodings ---- */

typedef struct {
    const char *type, *name;
} prop;

static int type_size(const char *t)
{
    static const char *const names[] = {"char", "uchar", "int8",  "uint8",  "short", "ushort",  "int16",  "uint16",
                                        "int",  "uint",  "int32", "uint32", "float", "float32", "double", "float64"};
    static const int sizes[] = {1, 1, 1, 1, 2, 2, 2, 2, 4, 4, 4, 4, 4, 4, 8, 8};
    for (int i = 0; i < 16; i++)
        if (strcmp(t, names[i]) == 0) return sizes[i];
    cr_assert_fail("unknown type %s", t);
    return 0;
}

static void put_value(FILE *f, const char *format, const char *type, double d)
{
    int n = type_size(type);
    bool is_float = type[0] == 'f' || type[0] == 'd';
    if (strcmp(format, "ascii") == 0) {
        if (is_float)
            fprintf(f, "%.17g ", n == 4 ? (double)(float)d : d);
        else
            fprintf(f, "%lld ", (long long)d);
        return;
    }
    uint64_t bits;
    if (is_float && n == 4) {
        float x = (float)d;
        uint32_t b;
        memcpy(&b, &x, 4);
        bits = b;
    } else if (is_float) {
        memcpy(&bits, &d, 8);
    } else {
        bits = (uint64_t)(int64_t)d;
    }
    bool big = strcmp(format, "binary_big_endian") == 0;
    for (int i = 0; i < n; i++) fputc((int)(bits >> 8 * (big ? n - 1 - i : i)) & 0xff, f);
}

/* faces: n, i0 .. i(n-1), repeated nf times. */
static const char *write_mesh(const char *name, const char *format, const prop *vp, int nvp, const double *values,
                              int nv, const char *count_type, const char *index_type, const int *faces, int nf)
{
    static char path[128];
    in_dir(path, sizeof path, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fprintf(f, "ply\nformat %s 1.0\ncomment made by test_ply\nelement vertex %d\n", format, nv);
    for (int i = 0; i < nvp; i++) fprintf(f, "property %s %s\n", vp[i].type, vp[i].name);
    fprintf(f, "element face %d\nproperty list %s %s vertex_indices\nend_header\n", nf, count_type, index_type);
    bool ascii = strcmp(format, "ascii") == 0;
    for (int v = 0; v < nv; v++) {
        for (int i = 0; i < nvp; i++) put_value(f, format, vp[i].type, values[v * nvp + i]);
        if (ascii) fputc('\n', f);
    }
    for (int k = 0, at = 0; k < nf; k++) {
        int n = faces[at++];
        put_value(f, format, count_type, n);
        for (int i = 0; i < n; i++) put_value(f, format, index_type, faces[at++]);
        if (ascii) fputc('\n', f);
    }
    cr_assert_eq(fclose(f), 0);
    return path;
}

static rtp_ply_mesh load(const char *path)
{
    rtp_ply_mesh m;
    char err[512];
    cr_assert(rtp_ply_read(path, &m, err, sizeof err), "%s", err);
    return m;
}

/* A house-shaped pentagon, a quad and a triangle over six vertices with normals and uvs. */
static const prop full_props[] = {{"float", "x"},  {"float", "y"},  {"float", "z"}, {"float", "nx"},
                                  {"float", "ny"}, {"float", "nz"}, {"float", "u"}, {"float", "v"}};
static const double full_values[] = {
    0,   0,   0, 0, 0, 1, 0,   0,   1, 0, 0, 0, 0, 1, 1, 0, 1,   1,    0,   0,   0,   1, 1,    1,
    0.5, 1.5, 0, 0, 0, 1, 0.5, 1.5, 0, 1, 0, 0, 0, 1, 0, 1, 0.1, -0.3, 2.7, 0.6, 0.8, 0, 0.25, 0.75,
};
static const int full_faces[] = {5, 0, 1, 2, 3, 4, 4, 0, 1, 5, 4, 3, 1, 2, 5};

/* ---- corpus ---- */

Test(ply, every_corpus_mesh_loads_with_its_counts)
{
    static const struct {
        const char *path;
        uint32_t vertices, triangles;
        bool normals, uvs;
    } corpus[] = {
        /* Vertex counts after joining bit-identical vertices (the file's count after the
         * "of"), triangle counts after dropping the zero-area triangles each file has. */
        {TRACE "simple/poly-sphere.ply", 121, 180, true, true},
        {TRACE "trimeshes/knight.ply", 603 /* of 618 */, 206, true, false},
        {TRACE "trimeshes/martini.ply", 6642, 12960 - 81, true, true},
        {TRACE "trimeshes/pawn.ply", 325 /* of 354 */, 118, true, false},
        {TRACE "trimeshes/revolution.ply", 1722, 3280 - 41, true, true},
        {TRACE "trimeshes/sculpt.ply", 5215 /* of 31059 */, 10353, false, false},
        {TRACE "trimeshes/table1.ply", 460 /* of 2640 */, 880 - 280, true, false},
        {TRACE "trimeshes/table2.ply", 800 /* of 4320 */, 1440 - 240, true, false},
    };
    for (size_t i = 0; i < sizeof corpus / sizeof corpus[0]; i++) {
        rtp_ply_mesh m = load(corpus[i].path);
        cr_expect_eq(m.vertex_count, corpus[i].vertices, "%s", corpus[i].path);
        cr_expect_eq(m.triangle_count, corpus[i].triangles, "%s", corpus[i].path);
        cr_expect_eq(m.normals != NULL, corpus[i].normals, "%s", corpus[i].path);
        cr_expect_eq(m.uvs != NULL, corpus[i].uvs, "%s", corpus[i].path);
        for (uint32_t t = 0; t < 3 * m.triangle_count; t++) cr_assert_lt(m.indices[t], m.vertex_count);
        rt_mesh_desc d = rtp_ply_view(&m);
        cr_expect_eq(d.positions, m.positions);
        cr_expect_eq(d.triangle_count, m.triangle_count);
        rtp_ply_free(&m);
        cr_expect_null(m.positions);
    }
}

Test(ply, ascii_floats_are_rounded_to_the_declared_float)
{
    /* poly-sphere.ply line 2 of the body: "1.28465e-08 0.5 1.76816e-08 ... 0.1 0". */
    rtp_ply_mesh m = load(TRACE "simple/poly-sphere.ply");
    cr_expect_eq(m.positions[1].x, (double)1.28465e-08f);
    cr_expect_eq(m.positions[1].y, 0.5);
    cr_expect_eq(m.normals[1].y, 1.0);
    cr_expect_eq(m.uvs[1].u, (double)0.1f);
    cr_expect_neq(m.uvs[1].u, 0.1);
    cr_expect_eq(m.indices[0], 1); /* first face: "3 1 11 12" */
    cr_expect_eq(m.indices[2], 12);
    rtp_ply_free(&m);
}

/* ---- encodings and header variants ---- */

Test(ply, ascii_little_and_big_endian_give_identical_arrays)
{
    static const char *const formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    rtp_ply_mesh m[3];
    for (int i = 0; i < 3; i++)
        m[i] = load(write_mesh(formats[i], formats[i], full_props, 8, full_values, 6, "uchar", "int", full_faces, 3));
    cr_assert_eq(m[0].vertex_count, 6);
    cr_assert_eq(m[0].triangle_count, 3 + 2 + 1);
    cr_assert_not_null(m[0].normals);
    cr_assert_not_null(m[0].uvs);
    for (int i = 1; i < 3; i++) {
        cr_assert_eq(m[i].vertex_count, m[0].vertex_count, "%s", formats[i]);
        cr_assert_eq(m[i].triangle_count, m[0].triangle_count, "%s", formats[i]);
        cr_expect_arr_eq(m[i].positions, m[0].positions, 6 * sizeof(rt_vec3), "%s", formats[i]);
        cr_expect_arr_eq(m[i].normals, m[0].normals, 6 * sizeof(rt_vec3), "%s", formats[i]);
        cr_expect_arr_eq(m[i].uvs, m[0].uvs, 6 * sizeof(rt_vec2), "%s", formats[i]);
        cr_expect_arr_eq(m[i].indices, m[0].indices, 18 * sizeof(uint32_t), "%s", formats[i]);
    }
    cr_expect_eq(m[0].positions[5].z, (double)2.7f);
    cr_expect_eq(m[2].uvs[3].v, 1.5);
    for (int i = 0; i < 3; i++) rtp_ply_free(&m[i]);
}

Test(ply, polygons_are_fan_triangulated)
{
    static const char text[] = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n3 3 1\n5 0 1 2 3 4\n4 0 1 5 4\n";
    rtp_ply_mesh m = load(put_text("fan.ply", text));
    static const uint32_t fan[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 1, 5, 0, 5, 4};
    cr_assert_eq(m.triangle_count, 5);
    cr_expect_arr_eq(m.indices, fan, sizeof fan);
    cr_expect_null(m.normals);
    cr_expect_null(m.uvs);
    rtp_ply_free(&m);
}

Test(ply, every_scalar_type_and_alias_in_both_byte_orders)
{
    static const prop props[] = {{"char", "x"},      {"int16", "y"},   {"double", "z"},   {"uint8", "red"},
                                 {"ushort", "junk"}, {"uint", "more"}, {"float64", "nx"}, {"float32", "ny"},
                                 {"int32", "nz"},    {"uint16", "s"},  {"int8", "t"},     {"short", "q"}};
    static const double values[] = {
        -128, -32768, 0.1, 255, 65535, 4294967295.0, 0.5, 0.25, -2, 65535, 127, 5, 127, 32767, -1e300, 0, 0,
        0,    0,      0,   7,   0,     -128,         0,   1,    2,  3,     1,   1, 1,   1,     1,      1, 1,
        1,    1};
    static const int faces[] = {3, 0, 1, 2};
    static const char *const formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    static const char *const index_types[] = {"ushort", "uint32", "int8"};
    for (int i = 0; i < 3; i++) {
        char name[32];
        snprintf(name, sizeof name, "types%d.ply", i);
        rtp_ply_mesh m = load(write_mesh(name, formats[i], props, 12, values, 3, "int", index_types[i], faces, 1));
        cr_expect_eq(m.positions[0].x, -128.0, "%s", formats[i]);
        cr_expect_eq(m.positions[0].y, -32768.0, "%s", formats[i]);
        cr_expect_eq(m.positions[0].z, 0.1, "%s", formats[i]);
        cr_expect_eq(m.positions[1].z, -1e300, "%s", formats[i]);
        cr_expect_eq(m.normals[0].x, 0.5);
        cr_expect_eq(m.normals[0].y, 0.25);
        cr_expect_eq(m.normals[0].z, -2.0);
        cr_expect_eq(m.normals[1].z, 7.0);
        cr_expect_eq(m.uvs[0].u, 65535.0, "%s", formats[i]);
        cr_expect_eq(m.uvs[0].v, 127.0, "%s", formats[i]);
        cr_expect_eq(m.uvs[1].v, -128.0, "%s", formats[i]);
        cr_expect_eq(m.triangle_count, 1);
        rtp_ply_free(&m);
    }
}

Test(ply, uv_aliases_and_partial_sets)
{
    static const char *const pairs[][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"tx", "ty"}};
    static const double values[] = {0, 0, 0, 0.25, 0.5, 1, 0, 0, 0.75, 1, 0, 1, 0, 1, 0};
    static const int faces[] = {3, 0, 1, 2};
    for (int i = 0; i < 4; i++) {
        prop p[] = {{"float", "x"}, {"float", "y"}, {"float", "z"}, {"float", pairs[i][0]}, {"float", pairs[i][1]}};
        rtp_ply_mesh m = load(write_mesh("uv.ply", "binary_little_endian", p, 5, values, 3, "uchar", "uint", faces, 1));
        cr_assert_not_null(m.uvs, "%s %s", pairs[i][0], pairs[i][1]);
        cr_expect_eq(m.uvs[0].u, 0.25);
        cr_expect_eq(m.uvs[1].v, 1.0);
        rtp_ply_free(&m);
    }
    /* u without v, nx without nz: ignored rather than half-filled. */
    prop p[] = {{"float", "x"}, {"float", "y"}, {"float", "z"}, {"float", "u"}, {"float", "nx"}};
    rtp_ply_mesh m = load(write_mesh("uv.ply", "ascii", p, 5, values, 3, "uchar", "uint", faces, 1));
    cr_expect_null(m.uvs);
    cr_expect_null(m.normals);
    rtp_ply_free(&m);
}

Test(ply, element_order_unknown_elements_lists_comments_and_crlf)
{
    static const char text[] =
        "ply\r\nformat ascii 1.0\r\ncomment faces first\r\nobj_info anything\r\n"
        "Created by some exporter without a comment keyword\r\n"
        "element face 2\r\nproperty uchar flags\r\nproperty list uint uint vertex_index\r\n"
        "property list uchar float texcoord\r\n"
        "element material 1\r\nproperty list int int weird\r\nproperty float shine\r\n"
        "element vertex 4\r\nproperty float z\r\nproperty list uchar uchar crumbs\r\nproperty float x\r\n"
        "property uchar red\r\nproperty float y\r\nend_header\r\n"
        "7 3 0 1 2 6 0 0 1 0 0 1\r\n\r\n"
        "0 3 2 1 3 0\r\n"
        "3 -1 -2 -3 0.5\r\n"
        "0 0 0 255 0\r\n1 2 9 9 1 0 0\r\n0 0 0 255 1\r\n  2   1   1 1 1 1 \t\r\n";
    rtp_ply_mesh m = load(put_text("order.ply", text));
    cr_assert_eq(m.vertex_count, 4);
    cr_assert_eq(m.triangle_count, 2);
    static const uint32_t tris[] = {0, 1, 2, 2, 1, 3};
    cr_expect_arr_eq(m.indices, tris, sizeof tris);
    cr_expect_eq(m.positions[1].x, 1.0);
    cr_expect_eq(m.positions[1].z, 1.0);
    cr_expect_eq(m.positions[2].y, 1.0);
    cr_expect_eq(m.positions[3].z, 2.0);
    cr_expect_eq(m.positions[3].x, 1.0);
    rtp_ply_free(&m);
}

Test(ply, degenerate_triangles_are_dropped)
{
    static const char text[] = "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\n"
                               "property double z\nelement face 5\nproperty list uchar int vertex_indices\n"
                               "end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n0 0 0\n"
                               "3 0 1 2\n3 0 0 2\n3 0 1 3\n3 0 4 1\n4 2 1 0 0\n";
    /* kept: (0,1,2) and (2,1,0) of the quad; dropped: repeated index, collinear, coincident. */
    rtp_ply_mesh m = load(put_text("degenerate.ply", text));
    static const uint32_t kept[] = {0, 1, 2, 2, 1, 0};
    cr_assert_eq(m.triangle_count, 2);
    cr_expect_arr_eq(m.indices, kept, sizeof kept);
    rtp_ply_free(&m);
}

/* ---- hostile files ---- */

static void expect_error(const char *path, const char *needle)
{
    rtp_ply_mesh m;
    char err[512];
    memset(&m, 0xab, sizeof m);
    cr_assert_not(rtp_ply_read(path, &m, err, sizeof err), "accepted, expected: %s", needle);
    cr_expect_null(m.positions);
    cr_expect_null(m.indices);
    cr_expect_null(strchr(err, '\n'), "not one line: %s", err);
    cr_expect_eq(strncmp(err, path, strlen(path)), 0, "does not name the file: %s", err);
    cr_expect_not_null(strstr(err, needle), "got \"%s\", expected \"%s\"", err, needle);
}

#define HEAD "ply\nformat ascii 1.0\n"
#define XYZ "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
#define FACE "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
#define TRI "0 0 0\n1 0 0\n0 1 0\n"

Test(ply, hostile_headers)
{
    static const struct {
        const char *text, *error;
    } cases[] = {
        {"", "line 1: not a PLY file"},
        {"\x7f"
         "ELF\x02\x01\x01\x00\x00\x00\n",
         "line 1: not a PLY file"},
        {"PLY\nformat ascii 1.0\n", "line 1: not a PLY file"},
        {HEAD XYZ "element face 1\n", "line 8: end of file before end_header"},
        {"ply\nformat ascii 2.0\n" XYZ FACE TRI "3 0 1 2\n", "line 2: expected 'format"},
        {"ply\nformat binary_middle_endian 1.0\n" XYZ FACE, "line 2: unknown format"},
        {"ply\n" XYZ FACE, "line 2: element before the format line"},
        {"ply\nend_header\n", "line 2: end_header before the format line"},
        {HEAD "format ascii 1.0\n", "line 3: second format line"},
        {HEAD "property float x\n", "line 3: property before any element"},
        {HEAD "element vertex 3\nproperty float64x x\n", "line 4: unknown property type"},
        {HEAD "element vertex 3\nproperty float\n", "line 4: expected 'property <type> <name>'"},
        {HEAD "element vertex\n", "line 3: expected 'element <name> <count>'"},
        {HEAD "element vertex -3\n", "line 3: element count is not a non-negative integer"},
        {HEAD "element vertex 99999999999999999999999\n", "line 3: element count too large"},
        {HEAD XYZ "element vertex 3\n", "line 7: element vertex declared twice"},
        {HEAD "element vertex 3\nproperty float x\nproperty float y\nproperty float x\n",
         "line 6: second property for x"},
        {HEAD "element vertex 3\nproperty list uchar float x\n", "line 4: property x must be a scalar"},
        {HEAD XYZ "element face 1\nproperty int vertex_indices\n", "line 8: property vertex_indices must be a list"},
        {HEAD XYZ "element face 1\nproperty list float int vertex_indices\n",
         "line 8: list count type must be an integer"},
        {HEAD XYZ "element face 1\nproperty list uchar float vertex_indices\n",
         "line 8: vertex indices must be integers"},
        {HEAD "element vertex 3\nproperty float x\nproperty float y\n" FACE TRI "3 0 1 2\n",
         "line 3: element vertex has no property z"},
        {HEAD FACE "3 0 1 2\n", "no element vertex"},
        {HEAD XYZ "end_header\n" TRI, "line 7: no element face with a vertex_indices list"},
        {HEAD "element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n" FACE TRI,
         "line 3: element vertex declares 4000000000 entries but the file has room for at most"},
        {HEAD XYZ "element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n" TRI,
         "line 7: element face declares 4000000000 entries"},
        {HEAD "element vertex 4294967295\nproperty float x\nproperty float y\nproperty float z\n" FACE,
         "line 3: too many vertices"},
        {HEAD "element a 1\nelement b 1\nelement c 1\nelement d 1\nelement e 1\nelement f 1\nelement g 1\n"
              "element h 1\nelement i 1\nelement j 1\nelement k 1\nelement l 1\nelement m 1\nelement n 1\n"
              "element o 1\nelement p 1\nelement q 1\n",
         "line 19: more than 16 elements"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char name[32];
        snprintf(name, sizeof name, "header%zu.ply", i);
        expect_error(put_text(name, cases[i].text), cases[i].error);
    }
}

Test(ply, too_many_properties)
{
    char text[4096] = HEAD "element vertex 1\n";
    for (int i = 0; i < 65; i++) snprintf(text + strlen(text), sizeof text - strlen(text), "property float p%d\n", i);
    expect_error(put_text("props.ply", text), "line 68: element vertex has more than 64 properties");
}

Test(ply, hostile_ascii_bodies)
{
    static const struct {
        const char *text, *error;
    } cases[] = {
        {HEAD XYZ FACE TRI, "line 13: face 0 of 1: unexpected end of file"},
        {HEAD XYZ FACE "0 0 0\n1 0 0\n", "line 12: vertex 2 of 3: unexpected end of file"},
        {HEAD XYZ FACE TRI "3 0 1 2\n3 0 1 2\n", "line 14: data after the last element"},
        {HEAD XYZ FACE TRI "3 0 1 3\n", "line 13: face 0 of 1: vertex index 3 out of range (3 vertices)"},
        {HEAD XYZ FACE TRI "3 0 -1 2\n", "line 13: face 0 of 1: vertex index -1 out of range"},
        {HEAD XYZ FACE "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 of 3: x is not a finite number"},
        {HEAD XYZ FACE "0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 of 3: z is not a finite number"},
        {HEAD XYZ FACE "0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 of 3: y is not a finite number"},
        {HEAD XYZ FACE "0 0 0\n1 0 abc\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 of 3: 'abc' is not a number"},
        {HEAD XYZ FACE "0 0 0\n1 0 0.5.5\n0 1 0\n3 0 1 2\n", "'0.5.5' is not a number"},
        {HEAD XYZ FACE "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "line 11: vertex 1 of 3: fewer values than the header declares"},
        {HEAD XYZ FACE "0 0 0\n1 0 0 0\n0 1 0\n3 0 1 2\n",
         "line 11: vertex 1 of 3: more values than the header declares"},
        {HEAD XYZ FACE TRI "3 0 1\n", "line 13: face 0 of 1: fewer values"},
        {HEAD XYZ FACE TRI "3 0 1 2.0\n", "'2.0' is not an integer"},
        {HEAD XYZ FACE TRI "300 0 1 2\n", "300 out of range for uchar"},
        {HEAD XYZ FACE TRI "3 0 1 99999999999999999999\n", "out of range for int"},
        {HEAD XYZ "element face 1\nproperty list int int vertex_indices\nend_header\n" TRI "-3 0 1 2\n",
         "face 0 of 1: negative list count"},
        {HEAD XYZ FACE "0 0 0\n1 0 1234567890123456789012345678901234567890123456789012345678901234567890\n",
         "value too long to be a number"},
        {HEAD XYZ FACE "garbage line here\nmore garbage\n\x01\x02\x03\n",
         "line 10: vertex 0 of 3: 'garbage' is not a number"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char name[32];
        snprintf(name, sizeof name, "body%zu.ply", i);
        expect_error(put_text(name, cases[i].text), cases[i].error);
    }
}

/* Binary files whose header is text and whose body is given as bytes. */
static const char *put_binary(const char *name, const char *header, const void *body, size_t size)
{
    char buf[1024];
    size_t n = strlen(header);
    cr_assert_lt(n + size, sizeof buf);
    memcpy(buf, header, n);
    memcpy(buf + n, body, size);
    return put_file(name, buf, n + size);
}

#define LE "ply\nformat binary_little_endian 1.0\n"
#define BXYZ "element vertex 3\nproperty uchar x\nproperty uchar y\nproperty uchar z\n"
#define BFACE "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n"

/* "byte N" where N is the offset of body byte `at` in a file with this header. */
static const char *at_byte(const char *header, size_t at, const char *rest)
{
    static char buf[256];
    snprintf(buf, sizeof buf, "byte %zu: %s", strlen(header) + at, rest);
    return buf;
}

Test(ply, hostile_binary_bodies)
{
    static const uint8_t tri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 1, 2};
    rtp_ply_mesh m = load(put_binary("ok.ply", LE BXYZ BFACE, tri, sizeof tri));
    cr_expect_eq(m.triangle_count, 1);
    cr_expect_eq(m.positions[1].x, 1.0);
    rtp_ply_free(&m);
    expect_error(put_binary("short.ply", LE BXYZ BFACE, tri, sizeof tri - 1),
                 at_byte(LE BXYZ BFACE, 12, "face 0 of 1: unexpected end of file"));
    static const uint8_t extra[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 1, 2, 9, 9};
    expect_error(put_binary("extra.ply", LE BXYZ BFACE, extra, sizeof extra),
                 at_byte(LE BXYZ BFACE, 13, "2 bytes after the last element"));
    static const uint8_t range[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 1, 200};
    expect_error(put_binary("range.ply", LE BXYZ BFACE, range, sizeof range),
                 at_byte(LE BXYZ BFACE, 12, "face 0 of 1: vertex index 200 out of range (3 vertices)"));
    /* A NaN float (0x7fc00000, little-endian) and an infinite double (big-endian). */
#define FXYZ "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
    static const uint8_t nan_float[] = {0, 0, 0, 0, 0, 0, 0xc0, 0x7f, 0, 0, 0, 0, 0};
    expect_error(put_binary("nan.ply", LE FXYZ BFACE, nan_float, sizeof nan_float),
                 at_byte(LE FXYZ BFACE, 4, "vertex 0 of 1: y is not a finite number"));
#define BE "ply\nformat binary_big_endian 1.0\n"
#define DZXY "element vertex 1\nproperty double z\nproperty double x\nproperty double y\n"
    static const uint8_t inf_double[28] = {0x7f, 0xf0, [24] = 3, 0, 0, 0};
    expect_error(put_binary("inf.ply", BE DZXY BFACE, inf_double, sizeof inf_double),
                 at_byte(BE DZXY BFACE, 0, "vertex 0 of 1: z is not a finite number"));
    /* A list count that claims four billion entries, in a skipped list and in the indices. */
#define JUNK "element vertex 1\nproperty uchar x\nproperty uchar y\nproperty uchar z\nproperty list uint float junk\n"
    static const uint8_t huge[] = {0, 0, 0, 0xff, 0xff, 0xff, 0xff, 1, 2, 3};
    expect_error(put_binary("huge.ply", LE JUNK BFACE, huge, sizeof huge),
                 at_byte(LE JUNK BFACE, 7, "vertex 0 of 1: unexpected end of file"));
#define UFACE "element face 1\nproperty list uint int vertex_indices\nend_header\n"
    static const uint8_t huge_face[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0, 1, 0, 0, 0};
    expect_error(put_binary("hugeface.ply", LE BXYZ UFACE, huge_face, sizeof huge_face),
                 at_byte(LE BXYZ UFACE, 21, "face 0 of 1: unexpected end of file"));
    expect_error(put_binary("absurd.ply",
                            LE "element vertex 4000000000\nproperty uchar x\nproperty uchar y\n"
                               "property uchar z\n" BFACE,
                            tri, sizeof tri),
                 "line 3: element vertex declares 4000000000 entries but the file has room for at most 4");
}

Test(ply, files_that_cannot_be_read)
{
    rtp_ply_mesh m;
    char err[256];
    cr_assert_not(rtp_ply_read("/nonexistent/mesh.ply", &m, err, sizeof err));
    cr_expect_str_eq(err, "/nonexistent/mesh.ply: cannot open: No such file or directory");
    cr_assert_not(rtp_ply_read(dir, &m, err, sizeof err));
    cr_expect_not_null(strstr(err, "is a directory"), "%s", err);
    /* A tiny error buffer is filled, truncated, and terminated. */
    char small[8];
    cr_assert_not(rtp_ply_read("/nonexistent/mesh.ply", &m, small, sizeof small));
    cr_expect_str_eq(small, "/nonexi");
}

/* Vertices equal in position, normal and uv are joined (the course's importer does),
 * so Loop subdivision sees a connected surface; vertices that differ in any attribute
 * stay apart. */
Test(ply, identical_vertices_are_joined)
{
    char scratch[64], path[128];
    cr_assert(tmpdir_make(scratch, sizeof scratch, "weld"), "cannot create a scratch folder");
    snprintf(path, sizeof path, "%s/soup.ply", scratch);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs("ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\n"
          "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
          "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n" /* face 0 */
          "1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n" /* face 1 repeats two corners exactly */
          "0 0 0 1 0 0\n"                           /* same position, other normal: kept */
          "3 0 1 2\n3 3 4 5\n",
          f);
    fclose(f);
    rtp_ply_mesh m = load(path);
    cr_assert_eq(m.vertex_count, 5);
    cr_assert_eq(m.triangle_count, 2);
    uint32_t want[6] = {0, 1, 2, 1, 3, 2};
    cr_assert_arr_eq(m.indices, want, sizeof want);
    cr_assert_eq(m.positions[3].x, 1);
    cr_assert_eq(m.positions[3].y, 1);
    cr_assert_eq(m.normals[4].x, 1);
    rtp_ply_free(&m);
    tmpdir_remove(scratch);
}

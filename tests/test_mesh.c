/* Mesh processing: smooth normals, Loop subdivision (format.md §6.7), the built-in Cube and square. */
#include "builtin_mesh.h"
#include "load/ply.h"
#include "mesh.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TRACE "../shared/cse457/assets/trace/"

static void *memory;
static rt_arena arena;

static void setup(void)
{
    size_t size = 64u << 20;
    memory = malloc(size);
    cr_assert_not_null(memory);
    rt_arena_init(&arena, memory, size);
}

static void teardown(void) { free(memory); }

TestSuite(mesh, .init = setup, .fini = teardown);

static rt_vec3 v3(double x, double y, double z)
{
    return rt_v3(rt_from_double(x), rt_from_double(y), rt_from_double(z));
}

static void expect_near(rt_vec3 got, rt_vec3 want, double tol, const char *what, uint32_t i)
{
    cr_expect(fabs(rt_to_double(got.x) - rt_to_double(want.x)) <= tol &&
                  fabs(rt_to_double(got.y) - rt_to_double(want.y)) <= tol &&
                  fabs(rt_to_double(got.z) - rt_to_double(want.z)) <= tol,
              "%s %u: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)", what, i, rt_to_double(got.x),
              rt_to_double(got.y), rt_to_double(got.z), rt_to_double(want.x), rt_to_double(want.y),
              rt_to_double(want.z));
}

static double length(rt_vec3 a) { return sqrt(rt_to_double(rt_v3_dot(a, a))); }

/* ---- closed test solids, wound counter-clockwise seen from outside ---- */

static const rt_vec3 tetra_p[] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
static const uint32_t tetra_i[] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
static const rt_vec3 octa_p[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const uint32_t octa_i[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
static const rt_vec3 box_p[] = {{-1, -1, -1}, {-1, -1, 1}, {-1, 1, -1}, {-1, 1, 1},
                                {1, -1, -1},  {1, -1, 1},  {1, 1, -1},  {1, 1, 1}};
static const uint32_t box_i[] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};

static rt_mesh_desc solid(const rt_vec3 *p, uint32_t nv, const uint32_t *idx, uint32_t nt)
{
    return (rt_mesh_desc){.positions = p, .vertex_count = nv, .indices = idx, .triangle_count = nt};
}

#define TETRA solid(tetra_p, 4, tetra_i, 4)
#define OCTA solid(octa_p, 6, octa_i, 8)
#define BOX solid(box_p, 8, box_i, 12)

/* ---- smooth normals ---- */

Test(mesh, smooth_normals_are_area_weighted_over_bit_identical_positions)
{
    /* Three separate triangles: two share the edge (0,0,0)-(0,2,0) with areas 2 (z = 0
     * plane) and 3 (x = 0 plane); the third starts at -0.0, which is not the same bits. */
    rt_vec3 p[] = {v3(0, 0, 0), v3(2, 0, 0),    v3(0, 2, 0),  v3(0, 0, 0), v3(0, 2, 0),
                   v3(0, 0, 3), v3(-0.0, 0, 0), v3(0, -1, 0), v3(0, 0, -1)};
    uint32_t idx[] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    rt_mesh_desc m = solid(p, 9, idx, 3);
    rt_vec3 *n;
    cr_assert_eq(rt_mesh_smooth_normals(&m, &arena, &n), RT_OK);
    /* cross products (0,0,4) and (6,0,0): the shared positions get (6,0,4)/|(6,0,4)|. */
    rt_vec3 shared = v3(3 / sqrt(13), 0, 2 / sqrt(13));
    rt_vec3 want[] = {shared, v3(0, 0, 1), shared, shared, shared, v3(1, 0, 0), v3(1, 0, 0), v3(1, 0, 0), v3(1, 0, 0)};
    for (uint32_t v = 0; v < 9; v++) expect_near(n[v], want[v], 1e-15, "normal", v);
    cr_expect_arr_eq(&n[0], &n[3], sizeof n[0], "coincident vertices must get the very same bits");
    /* The scratch (hash table, sums) is released: only the normals stay. */
    cr_expect_leq(arena.used, 16 + 9 * sizeof(rt_vec3));
}

typedef struct {
    rt_vec3 p;
    uint32_t v;
} tagged;

static int by_position(const void *a, const void *b)
{
    return memcmp(&((const tagged *)a)->p, &((const tagged *)b)->p, sizeof(rt_vec3));
}

Test(mesh, sculpt_gets_smooth_normals)
{
    rtp_ply_mesh ply;
    char err[256];
    cr_assert(rtp_ply_read(TRACE "trimeshes/sculpt.ply", &ply, err, sizeof err), "%s", err);
    rt_mesh_desc m = rtp_ply_view(&ply);
    rt_vec3 *n;
    cr_assert_eq(rt_mesh_smooth_normals(&m, &arena, &n), RT_OK);
    tagged *order = malloc(m.vertex_count * sizeof *order);
    for (uint32_t v = 0; v < m.vertex_count; v++) order[v] = (tagged){m.positions[v], v};
    qsort(order, m.vertex_count, sizeof *order, by_position);
    uint32_t groups = 0, flat = 0;
    for (uint32_t i = 0; i < m.vertex_count; i++) {
        uint32_t v = order[i].v;
        cr_assert_lt(fabs(length(n[v]) - 1), 1e-12, "normal %u is not unit", v);
        if (i == 0 || by_position(&order[i], &order[i - 1]) != 0)
            groups++;
        else
            cr_assert_arr_eq(&n[v], &n[order[i - 1].v], sizeof(rt_vec3), "vertex %u differs from its twin", v);
    }
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        const uint32_t *i = &m.indices[3 * t];
        rt_vec3 face = rt_v3_normalize(rt_v3_cross(rt_v3_sub(m.positions[i[1]], m.positions[i[0]]),
                                                   rt_v3_sub(m.positions[i[2]], m.positions[i[0]])));
        for (int k = 0; k < 3; k++) flat += rt_to_double(rt_v3_dot(face, n[i[k]])) > 1 - 1e-9;
    }
    /* The file gives every face its own three vertices; joined, each position is one vertex. */
    cr_expect_eq(groups, m.vertex_count, "%u distinct positions for %u vertices", groups, m.vertex_count);
    cr_expect_lt(m.vertex_count, m.triangle_count, "%u vertices for %u faces", m.vertex_count, m.triangle_count);
    cr_expect_lt(flat, m.vertex_count / 10, "%u of %u vertex normals are just the face normal", flat, m.vertex_count);
    free(order);
    rtp_ply_free(&ply);
}

Test(mesh, smooth_normals_report_a_full_arena_and_bad_indices)
{
    rt_mesh_desc m = OCTA;
    rt_vec3 *n;
    uint8_t small[256];
    rt_arena tiny;
    rt_arena_init(&tiny, small, sizeof small);
    cr_expect_eq(rt_mesh_smooth_normals(&m, &tiny, &n), RT_ERR_NOMEM);
    cr_expect_eq(tiny.used, 0);
    cr_expect_gt(tiny.wanted, sizeof small);
    uint32_t bad[] = {0, 1, 6};
    m = solid(octa_p, 6, bad, 1);
    cr_expect_eq(rt_mesh_smooth_normals(&m, &arena, &n), RT_ERR_INVALID);
}

/* ---- subdivision ---- */

static rt_mesh_desc subdivide(rt_mesh_desc m, uint32_t levels)
{
    rt_mesh_desc out;
    cr_assert_eq(rt_mesh_subdivide(&m, levels, &arena, &out), RT_OK);
    return out;
}

Test(mesh, closed_meshes_grow_by_their_edges)
{
    const struct {
        const char *name;
        rt_mesh_desc mesh;
        uint32_t v1, v2; /* V + E after one level, then V + E + E' with E' = 2E + 3F */
    } cases[] = {
        {"tetrahedron", TETRA, 4 + 6, 10 + 24},
        {"octahedron", OCTA, 6 + 12, 18 + 48},
        {"box", BOX, 8 + 18, 26 + 72},
    };
    for (size_t i = 0; i < 3; i++) {
        for (uint32_t level = 1; level <= 2; level++) {
            rt_arena_reset(&arena, 0);
            rt_mesh_desc out = subdivide(cases[i].mesh, level);
            cr_expect_eq(out.vertex_count, level == 1 ? cases[i].v1 : cases[i].v2, "%s level %u", cases[i].name, level);
            cr_expect_eq(out.triangle_count, cases[i].mesh.triangle_count << (2 * level), "%s", cases[i].name);
            cr_expect_null(out.uvs);
            cr_expect_not_null(out.normals);
            for (uint32_t t = 0; t < 3 * out.triangle_count; t++) cr_assert_lt(out.indices[t], out.vertex_count);
        }
    }
}

Test(mesh, one_level_of_the_octahedron_by_hand)
{
    /* Vertex 0 = (1,0,0) has valence 4: beta = 31/32, alpha = 4/31, so averaging gives
     * x = 66/128; its four neighbours (edge midpoints, valence 6, alpha = 2) average to
     * x = 0.375. The limit with eps = 3k/beta = 384/31 is (384/31 * 66/128 + 1.5) / (508/31). */
    rt_mesh_desc out = subdivide(OCTA, 1);
    cr_assert_eq(out.vertex_count, 18);
    expect_near(out.positions[0], v3(244.5 / 508, 0, 0), 1e-15, "position", 0);
    expect_near(out.normals[0], v3(1, 0, 0), 1e-15, "normal", 0);
    /* Vertex 6 is the midpoint of the first edge, 0-2: (24 * 0.375 + 1.265625) / 30. */
    expect_near(out.positions[6], v3(0.3421875, 0.3421875, 0), 1e-15, "position", 6);
    expect_near(out.normals[6], v3(sqrt(0.5), sqrt(0.5), 0), 1e-15, "normal", 6);
    /* Triangle (0,2,4) became (0,ab,ca), (2,bc,ab), (4,ca,bc), (ab,bc,ca) with ab = 6, bc = 7, ca = 8. */
    static const uint32_t first[] = {0, 6, 8, 2, 7, 6, 4, 8, 7, 6, 7, 8};
    cr_expect_arr_eq(out.indices, first, sizeof first);
}

Test(mesh, subdivided_octahedron_is_a_smooth_closed_blob)
{
    double lo[6], hi[6];
    for (uint32_t level = 1; level <= 5; level++) {
        rt_arena_reset(&arena, 0);
        rt_mesh_desc out = subdivide(OCTA, level);
        lo[level] = 1e9;
        hi[level] = 0;
        for (uint32_t v = 0; v < out.vertex_count; v++) {
            rt_vec3 p = out.positions[v], n = out.normals[v];
            double r = length(p);
            lo[level] = fmin(lo[level], r);
            hi[level] = fmax(hi[level], r);
            cr_assert_lt(fabs(length(n) - 1), 1e-12, "level %u normal %u is not unit", level, v);
            cr_assert_gt(rt_to_double(rt_v3_dot(n, p)) / r, 0.99, "level %u normal %u does not point outward", level,
                         v);
        }
        cr_expect(lo[level] > 0.4 && hi[level] < 0.49, "level %u radii [%g, %g]", level, lo[level], hi[level]);
    }
    /* Converging: each level moves the extreme radii less than the one before. */
    for (uint32_t level = 3; level <= 5; level++) {
        cr_expect_lt(fabs(lo[level] - lo[level - 1]), fabs(lo[level - 1] - lo[level - 2]), "level %u", level);
        cr_expect_lt(fabs(hi[level] - hi[level - 1]), fabs(hi[level - 1] - hi[level - 2]), "level %u", level);
    }
}

Test(mesh, uvs_are_midpoints_and_not_averaged)
{
    rt_vec3 p[] = {v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0)};
    rt_vec2 uv[] = {{0.25, 0.5}, {1, 0}, {0, 1}};
    uint32_t idx[] = {0, 1, 2};
    rt_mesh_desc m = solid(p, 3, idx, 1);
    m.uvs = uv;
    rt_mesh_desc out = subdivide(m, 1);
    cr_assert_eq(out.vertex_count, 6);
    cr_assert_not_null(out.uvs);
    rt_vec2 want[] = {{0.25, 0.5}, {1, 0}, {0, 1}, {0.625, 0.25}, {0.5, 0.5}, {0.125, 0.75}};
    cr_expect_arr_eq(out.uvs, want, sizeof want);
    rt_arena_reset(&arena, 0);
    out = subdivide(m, 2);
    cr_assert_eq(out.vertex_count, 15);
    /* Level 2's first new vertex is the midpoint of vertex 0 and ab (edge 0-3 of level 1). */
    cr_expect_eq(out.uvs[6].u, 0.4375);
    cr_expect_eq(out.uvs[6].v, 0.375);
    cr_expect_arr_eq(out.uvs, want, sizeof want);
}

Test(mesh, a_lone_triangle_keeps_its_plane_and_facing)
{
    /* Every vertex is on the border, corners have valence 2: the open-ring ordering and the
     * face-normal fallback must still give the triangle's own normal. */
    rt_vec3 p[] = {v3(0, 0, 0), v3(2, 0, 0), v3(0.5, 1.5, 0)};
    uint32_t idx[] = {0, 1, 2};
    rt_mesh_desc out = subdivide(solid(p, 3, idx, 1), 3);
    cr_assert_eq(out.triangle_count, 64);
    for (uint32_t v = 0; v < out.vertex_count; v++) {
        cr_expect_eq(out.positions[v].z, 0.0);
        cr_expect_eq(out.normals[v].x, 0.0, "vertex %u", v);
        cr_expect_eq(out.normals[v].y, 0.0, "vertex %u", v);
        cr_expect_lt(fabs(out.normals[v].z - 1.0), 1e-15, "vertex %u", v);
    }
}

Test(mesh, input_normals_are_ignored_and_results_are_reproducible)
{
    rt_vec3 junk[6];
    for (int i = 0; i < 6; i++) junk[i] = v3(0, 0, -1);
    rt_mesh_desc m = OCTA;
    rt_mesh_desc a = subdivide(m, 2);
    m.normals = junk;
    uint8_t *other = malloc(8u << 20);
    rt_arena second;
    rt_arena_init(&second, other + 48, (8u << 20) - 48); /* a different base and history */
    cr_assert_not_null(rt_arena_alloc(&second, 1000));
    rt_mesh_desc b;
    cr_assert_eq(rt_mesh_subdivide(&m, 2, &second, &b), RT_OK);
    cr_assert_eq(a.vertex_count, b.vertex_count);
    cr_expect_arr_eq(a.positions, b.positions, a.vertex_count * sizeof(rt_vec3));
    cr_expect_arr_eq(a.normals, b.normals, a.vertex_count * sizeof(rt_vec3));
    cr_expect_arr_eq(a.indices, b.indices, 3 * a.triangle_count * sizeof(uint32_t));
    free(other);
}

Test(mesh, subdivision_keeps_only_its_result_in_the_arena)
{
    rt_mesh_desc out = subdivide(OCTA, 3);
    size_t result = 3 * out.triangle_count * sizeof(uint32_t) + 2 * out.vertex_count * sizeof(rt_vec3);
    cr_expect_leq(arena.used, result + 3 * 16, "used %zu for a %zu-byte result", arena.used, result);
    cr_expect_gt(arena.high_water, 2 * result);
    uint8_t *lo = arena.base, *hi = arena.base + arena.used;
    cr_expect((uint8_t *)out.positions >= lo && (uint8_t *)(out.positions + out.vertex_count) <= hi);
    cr_expect((uint8_t *)out.normals >= lo && (uint8_t *)(out.normals + out.vertex_count) <= hi);
    cr_expect((uint8_t *)out.indices >= lo && (uint8_t *)(out.indices + 3 * out.triangle_count) <= hi);
}

Test(mesh, every_arena_size_short_of_enough_is_a_clean_nomem)
{
    rt_mesh_desc m = BOX, out;
    cr_assert_eq(rt_mesh_subdivide(&m, 2, &arena, &out), RT_OK);
    size_t need = arena.high_water;
    uint8_t *buf = malloc(need + 64);
    for (size_t cap = 0; cap < need; cap += 8) {
        rt_arena a;
        rt_arena_init(&a, buf, cap);
        if (cap >= 64) cr_assert_not_null(rt_arena_alloc(&a, 40)); /* something already there */
        size_t before = a.used;
        rt_status st = rt_mesh_subdivide(&m, 2, &a, &out);
        cr_assert_eq(st, RT_ERR_NOMEM, "capacity %zu of %zu", cap, need);
        cr_assert_eq(a.used, before, "capacity %zu: scratch not released", cap);
        cr_assert_gt(a.wanted, cap);
    }
    rt_arena a;
    rt_arena_init(&a, buf, need);
    cr_expect_eq(rt_mesh_subdivide(&m, 2, &a, &out), RT_OK);
    free(buf);
}

Test(mesh, subdivision_refuses_bad_arguments)
{
    rt_mesh_desc m = OCTA, out;
    cr_expect_eq(rt_mesh_subdivide(&m, 0, &arena, &out), RT_ERR_INVALID);
    cr_expect_eq(rt_mesh_subdivide(&m, RT_MAX_SUBDIVISION + 1, &arena, &out), RT_ERR_INVALID);
    uint32_t bad[] = {0, 1, 6};
    m = solid(octa_p, 6, bad, 1);
    cr_expect_eq(rt_mesh_subdivide(&m, 1, &arena, &out), RT_ERR_INVALID);
    cr_expect_eq(arena.used, 0);
}

/* ---- built-in meshes ---- */

Test(mesh, cube_matches_the_format)
{
    rt_mesh_desc c = rt_builtin_mesh_cube();
    cr_assert_eq(c.vertex_count, 24);
    cr_assert_eq(c.triangle_count, 12);
    cr_assert_not_null(c.normals);
    cr_assert_not_null(c.uvs);
    /* format.md §6.1: faces back, front, left, right, bottom, top; corner triangles per face. */
    static const rt_vec3 face_normal[6] = {{0, 0, -1}, {0, 0, 1}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
    static const uint32_t corners[2][6] = {{0, 1, 2, 2, 1, 3}, {1, 0, 2, 1, 2, 3}};
    for (uint32_t f = 0; f < 6; f++) {
        for (uint32_t k = 0; k < 6; k++)
            cr_expect_eq(c.indices[6 * f + k], 4 * f + corners[f % 2][k], "face %u index %u", f, k);
        for (uint32_t i = 4 * f; i < 4 * f + 4; i++) {
            rt_vec3 p = c.positions[i], n = face_normal[f];
            cr_expect(c.normals[i].x == n.x && c.normals[i].y == n.y && c.normals[i].z == n.z, "vertex %u", i);
            cr_expect_eq(rt_v3_dot(p, n), 0.5, "vertex %u is not on its face", i);
            cr_expect(rt_abs(p.x) == RT_C(0.5) && rt_abs(p.y) == RT_C(0.5) && rt_abs(p.z) == RT_C(0.5), "vertex %u", i);
            /* u follows x (y for left/right), v follows y (z for left/right, -z for bottom/top). */
            double u = f < 2 || f >= 4 ? p.x + 0.5 : p.y + 0.5;
            double v = f < 2 ? p.y + 0.5 : f < 4 ? p.z + 0.5 : 0.5 - p.z;
            cr_expect_eq(c.uvs[i].u, u, "vertex %u", i);
            cr_expect_eq(c.uvs[i].v, v, "vertex %u", i);
        }
        /* Corners 0..3 carry uv (0,0), (0,1), (1,0), (1,1). */
        for (uint32_t k = 0; k < 4; k++) {
            cr_expect_eq(c.uvs[4 * f + k].u, (double)(k / 2), "face %u corner %u", f, k);
            cr_expect_eq(c.uvs[4 * f + k].v, (double)(k % 2), "face %u corner %u", f, k);
        }
    }
    /* Every triangle is wound so that its cross product is the stored outward normal. */
    for (uint32_t t = 0; t < 12; t++) {
        const uint32_t *i = &c.indices[3 * t];
        rt_vec3 n = rt_v3_normalize(rt_v3_cross(rt_v3_sub(c.positions[i[1]], c.positions[i[0]]),
                                                rt_v3_sub(c.positions[i[2]], c.positions[i[0]])));
        for (int k = 0; k < 3; k++) /* by value: the cross product has some -0.0 */
            cr_expect(n.x == c.normals[i[k]].x && n.y == c.normals[i[k]].y && n.z == c.normals[i[k]].z, "triangle %u",
                      t);
    }
}

Test(mesh, square_is_the_unit_plane)
{
    rt_mesh_desc s = rt_builtin_mesh_square();
    cr_assert_eq(s.vertex_count, 4);
    cr_assert_eq(s.triangle_count, 2);
    double area = 0;
    for (uint32_t v = 0; v < 4; v++) {
        rt_vec3 p = s.positions[v];
        cr_expect(rt_abs(p.x) == RT_C(0.5) && rt_abs(p.y) == RT_C(0.5) && p.z == RT_ZERO, "vertex %u", v);
        cr_expect_eq(s.normals[v].x, 0.0);
        cr_expect_eq(s.normals[v].y, 0.0);
        cr_expect_eq(s.normals[v].z, 1.0);
        cr_expect_eq(s.uvs[v].u, p.x + 0.5);
        cr_expect_eq(s.uvs[v].v, p.y + 0.5);
    }
    for (uint32_t t = 0; t < 2; t++) {
        const uint32_t *i = &s.indices[3 * t];
        rt_vec3 n = rt_v3_cross(rt_v3_sub(s.positions[i[1]], s.positions[i[0]]),
                                rt_v3_sub(s.positions[i[2]], s.positions[i[0]]));
        cr_expect_gt(n.z, 0.0, "triangle %u faces +z", t);
        area += n.z / 2;
    }
    cr_expect_eq(area, 1.0);
}

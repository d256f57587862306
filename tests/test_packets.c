/* The stream queries (core/bvh_stream.c: packets of rays under the SSE2, AVX2 and AVX-512
 * kernels) give every ray exactly what the one-ray queries give it, and a render traced
 * by groups of pixels (core/render_group.c), in packets or one ray at a time, is the same
 * bytes as one traced pixel by pixel, under every kernel this CPU runs. */
#include "bvh.h"
#include "cli/cli.h"
#include "load/scene_open.h"
#include "reference.h"
#include "render.h"
#include "same_hit.h"
#include "scene_query.h"
#include "sha256.h"
#include "thread/kernel.h"
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t lcg_state;
static double next_unit(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg_state >> 11) / 9007199254740992.0;
}
static double next_range(double lo, double hi) { return lo + (hi - lo) * next_unit(); }

/* A soup of triangles in [-10, 10]^3 (neighbours sharing edges, some twice over) and
 * spheres; memory from a malloc'd arena. */
static void soup(rt_scene *s, void **memory, uint32_t triangles, uint32_t spheres)
{
    size_t size = 64u << 20;
    *memory = malloc(size);
    rt_arena arena;
    rt_arena_init(&arena, *memory, size);
    static rt_material material;
    uint32_t vertices = triangles + 2;
    rt_vec3 *pos = malloc(sizeof(rt_vec3) * vertices);
    uint32_t *idx = malloc(sizeof(uint32_t) * triangles * 3);
    for (uint32_t i = 0; i < vertices; i++)
        pos[i] = rt_v3(next_range(-10, 10), next_range(-10, 10), next_range(-10, 10));
    for (uint32_t t = 0; t < triangles; t++) { /* a strip: neighbours share an edge */
        idx[3 * t] = t;
        idx[3 * t + 1] = t + 1;
        idx[3 * t + 2] = t + 2;
        if (t % 5 == 0) pos[t + 2] = rt_v3_add(pos[t], rt_v3(next_range(-1, 1), next_range(-1, 1), next_range(-1, 1)));
        /* Every seventh triangle again: exact ties, which go to the lower reference. */
        if (t % 7 == 6) memcpy(&idx[3 * t], &idx[3 * (t - 1)], 3 * sizeof *idx);
    }
    rt_mesh_desc mesh = {pos, NULL, NULL, vertices, idx, triangles};
    rt_object_desc *objs = calloc(spheres + 1, sizeof *objs);
    objs[0].kind = RT_SHAPE_MESH;
    objs[0].world = rt_affine_identity();
    for (uint32_t i = 1; i <= spheres; i++) {
        objs[i].kind = RT_SHAPE_SPHERE;
        rt_real r = next_range(0.5, 3);
        objs[i].world = rt_affine_trs(rt_v3(next_range(-10, 10), next_range(-10, 10), next_range(-10, 10)),
                                      rt_v3(0, 0, 0), rt_v3(r, r, r));
    }
    material.index_of_refraction = 1;
    material.diffuse.texture = material.specular.texture = RT_NO_TEXTURE;
    material.emissive.texture = material.transmittance.texture = RT_NO_TEXTURE;
    rt_scene_desc d = {0};
    d.materials = &material;
    d.material_count = 1;
    d.meshes = &mesh;
    d.mesh_count = 1;
    d.objects = objs;
    d.object_count = spheres + 1;
    d.camera.world = rt_affine_identity();
    d.camera.fov_degrees = 50;
    d.camera.width = d.camera.height = 8;
    rt_build_error err;
    cr_assert_eq(rt_scene_build(&d, &arena, NULL, s, &err), RT_OK, "%s", err.what);
    free(pos);
    free(idx);
    free(objs);
}

#define RAYS 4096

/* Segments from origins near `from` (within spread) to one end (like a point light's
 * shadow rays from a tile's hit points), n of them from ray i on; a few fall short of the
 * end, so that the rays do not share it. */
static uint32_t to_one_end(rt_ray_setup *rs, uint32_t i, uint32_t n, rt_vec3 from, double spread)
{
    rt_vec3 end = rt_v3(next_range(-12, 12), next_range(-12, 12), next_range(-12, 12));
    for (uint32_t k = 0; k < n && i < RAYS; k++, i++) {
        rt_vec3 o = rt_v3_add(
            from, rt_v3(next_range(-spread, spread), next_range(-spread, spread), next_range(-spread, spread)));
        rt_vec3 delta = rt_v3_sub(end, o);
        rt_real length = rt_v3_length(delta);
        rt_ray r = {o, rt_v3_scale(delta, rt_div(RT_ONE, length)), RT_HIT_EPSILON,
                    i % 37 == 0 ? rt_half(length) : length};
        rs[i] = rt_intersect_prepare(r);
    }
    return i;
}

/* Bundles of 1 to 64 rays from one origin into a narrow cone (like a tile's camera rays)
 * or a wide one, with segments (shadow rays), a few starting at t = 0 and a few with a
 * zero direction component (rays the float bounds do not take); and bundles of segments
 * to one end. */
static void bundles(rt_ray_setup *rs)
{
    for (uint32_t i = 0; i < RAYS;) {
        rt_vec3 o = rt_v3(next_range(-20, 20), next_range(-20, 20), next_range(-20, 20));
        if (next_unit() < 0.25) {
            i = to_one_end(rs, i, 1 + (uint32_t)(next_unit() * 64), o, next_unit() < 0.5 ? 0.5 : 8);
            continue;
        }
        rt_vec3 aim = rt_v3_normalize(rt_v3_sub(rt_v3(next_range(-5, 5), next_range(-5, 5), next_range(-5, 5)), o));
        double spread = next_unit() < 0.7 ? 0.02 : 0.8;
        uint32_t n = 1 + (uint32_t)(next_unit() * 64);
        for (uint32_t k = 0; k < n && i < RAYS; k++, i++) {
            rt_vec3 d = rt_v3_normalize(rt_v3_add(
                aim, rt_v3(next_range(-spread, spread), next_range(-spread, spread), next_range(-spread, spread))));
            if (i % 97 == 0) d.x = 0;
            rt_ray r = {o, d, i % 53 == 0 ? 0 : RT_HIT_EPSILON, i % 3 == 0 ? next_range(1, 30) : RT_REAL_MAX};
            rs[i] = rt_intersect_prepare(r);
        }
    }
}

/* Every kernel's stream and one-ray queries against the portable kernel's one-ray walk. */
Test(packets, stream_queries_equal_one_ray_queries)
{
    lcg_state = 21;
    rt_scene s;
    void *memory;
    soup(&s, &memory, 3000, 40);
    static rt_ray_setup rs[RAYS];
    static rt_scene_hit one[RAYS], many[RAYS];
    static bool one_found[RAYS], many_found[RAYS], one_any[RAYS], many_any[RAYS];
    bundles(rs);
    uint32_t hits = 0, blocked = 0;
    cr_assert(rt_bvh_set_kernel(&s.bvh, RT_KERNEL_PORTABLE));
    for (uint32_t i = 0; i < RAYS; i++) {
        one_found[i] = rt_scene_nearest(&s, &rs[i], true, &one[i]);
        one_any[i] = rt_scene_any(&s, &rs[i], true);
        hits += one_found[i];
        blocked += one_any[i];
    }
    cr_assert(hits > RAYS / 4 && hits < RAYS - RAYS / 8, "%u of %u rays hit", hits, RAYS);
    int kernels = 0;
    for (rt_kernel k = RT_KERNEL_PORTABLE; k <= RT_KERNEL_AVX512; k++) {
        if (!rtp_kernel_runs(k)) continue;
        kernels++;
        cr_assert(rt_bvh_set_kernel(&s.bvh, k));
        memset(many, 0, sizeof many);
        rt_scene_nearest_stream(&s, rs, RAYS, many, many_found);
        rt_scene_any_stream(&s, rs, RAYS, many_any);
        for (uint32_t i = 0; i < RAYS; i++) {
            cr_assert_eq(many_found[i], one_found[i], "%s, ray %u: nearest", rtp_kernel_name(k), i);
            cr_assert_eq(many_any[i], one_any[i], "%s, ray %u: any", rtp_kernel_name(k), i);
            rt_scene_hit alone;
            cr_assert_eq(rt_scene_nearest(&s, &rs[i], true, &alone), one_found[i], "%s, ray %u: one-ray nearest",
                         rtp_kernel_name(k), i);
            cr_assert_eq(rt_scene_any(&s, &rs[i], true), one_any[i], "%s, ray %u: one-ray any", rtp_kernel_name(k), i);
            if (!one_found[i]) continue;
            cr_assert_eq(many[i].prim, one[i].prim, "%s, ray %u: primitive %u, one ray %u", rtp_kernel_name(k), i,
                         many[i].prim, one[i].prim);
            cr_assert(same_hit(&many[i].hit, &one[i].hit), "%s, ray %u: hit records differ", rtp_kernel_name(k), i);
            cr_assert_eq(alone.prim, one[i].prim, "%s, ray %u: one-ray primitive", rtp_kernel_name(k), i);
            cr_assert(same_hit(&alone.hit, &one[i].hit), "%s, ray %u: one-ray hit records differ", rtp_kernel_name(k),
                      i);
        }
    }
    cr_assert_geq(kernels, 1);
    free(memory);
}

/* SHA-256 of a render of corpus scene `name` at size x size with 4^aa samples per pixel
 * under kernel k: through rt_render_region, or by_pixel, rt_render_pixel pixel by pixel. */
static void render_hash(const char *name, rt_kernel k, uint32_t size, int32_t aa, bool by_pixel, uint8_t digest[32])
{
    char path[4096], err[1024];
    snprintf(path, sizeof path, "%s/%s", rt_test_trace_dir(), name);
    rtp_scene_options opt = rtp_scene_default_options();
    opt.width = opt.height = size;
    opt.aa = aa;
    opt.threads = 1;
    opt.kernel_forced = true;
    opt.kernel = k;
    rtp_scene b;
    cr_assert_eq(rtp_scene_open(path, &opt, &b, err, sizeof err), 0, "%s", err);
    cr_assert_eq(b.scene.bvh.kernel, k);
    uint8_t *rgb = calloc((size_t)size * size, 3);
    rt_tracer tr = {.scene = &b.scene, .use_bvh = true};
    if (!by_pixel) rt_render_region(&tr, 0, 0, size, size, rgb);
    for (uint32_t i = 0; by_pixel && i < size * size; i++) {
        rt_vec3 c = rt_render_pixel(&tr, i % size, i / size);
        rgb[3 * i] = rt_render_color_byte(c.x);
        rgb[3 * i + 1] = rt_render_color_byte(c.y);
        rgb[3 * i + 2] = rt_render_color_byte(c.z);
    }
    rt_sha256_ppm(rgb, size, size, digest);
    free(rgb);
    rtp_scene_close(&b);
}

/* Coloured and opaque shadows, glass, a mirror, triangles and quadrics, at an odd size
 * (partial pixel groups), with 1, 4 and 16 samples per pixel: the render by groups of
 * pixels, one ray at a time (the portable kernel) or in packets, against the portable
 * kernel's render pixel by pixel. */
Test(packets, renders_equal_the_pixel_path)
{
    static const char *const scenes[] = {"simple/box_cyl_trans_shadow.yaml", "simple/box_cyl_opaque_shadow.yaml",
                                         "simple/box_cyl_reflect.yaml", "trimeshes/martini.yaml"};
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
        for (int32_t aa = 0; aa <= 2; aa++) {
            uint8_t want[32], got[32];
            render_hash(scenes[i], RT_KERNEL_PORTABLE, aa == 2 ? 19 : 61, aa, true, want);
            for (rt_kernel k = RT_KERNEL_PORTABLE; k <= RT_KERNEL_AVX512; k++) {
                if (!rtp_kernel_runs(k)) continue;
                render_hash(scenes[i], k, aa == 2 ? 19 : 61, aa, false, got);
                cr_assert(!memcmp(want, got, 32), "%s, aa %d, under %s: another image", scenes[i], aa,
                          rtp_kernel_name(k));
            }
        }
}

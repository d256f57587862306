/* `rtk info`: counts of corpus and hand-written scenes, the SAH cost on a hand-made BVH,
 * and the command's text, JSON and exit codes. */
#include "capture.h"
#include "cli/exit_codes.h"
#include "cli/info_cmd.h"
#include "debug/scene_stats.h"
#include "json_check.h"
#include "reference.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char dir[64], scene_path[128];
static rtp_scene built;
static bool built_open;
static rtp_scene_stats st;

/* A subdivided Cube, a Plane, a sphere and a cylinder; a point, a directional and an area
 * light; a textured material (3x2 texture) and one that is not trace compatible. */
static const char scene_text[] =
    "Textures:\n"
    "    Checks: {Path: assets/checks.png, Bilinear: false}\n"
    "    Unused: {Path: assets/none.png}\n"
    "Materials:\n"
    "    Painted:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 1, G: 1, B: 1}, Use Texture: true, Color Map: Checks}\n"
    "    Plain: {Shader: Blinn-Phong Shader, Uniforms: {}}\n"
    "    Depth: {Shader: Depth Shader, Uniforms: {}}\n"
    "ShaderPrograms:\n"
    "    Depth Shader: {Trace Compatible: false}\n"
    "Root:\n"
    "    Name: Root\n"
    "    Children:\n"
    "        - {Name: Block, Components: {TriangleMesh: {Mesh: Cube, Material: Painted, LoopSubdivision: 2}}}\n"
    "        - {Name: Floor, Components: {Plane: {Material: Plain}}}\n"
    "        - {Name: Ball, Components: {Sphere: {Material: Plain}}}\n"
    "        - {Name: Post, Components: {Cylinder: {Material: Plain}}}\n"
    "        - {Name: Ghost, Components: {Sphere: {Material: Depth}}}\n"
    "        - {Name: Off, Enabled: false, Components: {Sphere: {Material: Plain}}}\n"
    "        - {Name: Bulb, Components: {PointLight: {}}}\n"
    "        - {Name: Sun, Components: {DirectionalLight: {}}}\n"
    "        - {Name: Panel, Components: {AreaLight: {}}}\n";

static void setup(void)
{
    cr_assert(tmpdir_make(dir, sizeof dir, "info"), "cannot create a scratch folder");
    char path[160], err[RTP_ERR_SIZE];
    snprintf(path, sizeof path, "%s/assets", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    snprintf(path, sizeof path, "%s/assets/checks.png", dir);
    uint8_t rgb[3 * 2 * 3] = {255, 255, 255, 0, 0, 0, 255, 255, 255, 0, 0, 0, 255, 255, 255, 0, 0, 0};
    rtp_image texture = {3, 2, rgb};
    cr_assert(rtp_image_write(path, &texture, err, sizeof err), "%s", err);
    snprintf(scene_path, sizeof scene_path, "%s/scene.yaml", dir);
    FILE *f = fopen(scene_path, "wb");
    cr_assert_not_null(f);
    fputs(scene_text, f);
    cr_assert_eq(fclose(f), 0);
    cr_redirect_stderr();
}

static void teardown(void)
{
    if (built_open) rtp_scene_close(&built);
    tmpdir_remove(dir);
}

TestSuite(info, .init = setup, .fini = teardown);

static const char *corpus(const char *name)
{
    static char path[4096];
    snprintf(path, sizeof path, "%s/%s", rt_test_trace_dir(), name);
    return path;
}

static void open_scene(const char *path)
{
    rtp_scene_options opt = {.max_memory = (size_t)1 << 30, .depth = -1, .aa = -1};
    char err[RTP_ERR_SIZE];
    cr_assert_eq(rtp_scene_open(path, &opt, &built, err, sizeof err), RTP_EXIT_OK, "%s", err);
    built_open = true;
    rtp_scene_stats_compute(&built, &st);
}

Test(info, cyl_diffuse_counts)
{
    open_scene(corpus("simple/cyl_diffuse.yaml"));
    /* Root, Render Camera, rotate, rotate, Directional Light, rotate, rotate, Cylinder. */
    cr_expect_eq(st.nodes, 8u);
    cr_expect_eq(st.cylinders, 1u);
    cr_expect_eq(st.spheres + st.meshes + st.triangles, 0u);
    cr_expect_eq(st.lights[RT_LIGHT_DIRECTIONAL], 1u);
    cr_expect_eq(st.lights[RT_LIGHT_POINT] + st.lights[RT_LIGHT_AREA], 0u);
    /* The Textured and Emissive materials use shaders that are not trace compatible. */
    cr_assert_eq(built.scene.material_count, 4u);
    cr_expect_str_eq(built.loaded.material_names[2], "Cylinder");
    cr_expect_eq(built.scene.texture_count, 0u);
    /* One primitive: the root's one child is a leaf; a ray pays the root's visit and one test. */
    cr_expect_eq(st.bvh_nodes, 1u);
    cr_expect_eq(st.bvh_leaves, 1u);
    cr_expect_eq(st.bvh_depth, 2u);
    cr_expect_eq(st.sah_cost, 2.0);
    cr_expect(st.arena_used > 0 && st.arena_used <= st.arena_high_water && st.arena_high_water <= st.arena_capacity);
}

Test(info, texture_reflection_counts)
{
    open_scene(corpus("simple/texture_reflection.yaml"));
    cr_expect_eq(st.spheres, 1u);
    cr_expect_eq(st.meshes, 1u);
    cr_expect_eq(st.triangles, 12u, "the Cube");
    cr_expect_eq(st.lights[RT_LIGHT_DIRECTIONAL], 2u);
    cr_assert_eq(built.scene.texture_count, 1u);
    cr_expect_str_eq(built.loaded.texture_names[0], "texture-checkerboard");
    cr_expect_eq(built.scene.textures[0].width, 542u);
    cr_expect_eq(built.scene.textures[0].height, 538u);
    cr_expect(st.bvh_nodes < st.bvh_leaves && st.bvh_leaves <= (RT_BVH_WIDTH - 1) * st.bvh_nodes + 1,
              "a tree of 2 to RT_BVH_WIDTH children per node");
    cr_expect(st.sah_cost >= 1.0 && st.sah_cost <= st.bvh_nodes + 13.0, "SAH cost %g", st.sah_cost);
}

Test(info, hand_written_scene_counts)
{
    open_scene(scene_path);
    cr_expect_eq(st.nodes, 9u, "Root and its children but Off");
    cr_expect_eq(st.spheres, 1u, "Ghost's material is not traced");
    cr_expect_eq(st.cylinders, 1u);
    cr_expect_eq(st.meshes, 2u);
    cr_expect_eq(st.triangles_loaded, 12u + 2u);
    cr_expect_eq(st.triangles, 12u * 16u + 2u, "two Loop levels make 16 triangles of each");
    cr_expect_eq(st.lights[RT_LIGHT_POINT], 1u);
    cr_expect_eq(st.lights[RT_LIGHT_DIRECTIONAL], 1u);
    cr_expect_eq(st.lights[RT_LIGHT_AREA], 1u);
    cr_assert_eq(built.scene.material_count, 2u);
    cr_expect_str_eq(built.loaded.material_names[0], "Painted");
    cr_expect_str_eq(built.loaded.material_names[1], "Plain");
    cr_assert_eq(built.scene.texture_count, 1u, "Unused is not read");
    cr_expect_str_eq(built.loaded.texture_names[0], "Checks");
    cr_expect_eq(built.scene.textures[0].width, 3u);
    cr_expect_eq(built.scene.textures[0].height, 2u);
    cr_expect_not(built.scene.textures[0].bilinear);
    cr_expect(st.bvh_nodes < st.bvh_leaves && st.bvh_leaves <= (RT_BVH_WIDTH - 1) * st.bvh_nodes + 1);
}

Test(info, sah_cost_of_a_hand_made_tree)
{
    /* A root over [0,1]^3 (area 6) with two leaf children [0,0.5]x[0,1]^2 and
     * [0.5,1]x[0,1]^2 (area 4 each) of 1 and 2 primitives: 1 visit + 4/6 * 1 test +
     * 4/6 * 2 tests = 3. */
    int g = rt_bound_grid(RT_ONE);
    rt_bound o = rt_bound_below(RT_ZERO, g), h = rt_bound_below(RT_C(0.5), g), l = rt_bound_below(RT_ONE, g);
    rt_bound e = rt_bound_below(RT_ZERO, g); /* unused slots */
    rt_bvh_node root = {{{o, h, e, e}, {o, o, e, e}, {o, o, e, e}, {h, l, e, e}, {l, l, e, e}, {l, l, e, e}},
                        {0, 1, 0, 0},
                        {1, 2, RT_BVH_NO_CHILD, RT_BVH_NO_CHILD}};
    rt_bvh bvh = {&root, 1, NULL, 2, g, RT_ONE, RT_KERNEL_PORTABLE};
    cr_expect_float_eq(rtp_scene_stats_sah_cost(&bvh, 3), 3.0, 1e-12);
    rt_bvh_node lone = {{{o}, {o}, {o}, {l}, {l}, {l}}, {0}, {2, RT_BVH_NO_CHILD, RT_BVH_NO_CHILD, RT_BVH_NO_CHILD}};
    rt_bvh leaf = {&lone, 1, NULL, 2, g, RT_ONE, RT_KERNEL_PORTABLE};
    cr_expect_float_eq(rtp_scene_stats_sah_cost(&leaf, 2), 3.0, 1e-12,
                       "a lone leaf: the root's visit and one test per primitive");
    cr_expect_eq(rtp_scene_stats_sah_cost(&bvh, 0), 0.0, "no primitives");
}

/* Runs `rtk info` with the arguments up to NULL; its output in *out. */
static int info_cmd(char **out, ...)
{
    char *argv[16] = {"info"};
    int argc = 1;
    va_list ap;
    va_start(ap, out);
    for (const char *s; argc < 15 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    va_end(ap);
    return capture_stdout(rtp_cmd_info, argc, argv, out);
}

Test(info, text_output)
{
    char *out;
    cr_assert_eq(info_cmd(&out, scene_path, NULL), RTP_EXIT_OK);
    cr_assert_not_null(out);
    cr_expect(strstr(out, "nodes       9 enabled\n") != NULL, "%s", out);
    cr_expect(strstr(out, "primitives  1 sphere, 1 cylinder, 2 meshes with 194 triangles (14 before subdivision)\n"),
              "%s", out);
    cr_expect(strstr(out, "lights      1 point, 1 directional, 1 area\n") != NULL, "%s", out);
    cr_expect(strstr(out, "materials   2 trace compatible\n              Painted\n              Plain\n"), "%s", out);
    cr_expect(strstr(out, "              Checks: 3x2, nearest\n") != NULL, "%s", out);
    cr_expect(strstr(out, "camera      perspective, vertical FOV 50 degrees, 1280x720 px") != NULL, "%s", out);
    cr_expect(strstr(out, "trace       maximum depth 5, shadows none,") != NULL, "%s", out);
    cr_expect(strstr(out, "bvh         ") != NULL && strstr(out, "SAH cost") != NULL, "%s", out);
    cr_expect(strstr(out, "memory      arena ") != NULL, "%s", out);
    free(out);
}

Test(info, json_parses_and_counts)
{
    static const char *const scenes[] = {"simple/cyl_diffuse.yaml", "simple/texture_reflection.yaml",
                                         "trimeshes/chess.yaml", "more/cornell_ray.yaml"};
    char *out;
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(info_cmd(&out, corpus(scenes[i]), "--json", NULL), RTP_EXIT_OK, "%s", scenes[i]);
        cr_expect(json_is_valid(out), "%s: not JSON:\n%s", scenes[i], out);
        free(out);
    }
    cr_assert_eq(info_cmd(&out, "--json", scene_path, NULL), RTP_EXIT_OK);
    cr_expect(json_is_valid(out), "%s", out);
    cr_expect(strstr(out, "\"primitives\": {\"spheres\": 1, \"cylinders\": 1, \"meshes\": 2, \"triangles\": 194, "
                          "\"triangles_before_subdivision\": 14}"),
              "%s", out);
    cr_expect(strstr(out, "\"textures\": [{\"name\": \"Checks\", \"width\": 3, \"height\": 2, \"bilinear\": false}]"),
              "%s", out);
    cr_expect(strstr(out, "\"materials\": [\"Painted\", \"Plain\"]") != NULL, "%s", out);
    free(out);
}

Test(info, errors)
{
    char missing[160], *out;
    snprintf(missing, sizeof missing, "%s/none.yaml", dir);
    cr_expect_eq(info_cmd(&out, missing, NULL), RTP_EXIT_INPUT);
    free(out);
    cr_expect_eq(info_cmd(&out, NULL), RTP_EXIT_USAGE);
    free(out);
    cr_expect_eq(info_cmd(&out, scene_path, scene_path, NULL), RTP_EXIT_USAGE);
    free(out);
    cr_expect_eq(info_cmd(&out, scene_path, "--bogus", NULL), RTP_EXIT_USAGE);
    free(out);
    cr_expect_eq(info_cmd(&out, scene_path, "--max-memory", "1K", NULL), RTP_EXIT_MEMORY);
    free(out);
}

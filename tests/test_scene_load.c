/* The YAML scene loader: facts of the corpus scenes, the missing-asset errors, and
 * small hand-written scenes for defaults, quirks and malformed input. */
#include "load/scene_load.h"
#include "reference.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char dir[64];
static char scene_path[256];
static char err[RTP_ERR_SIZE];
static rtp_loaded_scene scene;

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "scene"), "cannot create a scratch folder"); }

static void teardown(void)
{
    rtp_scene_unload(&scene);
    tmpdir_remove(dir);
}

TestSuite(scene_load, .init = setup, .fini = teardown);

/* Writes text to dir/rel, creating the folders on the way. */
static const char *put_file(const char *rel, const char *text)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    for (char *p = path + strlen(dir) + 1; (p = strchr(p, '/')) != NULL; p++) {
        *p = '\0';
        mkdir(path, 0777);
        *p = '/';
    }
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot create %s", path);
    cr_assert_eq(fwrite(text, 1, strlen(text), f), strlen(text));
    cr_assert_eq(fclose(f), 0);
    return path;
}

/* Writes a scene to dir/rel and loads it into `scene`, the message (if any) in err. */
static bool load_as(const char *rel, const char *yaml, const char *assets_root)
{
    rtp_scene_unload(&scene);
    snprintf(scene_path, sizeof scene_path, "%s", put_file(rel, yaml));
    return rtp_scene_load(scene_path, assets_root, &scene, err, sizeof err);
}

static bool load(const char *yaml) { return load_as("scene.yaml", yaml, NULL); }

static bool load_corpus(const char *rel)
{
    rtp_scene_unload(&scene);
    snprintf(scene_path, sizeof scene_path, "%s/%s", rt_test_trace_dir(), rel);
    return rtp_scene_load(scene_path, NULL, &scene, err, sizeof err);
}

/* Asserts that loading failed with exactly "<scene>:<line>:<col>: <message>" and left nothing behind. */
static void expect_error(int line, int col, const char *message)
{
    static const rtp_loaded_scene empty;
    char want[RTP_ERR_SIZE];
    snprintf(want, sizeof want, "%s:%d:%d: %s", scene_path, line, col, message);
    cr_assert_str_eq(err, want);
    cr_assert(memcmp(&scene, &empty, sizeof scene) == 0, "a failed load must leave the scene empty");
}

static void expect_load_error(const char *yaml, int line, int col, const char *message)
{
    cr_assert_not(load(yaml), "loaded a scene that should fail with: %s", message);
    expect_error(line, col, message);
}

static double byte(int b) { return b / 255.0; }

/* ---- The corpus ---- */

typedef struct {
    const char *file;
    uint32_t materials, objects, lights, meshes, textures, nodes;
    uint32_t width, shadows, max_depth;
} corpus_facts;

/* Counted independently from the files: traced materials, enabled geometry using them. */
static const corpus_facts corpus[] = {
    {"simple/box.yaml", 2, 1, 1, 1, 0, 4, 512, 0, 3},
    {"simple/box_dist_atten.yaml", 2, 1, 1, 1, 0, 4, 512, 0, 3},
    {"simple/box_cyl_opaque_shadow.yaml", 4, 2, 1, 1, 0, 6, 512, 2, 3},
    {"simple/box_cyl_trans_shadow.yaml", 4, 2, 1, 1, 0, 6, 512, 2, 3},
    {"simple/box_cyl_reflect.yaml", 4, 2, 2, 1, 0, 7, 512, 2, 3},
    {"simple/cube_transparent.yaml", 3, 1, 2, 1, 0, 8, 512, 2, 3},
    {"simple/cyl_emissive.yaml", 4, 1, 0, 0, 0, 5, 512, 2, 3},
    {"simple/cyl_ambient.yaml", 4, 1, 1, 0, 0, 6, 512, 0, 3},
    {"simple/cyl_diffuse.yaml", 4, 1, 1, 0, 0, 8, 512, 2, 3},
    {"simple/cyl_diff_spec.yaml", 4, 1, 1, 0, 0, 5, 512, 0, 3},
    {"simple/cylinder_refract.yaml", 5, 3, 1, 0, 0, 18, 512, 2, 3},
    {"simple/sphere_refract.yaml", 5, 3, 1, 0, 0, 15, 512, 2, 3},
    {"simple/poly_sphere.yaml", 3, 1, 1, 1, 0, 4, 512, 2, 3},
    {"simple/texture_reflection.yaml", 4, 2, 2, 1, 1, 9, 512, 2, 3},
    {"trimeshes/box_sphere.yaml", 4, 2, 3, 1, 0, 9, 512, 2, 3},
    {"trimeshes/chess.yaml", 7, 8, 2, 5, 0, 16, 512, 2, 3},
    {"trimeshes/martini.yaml", 3, 1, 2, 1, 0, 6, 512, 2, 3},
    {"trimeshes/revolution.yaml", 3, 1, 2, 1, 0, 6, 512, 2, 3},
    {"trimeshes/sculpt.yaml", 4, 2, 3, 2, 0, 8, 512, 2, 3},
    {"more/lecture.yaml", 5, 3, 2, 1, 1, 10, 512, 2, 3},
    {"more/chess_mcpt.yaml", 7, 7, 4, 3, 0, 15, 512, 2, 5},
    {"more/cornell_ray.yaml", 5, 7, 2, 2, 0, 12, 512, 2, 5},
};

Test(scene_load, every_corpus_scene_with_its_assets_loads)
{
    for (size_t i = 0; i < sizeof corpus / sizeof corpus[0]; i++) {
        const corpus_facts *c = &corpus[i];
        cr_assert(load_corpus(c->file), "%s", err);
        const rt_scene_desc *d = &scene.desc;
        cr_expect_eq(d->material_count, c->materials, "%s: materials", c->file);
        cr_expect_eq(d->object_count, c->objects, "%s: objects", c->file);
        cr_expect_eq(d->light_count, c->lights, "%s: lights", c->file);
        cr_expect_eq(d->mesh_count, c->meshes, "%s: meshes", c->file);
        cr_expect_eq(d->texture_count, c->textures, "%s: textures", c->file);
        cr_expect_eq(scene.node_count, c->nodes, "%s: nodes", c->file);
        cr_expect_eq(d->camera.width, c->width, "%s: width", c->file);
        cr_expect_eq(d->camera.height, c->width, "%s: height", c->file);
        cr_expect_eq(d->camera.trace.shadows, c->shadows, "%s: shadows", c->file);
        cr_expect_eq(d->camera.trace.max_depth, c->max_depth, "%s: depth", c->file);
        for (uint32_t o = 0; o < d->object_count; o++) {
            cr_expect_lt(d->objects[o].material, d->material_count, "%s: object %u", c->file, o);
            cr_expect_lt(d->objects[o].source, scene.node_count, "%s: object %u", c->file, o);
            if (d->objects[o].kind == RT_SHAPE_MESH) cr_expect_lt(d->objects[o].mesh, d->mesh_count);
        }
    }
}

Test(scene_load, lecture_materials_lights_and_texture)
{
    cr_assert(load_corpus("more/lecture.yaml"), "%s", err);
    const rt_scene_desc *d = &scene.desc;
    /* Traced materials in file order: Blinn-Phong Material, Box, Green, Purple, Toon Material. */
    const rt_material *blinn = &d->materials[0], *box = &d->materials[1], *green = &d->materials[2];
    cr_expect_eq(blinn->diffuse.color.x, byte(191)); /* 0.75 */
    cr_expect_eq(blinn->diffuse.color.y, 0.0);
    cr_expect_eq(blinn->specular.color.z, byte(127)); /* 0.5 */
    cr_expect_eq(blinn->diffuse.texture, RT_NO_TEXTURE);
    cr_expect_eq(green->transmittance.color.y, byte(204)); /* 0.8 */
    cr_expect_eq(green->diffuse.color.y, byte(63));        /* 0.25098f * 255.0f = 63.9999, truncated */
    cr_expect_eq(green->index_of_refraction, 1.5);
    cr_expect_eq(green->shininess, 256.0);
    cr_expect_eq(box->diffuse.texture, 0u);
    cr_expect_eq(box->shininess, 0.0);
    cr_expect_eq(d->textures[0].width, 542u);
    cr_expect_eq(d->textures[0].height, 538u);
    cr_expect(d->textures[0].bilinear);

    cr_assert_eq(d->light_count, 2u);
    cr_expect_eq(d->lights[0].kind, RT_LIGHT_DIRECTIONAL);
    cr_expect_eq(d->lights[0].color.x, 1.25); /* Intensity Multiplier 1.25 x Color 1 */
    cr_expect_eq(d->lights[0].color.z, 1.25);
    cr_expect_eq(d->lights[1].kind, RT_LIGHT_POINT);
    cr_expect_eq(d->lights[1].atten_const, 0.5);
    cr_expect_eq(d->lights[1].atten_linear, 0.25);
    cr_expect_eq(d->lights[1].atten_quad, 0.005);
    cr_expect_eq(d->lights[1].world.translation.y, 10.0);

    cr_assert_eq(d->object_count, 3u);
    cr_expect_eq(d->objects[0].kind, RT_SHAPE_MESH);
    cr_expect_eq(d->objects[0].material, 1u);
    cr_expect_eq(d->meshes[d->objects[0].mesh].triangle_count, 12u); /* the built-in Cube */
    cr_expect_str_eq(scene.node_names[d->objects[1].source], "Sphere 1");
    cr_expect_eq(d->objects[1].kind, RT_SHAPE_SPHERE);
    cr_expect_eq(d->objects[1].material, 3u); /* Purple */
    cr_expect_eq(d->objects[1].world.translation.x, -2.5);
    cr_expect_eq(d->objects[1].world.linear.m[0][0], 4.0);
    cr_expect_eq(d->camera.fov_degrees, 53.13);
    cr_expect_eq(d->camera.world.translation.z, 15.0);
}

Test(scene_load, box_has_the_trace_defaults_for_missing_keys)
{
    cr_assert(load_corpus("simple/box.yaml"), "%s", err);
    const rt_trace_settings *t = &scene.desc.camera.trace;
    cr_expect_eq(t->shadows, 0u);
    cr_expect(t->reflections);
    cr_expect(t->refractions);
    cr_expect_eq(t->max_depth, 3u);
}

Test(scene_load, chess_mcpt_crlf_monte_carlo_settings_and_area_lights)
{
    cr_assert(load_corpus("more/chess_mcpt.yaml"), "%s", err);
    const rt_camera_desc *c = &scene.desc.camera;
    cr_expect_eq(c->trace.samples_per_pixel_index, 3u);
    cr_expect_eq(c->trace.monte_carlo, 2u);
    cr_expect_eq(c->trace.aperture_size, 0.3);
    cr_expect_eq(c->trace.focus_distance, 5.25);
    cr_expect_not(c->trace.caustics);
    cr_expect_eq(c->fov_degrees, 45.0);
    int area = 0;
    for (uint32_t i = 0; i < scene.desc.light_count; i++) area += scene.desc.lights[i].kind == RT_LIGHT_AREA;
    cr_expect_eq(area, 3);
}

Test(scene_load, cornell_planes_share_the_square_mesh)
{
    cr_assert(load_corpus("more/cornell_ray.yaml"), "%s", err);
    const rt_scene_desc *d = &scene.desc;
    int planes = 0;
    uint32_t square = UINT32_MAX;
    for (uint32_t i = 0; i < d->object_count; i++) {
        if (strncmp(scene.node_names[d->objects[i].source], "Plane", 5) != 0) continue;
        cr_expect_eq(d->objects[i].kind, RT_SHAPE_MESH);
        if (square == UINT32_MAX) square = d->objects[i].mesh;
        cr_expect_eq(d->objects[i].mesh, square);
        planes++;
    }
    cr_expect_eq(planes, 5);
}

Test(scene_load, chess_reads_each_mesh_file_once)
{
    cr_assert(load_corpus("trimeshes/chess.yaml"), "%s", err);
    cr_expect_eq(scene.desc.mesh_count, 5u); /* Cube, knight, pawn, table1, table2 */
}

Test(scene_load, dragon_reports_the_missing_mesh)
{
    cr_assert_not(load_corpus("trimeshes/dragon.yaml"));
    cr_expect(strstr(err, "assets/dragon.ply") != NULL, "%s", err);
    cr_expect(strstr(err, "Meshes/dragon/Path: cannot read '") != NULL, "%s", err);
    cr_expect(strstr(err, "No such file or directory") != NULL, "%s", err);
    expect_error(12, 15, strstr(err, "Meshes/"));
}

Test(scene_load, revolution_texture_reports_the_missing_texture)
{
    cr_assert_not(load_corpus("trimeshes/revolution_texture.yaml"));
    cr_expect(strstr(err, "Textures/marble/Path: cannot read '") != NULL, "%s", err);
    cr_expect(strstr(err, "assets/marble.png") != NULL, "%s", err);
}

/* ---- Hand-written scenes ---- */

#define RED_MATERIAL                       \
    "Materials:\n"                         \
    "    Red:\n"                           \
    "        Shader: Blinn-Phong Shader\n" \
    "        Uniforms:\n"                  \
    "            Diffuse: {Color: {A: 1, R: 0.75, G: 0.7, B: 0.12}}\n"

#define ONE_SPHERE              \
    "Root:\n"                   \
    "    Name: Root\n"          \
    "    Components: {}\n"      \
    "    Children:\n"           \
    "        -   Name: Ball\n"  \
    "            Components:\n" \
    "                Sphere: {Material: Red}\n"

Test(scene_load, minimal_scene_gets_the_default_camera)
{
    cr_assert(load(RED_MATERIAL ONE_SPHERE), "%s", err);
    const rt_scene_desc *d = &scene.desc;
    cr_assert_eq(d->object_count, 1u);
    cr_expect_eq(d->light_count, 0u);
    cr_expect_eq(d->objects[0].source, 1u);
    cr_expect_str_eq(scene.node_names[0], "Root");
    cr_expect_str_eq(scene.node_names[1], "Ball");
    const rt_camera_desc *c = &d->camera;
    cr_expect_eq(c->width, 1280u);
    cr_expect_eq(c->height, 720u);
    cr_expect_eq(c->fov_degrees, 50.0);
    cr_expect(c->perspective);
    cr_expect_eq(c->ortho_width, 5.0);
    cr_expect_eq(c->world.translation.z, 2.5);
    cr_expect_eq(c->world.linear.m[1][1], 1.0);
    cr_expect_eq(c->trace.max_depth, 5u);
    cr_expect_eq(c->trace.shadows, 0u);
    cr_expect(c->trace.reflections && c->trace.refractions);
    cr_expect_eq(c->trace.samples_per_pixel_index, 0u);
    cr_expect_eq(c->trace.monte_carlo, 0u);
    cr_expect(c->trace.diffuse_reflection && c->trace.caustics && c->trace.random_single_branching);
    cr_expect_eq(c->trace.focus_distance, 1.0);
    cr_expect_eq(c->trace.aperture_size, 0.0);
}

Test(scene_load, material_colours_are_quantised_and_channels_default)
{
    cr_assert(load(RED_MATERIAL ONE_SPHERE), "%s", err);
    const rt_material *m = &scene.desc.materials[0];
    cr_expect_eq(m->diffuse.color.x, byte(191));
    cr_expect_eq(m->diffuse.color.y, byte(178));
    cr_expect_eq(m->diffuse.color.z, byte(30));
    cr_expect_eq(m->specular.color.x, byte(127)); /* default 0.5 */
    cr_expect_eq(m->emissive.color.y, 0.0);
    cr_expect_eq(m->transmittance.color.z, 0.0);
    cr_expect_eq(m->specular.texture, RT_NO_TEXTURE);
    cr_expect_eq(m->shininess, 20.0);
    cr_expect_eq(m->index_of_refraction, 1.0);
}

Test(scene_load, out_of_range_colours_are_clamped_before_quantising)
{
    cr_assert(load("Materials:\n"
                   "    Red:\n"
                   "        Shader: Blinn-Phong Shader\n"
                   "        Uniforms:\n"
                   "            Emissive: {Color: {R: 1.5, G: -0.25, B: 1}}\n"
                   "            Shininess: 5e-05\n"
                   "            IndexOfRefraction: 2\n" ONE_SPHERE),
              "%s", err);
    const rt_material *m = &scene.desc.materials[0];
    cr_expect_eq(m->emissive.color.x, 1.0);
    cr_expect_eq(m->emissive.color.y, 0.0);
    cr_expect_eq(m->emissive.color.z, 1.0);
    cr_expect_eq(m->shininess, 5e-05);
    cr_expect_eq(m->index_of_refraction, 2.0);
}

Test(scene_load, crlf_without_final_newline)
{
    const char *lf = RED_MATERIAL ONE_SPHERE;
    char crlf[2048];
    size_t n = 0;
    for (const char *p = lf; *p; p++) {
        if (*p == '\n') crlf[n++] = '\r';
        crlf[n++] = *p;
    }
    crlf[n - 2] = '\0'; /* drop the final CRLF */
    cr_assert(load(crlf), "%s", err);
    cr_expect_eq(scene.desc.object_count, 1u);
    cr_expect_eq(scene.desc.materials[0].diffuse.color.x, byte(191));
}

Test(scene_load, sections_are_read_in_the_skeleton_order)
{
    /* Root first and the shader program after the material that names it. */
    cr_assert(load(ONE_SPHERE "Materials:\n"
                              "    Red: {Shader: Mine}\n"
                              "ShaderPrograms:\n"
                              "    Mine: {Trace Compatible: true}\n"),
              "%s", err);
    cr_expect_eq(scene.desc.object_count, 1u);
}

Test(scene_load, geometry_with_untraced_materials_is_left_out)
{
    cr_assert(load("ShaderPrograms:\n"
                   "    Flat: {Trace Compatible: false}\n"
                   "    Toon Shader: {Vertex: x.vert}\n"
                   "Materials:\n"
                   "    A: {Shader: Flat}\n"
                   "    B: {Shader: Undefined Shader}\n"
                   "    C: {Shader: Toon Shader}\n"
                   "    D: {Shader: Blinn-Phong Shader}\n"
                   "Root:\n"
                   "    Name: Root\n"
                   "    Components:\n"
                   "        Transform: {}\n"
                   "    Children:\n"
                   "        - {Name: a, Components: {Sphere: {Material: A}}}\n"
                   "        - {Name: b, Components: {TriangleMesh: {Material: B, Mesh: Nowhere}}}\n"
                   "        - {Name: c, Components: {Cylinder: {Material: C}}}\n"
                   "        - {Name: d, Components: {Plane: {Material: D}}}\n"
                   "        - {Name: e, Components: {Sphere: {Material: Not Defined}}}\n"),
              "%s", err);
    const rt_scene_desc *d = &scene.desc;
    cr_assert_eq(d->material_count, 2u);
    cr_assert_eq(d->object_count, 2u);
    cr_expect_eq(d->objects[0].kind, RT_SHAPE_CYLINDER);
    cr_expect_eq(d->objects[0].material, 0u);
    cr_expect_str_eq(scene.node_names[d->objects[0].source], "c");
    cr_expect_eq(d->objects[1].kind, RT_SHAPE_MESH);
    cr_expect_eq(d->objects[1].material, 1u);
    cr_expect_eq(d->mesh_count, 1u);
}

Test(scene_load, unknown_keys_and_other_years_keys_are_ignored)
{
    cr_assert(load("Name: test\n"
                   "Something Else: [1, 2]\n"
                   "Cubemaps: {Sky: {Path: assets/nowhere_ft.png}}\n"
                   "Materials:\n"
                   "    Red:\n"
                   "        Shader: Blinn-Phong Shader\n"
                   "        Colour: blue\n"
                   "        Uniforms: {ShadowBias: 0.01, Shininess: 3, Glow: {Color: 7}}\n"
                   "Root:\n"
                   "    Name: Root\n"
                   "    Layer: 4\n"
                   "    Components:\n"
                   "        Transform: {Shear: {X: 1}}\n"
                   "        EnvironmentMap: {Resolution (px): 400}\n"
                   "        ParticleSystem: {Rate: 3}\n"
                   "        Camera:\n"
                   "            Near Plane: 0.1\n"
                   "            Far Plane: 100\n"
                   "            Trace Debugger: {Show Shadow Rays: true}\n"
                   "            Trace: {Enable Shadows: false, Shadows: 1, Sample Count Type: 2}\n"
                   "        Sphere: {Material: Red, Quality: 4, Radius: 3}\n"),
              "%s", err);
    cr_expect_eq(scene.desc.object_count, 1u);
    cr_expect_eq(scene.desc.materials[0].shininess, 3.0);
    cr_expect_eq(scene.desc.camera.trace.shadows, 1u);
}

Test(scene_load, disabled_subtrees_are_skipped)
{
    cr_assert(load(RED_MATERIAL "Root:\n"
                                "    Name: Root\n"
                                "    Children:\n"
                                "        -   Name: Off\n"
                                "            Enabled: false\n"
                                "            Components:\n"
                                "                Camera: {Render Width (px): 64}\n"
                                "                PointLight: {}\n"
                                "            Children:\n"
                                "                - {Name: Inner, Components: {Sphere: {Material: Red}}}\n"
                                "        -   Name: On\n"
                                "            Enabled: true\n"
                                "            Components:\n"
                                "                Camera: {Render Width (px): 32}\n"
                                "                Cylinder: {Material: Red}\n"),
              "%s", err);
    const rt_scene_desc *d = &scene.desc;
    cr_expect_eq(d->object_count, 1u);
    cr_expect_eq(d->objects[0].kind, RT_SHAPE_CYLINDER);
    cr_expect_eq(d->light_count, 0u);
    cr_expect_eq(d->camera.width, 32u);
    cr_assert_eq(scene.node_count, 2u);
    cr_expect_str_eq(scene.node_names[1], "On");
}

Test(scene_load, first_camera_in_depth_first_order_wins)
{
    cr_assert(load("Root:\n"
                   "    Name: Root\n"
                   "    Children:\n"
                   "        -   Name: A\n"
                   "            Children:\n"
                   "                - {Name: A1, Components: {Camera: {Render Width (px): 11}}}\n"
                   "        -   {Name: B, Components: {Camera: {Render Width (px): 22}}}\n"),
              "%s", err);
    cr_expect_eq(scene.desc.camera.width, 11u);
}

Test(scene_load, transforms_compose_from_the_root)
{
    cr_assert(load(RED_MATERIAL "Root:\n"
                                "    Name: Root\n"
                                "    Components:\n"
                                "        Transform: {Translation: {X: 1}, Scale: {X: 2, Y: 2, Z: 2}}\n"
                                "    Children:\n"
                                "        -   Name: Child\n"
                                "            Components:\n"
                                "                Transform: {Translation: {X: 1, Y: 0.5}, Rotation: {Z: 90}}\n"
                                "                Sphere: {Material: Red}\n"),
              "%s", err);
    const rt_affine *w = &scene.desc.objects[0].world;
    cr_expect_eq(w->translation.x, 3.0); /* 1 + 2 * 1 */
    cr_expect_eq(w->translation.y, 1.0);
    cr_expect_eq(w->translation.z, 0.0);
    /* Local x maps to world +y (rotation by 90 degrees about Z), scaled by the parent's 2. */
    cr_expect_float_eq(w->linear.m[1][0], 2.0, 1e-12);
    cr_expect_float_eq(w->linear.m[0][1], -2.0, 1e-12);
    cr_expect_float_eq(w->linear.m[0][0], 0.0, 1e-12);
    cr_expect_eq(w->linear.m[2][2], 2.0);
}

Test(scene_load, lights_defaults_and_intensity_multiplier)
{
    cr_assert(load("Root:\n"
                   "    Name: Root\n"
                   "    Children:\n"
                   "        - {Name: p, Components: {PointLight: {}}}\n"
                   "        - {Name: d, Components: {DirectionalLight: {Color: {R: 0.5, G: 0.25, B: 2},\n"
                   "                                                    Intensity Multiplier: 2}}}\n"
                   "        - {Name: a, Components: {AreaLight: {Ambient: {R: 0.1}, Quad Atten: 0,\n"
                   "                                             Const Atten: 1, Linear Atten: 0.5}}}\n"),
              "%s", err);
    const rt_light_desc *l = scene.desc.lights;
    cr_assert_eq(scene.desc.light_count, 3u);
    cr_expect_eq(l[0].kind, RT_LIGHT_POINT);
    cr_expect_eq(l[0].color.y, 1.0);
    cr_expect_eq(l[0].ambient.x, 0.0);
    cr_expect_eq(l[0].atten_const, 0.0);
    cr_expect_eq(l[0].atten_linear, 0.0);
    cr_expect_eq(l[0].atten_quad, 0.2);
    cr_expect_eq(l[1].kind, RT_LIGHT_DIRECTIONAL);
    cr_expect_eq(l[1].color.x, 1.0);
    cr_expect_eq(l[1].color.y, 0.5);
    cr_expect_eq(l[1].color.z, 4.0); /* not clamped or quantised */
    cr_expect_eq(l[2].kind, RT_LIGHT_AREA);
    cr_expect_eq(l[2].ambient.x, 0.1);
    cr_expect_eq(l[2].atten_const, 1.0);
    cr_expect_eq(l[2].atten_linear, 0.5);
    cr_expect_eq(l[2].atten_quad, 0.0);
}

Test(scene_load, numbers_in_any_spelling)
{
    cr_assert(
        load("Root:\n"
             "    Name: Root\n"
             "    Components:\n"
             "        Camera:\n"
             "            FOV: \"45\"\n"
             "            Render Width (px): 640.0\n"
             "            Render Height (px): 16384\n"
             "            Orthographic View Width: 1e1\n"
             "            Trace:\n"
             "                Shadows: 7\n"
             "                Samples Per Pixel: 9\n"
             "                Monte Carlo: 2\n"
             "                Focus Distance: {Interpolation: 0, FrameTimes: [0, 1], FrameValues: [-7.5e-09, 3]}\n"
             "                Maximum Recursion Depth: 0\n"),
        "%s", err);
    const rt_camera_desc *c = &scene.desc.camera;
    cr_expect_eq(c->fov_degrees, 45.0);
    cr_expect_eq(c->width, 640u);
    cr_expect_eq(c->height, 16384u);
    cr_expect_eq(c->ortho_width, 10.0);
    cr_expect_eq(c->trace.shadows, 2u); /* clamped to the last choice */
    cr_expect_eq(c->trace.samples_per_pixel_index, 7u);
    cr_expect_eq(c->trace.monte_carlo, 2u);
    cr_expect_eq(c->trace.focus_distance, -7.5e-09);
    cr_expect_eq(c->trace.max_depth, 0u);
}

Test(scene_load, loop_subdivision_up_to_five)
{
    cr_assert(load(RED_MATERIAL "Root:\n"
                                "    Name: Root\n"
                                "    Components:\n"
                                "        TriangleMesh: {Material: Red, Mesh: Cube, LoopSubdivision: 5}\n"),
              "%s", err);
    cr_expect_eq(scene.desc.objects[0].subdivision, 5u);
    expect_load_error(RED_MATERIAL "Root:\n"
                                   "    Name: Root\n"
                                   "    Components:\n"
                                   "        TriangleMesh: {Material: Red, Mesh: Cube, LoopSubdivision: 6}\n",
                      9, 68, "Root/Components/TriangleMesh/LoopSubdivision: expected an integer from 0 to 5, got '6'");
}

Test(scene_load, mesh_files_are_read_once_and_resolved_from_the_assets_folder)
{
    put_file("assets/tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                               "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    cr_assert(load_as("assets/scenes/tri.yaml",
                      RED_MATERIAL "Meshes:\n"
                                   "    One: {Path: assets/tri.ply}\n"
                                   "    Two: {Path: assets/tri.ply}\n"
                                   "    Unused: {Path: assets/missing.ply}\n"
                                   "Root:\n"
                                   "    Name: Root\n"
                                   "    Children:\n"
                                   "        - {Name: a, Components: {TriangleMesh: {Material: Red, Mesh: One}}}\n"
                                   "        - {Name: b, Components: {TriangleMesh: {Material: Red, Mesh: Two}}}\n"
                                   "        - {Name: c, Components: {TriangleMesh: {Material: Red, Mesh: One}}}\n",
                      NULL),
              "%s", err);
    const rt_scene_desc *d = &scene.desc;
    cr_assert_eq(d->mesh_count, 2u);
    cr_expect_eq(d->meshes[0].triangle_count, 1u);
    cr_expect_eq(d->meshes[0].positions, d->meshes[1].positions);
    cr_expect_eq(d->objects[0].mesh, d->objects[2].mesh);
    cr_expect_neq(d->objects[0].mesh, d->objects[1].mesh);
}

Test(scene_load, missing_texture_names_its_key_and_the_resolved_path)
{
    const char *yaml = "Textures:\n"
                       "    Unused: {Path: assets/also_missing.png}\n"
                       "    Wood: {Bilinear: false, Path: assets/missing.png}\n"
                       "Materials:\n"
                       "    Red:\n"
                       "        Shader: Blinn-Phong Shader\n"
                       "        Uniforms:\n"
                       "            Diffuse: {Color Map: Wood, Use Texture: true}\n" ONE_SPHERE;
    cr_assert_not(load_as("assets/scenes/tex.yaml", yaml, NULL));
    char message[512];
    snprintf(message, sizeof message,
             "Textures/Wood/Path: cannot read '%s/assets/missing.png': No such file or directory", dir);
    expect_error(3, 35, message);

    cr_assert_not(load_as("scene.yaml", yaml, "/nonexistent/root"));
    expect_error(3, 35,
                 "Textures/Wood/Path: cannot read '/nonexistent/root/assets/missing.png': No such file or directory");
}

Test(scene_load, unused_textures_are_not_read)
{
    cr_assert(load("Textures:\n"
                   "    Wood: {Path: assets/missing.png}\n"
                   "Materials:\n"
                   "    Red:\n"
                   "        Shader: Blinn-Phong Shader\n"
                   "        Uniforms:\n"
                   "            Diffuse: {Color Map: Wood, Use Texture: false}\n"
                   "            Specular: {Color Map: \"\", Use Texture: true}\n"
                   "    Flat:\n"
                   "        Shader: Textured Shader\n"
                   "        Uniforms:\n"
                   "            Diffuse: {Color Map: Wood, Use Texture: true}\n" ONE_SPHERE),
              "%s", err);
    cr_expect_eq(scene.desc.texture_count, 0u);
    cr_expect_eq(scene.desc.materials[0].diffuse.texture, RT_NO_TEXTURE);
    cr_expect_eq(scene.desc.materials[0].specular.texture, RT_NO_TEXTURE);
}

/* ---- Malformed input ---- */

Test(scene_load, wrong_types_name_the_key_path_and_place)
{
    expect_load_error("Materials:\n"
                      "    Red:\n"
                      "        Shader: Blinn-Phong Shader\n"
                      "        Uniforms:\n"
                      "            Shininess: [1, 2]\n" ONE_SPHERE,
                      5, 24, "Materials/Red/Uniforms/Shininess: expected a finite number, got a list");
    expect_load_error(ONE_SPHERE "Materials: [Red]\n", 8, 12, "Materials: expected a map, got a list");
    expect_load_error("Root:\n"
                      "    Name: Root\n"
                      "    Children: {Name: x}\n",
                      3, 15, "Root/Children: expected a list, got a map");
    expect_load_error("Root:\n"
                      "    Name: Root\n"
                      "    Enabled: yes\n",
                      3, 14, "Root/Enabled: expected true or false, got 'yes'");
    expect_load_error("Root:\n"
                      "    Name: [Root]\n",
                      2, 11, "Root/Name: expected a string, got a list");
    expect_load_error("Root:\n"
                      "    Name: Root\n"
                      "    Children:\n"
                      "        - {Name: a}\n"
                      "        - {Name: b, Components: {Transform: {Scale: {X: {Y: 1}}}}}\n",
                      5, 57, "Root/Children[1]/Components/Transform/Scale/X: expected a finite number, got a map");
}

Test(scene_load, bad_numbers_are_rejected)
{
    static const char *bad[] = {"abc", "1.5x", "nan", "inf", ".inf", "1e999", "0x", "''"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char yaml[512], message[256];
        snprintf(yaml, sizeof yaml, "Root:\n    Name: Root\n    Components:\n        Camera: {FOV: %s}\n", bad[i]);
        const char *shown = strcmp(bad[i], "''") ? bad[i] : NULL;
        if (shown)
            snprintf(message, sizeof message, "Root/Components/Camera/FOV: expected a finite number, got '%s'", shown);
        else
            snprintf(message, sizeof message,
                     "Root/Components/Camera/FOV: expected a finite number, got an empty value");
        expect_load_error(yaml, 4, 23, message);
    }
}

Test(scene_load, image_sizes_and_indices_are_checked)
{
    expect_load_error("Root: {Name: R, Components: {Camera: {Render Width (px): 0}}}\n", 1, 58,
                      "Root/Components/Camera/Render Width (px): expected an integer from 1 to 16384, got '0'");
    expect_load_error("Root: {Name: R, Components: {Camera: {Render Height (px): 16385}}}\n", 1, 59,
                      "Root/Components/Camera/Render Height (px): expected an integer from 1 to 16384, got '16385'");
    expect_load_error("Root: {Name: R, Components: {Camera: {Render Width (px): 2.5}}}\n", 1, 58,
                      "Root/Components/Camera/Render Width (px): expected an integer from 1 to 16384, got '2.5'");
    expect_load_error("Root: {Name: R, Components: {Camera: {Trace: {Shadows: -1}}}}\n", 1, 56,
                      "Root/Components/Camera/Trace/Shadows: expected an integer from 0 to 2, got '-1'");
}

Test(scene_load, truncated_yaml)
{
    expect_load_error("Materials:\n"
                      "    Red: {Shader: Blinn-Phong Shader, Uniforms: {Diffuse: {Color: {R: 0.5",
                      3, 1, /* libyaml reports the end of the input on the line after */
                      "invalid YAML: did not find expected ',' or '}' while parsing a flow mapping");

    /* The first half of a real scene: valid YAML that ends before Root. */
    char path[512];
    snprintf(path, sizeof path, "%s/more/lecture.yaml", rt_test_trace_dir());
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    char half[8192];
    size_t n = fread(half, 1, sizeof half - 1, f);
    fclose(f);
    half[n / 2] = '\0';
    cr_assert_not(load(half));
    cr_expect(strstr(err, "Root: missing, expected a map") != NULL || strstr(err, "invalid YAML") != NULL, "%s", err);
}

Test(scene_load, missing_required_keys)
{
    expect_load_error("Materials: {}\n", 1, 1, "Root: missing, expected a map");
    expect_load_error("Root:\n"
                      "    Name: Root\n"
                      "    Children:\n"
                      "        - {Enabled: true}\n",
                      4, 11, "Root/Children[0]/Name: missing, expected a string");
    expect_load_error(RED_MATERIAL "Root: {Name: R, Components: {TriangleMesh: {Material: Red}}}\n", 6, 44,
                      "Root/Components/TriangleMesh/Mesh: missing, expected a string");
    /* Children and Components may be left out. */
    cr_assert(load("Root: {Name: R}\n"), "%s", err);
    cr_expect_eq(scene.node_count, 1u);
}

Test(scene_load, references_to_undefined_names)
{
    expect_load_error("Materials:\n"
                      "    Red:\n"
                      "        Shader: Blinn-Phong Shader\n"
                      "        Uniforms:\n"
                      "            Diffuse: {Color Map: Marble, Use Texture: true}\n" ONE_SPHERE,
                      5, 34, "Materials/Red/Uniforms/Diffuse/Color Map: no texture named 'Marble' in Textures");
    expect_load_error(RED_MATERIAL "Root: {Name: R, Components: {TriangleMesh: {Material: Red, Mesh: Pyramid}}}\n", 6,
                      66, "Root/Components/TriangleMesh/Mesh: no mesh named 'Pyramid' in Meshes, and it is not 'Cube'");
}

Test(scene_load, unsupported_components)
{
    expect_load_error(RED_MATERIAL "Root:\n"
                                   "    Name: Root\n"
                                   "    Components:\n"
                                   "        Cone: {Material: Red}\n",
                      9, 9, "Root/Components/Cone: component not supported");
}

Test(scene_load, odd_documents)
{
    expect_load_error("- 1\n- 2\n", 1, 1, "expected a scene (a YAML map), got a list");
    expect_load_error("", 1, 1, "expected a scene (a YAML map), got an empty file");
    expect_load_error("Root: &r {Name: R, Children: [*r]}\n", 1, 7,
                      "this node is reused through an alias; aliases are not supported");

    snprintf(scene_path, sizeof scene_path, "%s/absent.yaml", dir);
    cr_assert_not(rtp_scene_load(scene_path, NULL, &scene, err, sizeof err));
    char want[512];
    snprintf(want, sizeof want, "%s: cannot open: No such file or directory", scene_path);
    cr_expect_str_eq(err, want);
}

Test(scene_load, unreadable_mesh_file_names_its_key)
{
    put_file("assets/bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n");
    cr_assert_not(load_as("assets/bad.yaml",
                          RED_MATERIAL "Meshes: {Bad: {Path: assets/bad.ply}}\n"
                                       "Root: {Name: R, Components: {TriangleMesh: {Material: Red, Mesh: Bad}}}\n",
                          NULL));
    char want[512];
    snprintf(want, sizeof want, "%s:6:22: Meshes/Bad/Path: %s/assets/bad.ply: ", scene_path, dir);
    cr_expect(strncmp(err, want, strlen(want)) == 0, "%s", err);
}

Test(scene_load, deep_node_nesting_is_refused)
{
    size_t depth = 1200, size = depth * 40 + 64, n = 0;
    char *yaml = malloc(size);
    n += (size_t)snprintf(yaml + n, size - n, "Root: ");
    for (size_t i = 0; i < depth; i++) n += (size_t)snprintf(yaml + n, size - n, "{Name: n, Children: [");
    n += (size_t)snprintf(yaml + n, size - n, "{Name: leaf}");
    for (size_t i = 0; i < depth; i++) n += (size_t)snprintf(yaml + n, size - n, "]}");
    snprintf(yaml + n, size - n, "\n");
    cr_assert_not(load(yaml));
    free(yaml);
    cr_expect(strstr(err, "nodes nested more than 1000 deep") != NULL, "%s", err);
}

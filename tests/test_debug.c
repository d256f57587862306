/* `rtk debug`: what the ray tree says about known pixels of corpus and hand-written scenes,
 * that its colour is the rendered pixel's to the bit, that the terms add up, and the CLI
 * (text, JSON that parses, the SVG and its embedded image, usage errors). */
#include "capture.h"
#include "cli/debug_cmd.h"
#include "cli/exit_codes.h"
#include "debug/pixel_trace.h"
#include "json_check.h"
#include "reference.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAPACITY (1u << 16)

static char dir[64], tiny_path[128], mc_path[128];
static rtp_scene built;
static bool built_open;
static rtp_pixel_trace pt;

/* A glass ball on a floor, lit by a point light, 12x9 pixels, 4 samples per pixel. */
static const char tiny_scene[] =
    "Materials:\n"
    "    Glass:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 0.2, G: 0.3, B: 0.4}}\n"
    "            Specular: {Color: {R: 0.5, G: 0.5, B: 0.5}}\n"
    "            Transmittence: {Color: {R: 0.5, G: 0.6, B: 0.7}}\n"
    "            IndexOfRefraction: 1.5\n"
    "    Floor:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 0.8, G: 0.8, B: 0.8}}\n"
    "            Specular: {Color: {R: 0, G: 0, B: 0}}\n"
    "Root:\n"
    "    Name: Root\n"
    "    Children:\n"
    "        - Name: Eye\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 0.5, Z: 4}}\n"
    "              Camera: {FOV: 40, Render Width (px): 12, Render Height (px): 9,\n"
    "                       Trace: {Samples Per Pixel: 1, Shadows: 2, Maximum Recursion Depth: 4}}\n"
    "        - Name: Lamp\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 2, Y: 3, Z: 2}}\n"
    "              PointLight: {Ambient: {R: 0.1, G: 0.1, B: 0.1}, Quad Atten: 0.01}\n"
    "        - Name: Ball\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 0.5, Z: 0}}\n"
    "              Sphere: {Material: Glass}\n"
    "        - Name: Ground\n"
    "          Components:\n"
    "              Transform: {Rotation: {X: -90}, Scale: {X: 6, Y: 6, Z: 6}}\n"
    "              Plane: {Material: Floor}\n";

/* Monte Carlo: a glossy floor and a red back wall under an area light that the camera
 * sees (pixel row 0-2), 16x12 pixels, 4 samples per pixel. */
static const char mc_scene[] =
    "Materials:\n"
    "    Glossy:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 0.2, G: 0.3, B: 0.4}}\n"
    "            Specular: {Color: {R: 0.7, G: 0.7, B: 0.7}}\n"
    "            Shininess: 50\n"
    "    Wall:\n"
    "        Shader: Blinn-Phong Shader\n"
    "        Uniforms:\n"
    "            Diffuse: {Color: {R: 0.8, G: 0.2, B: 0.2}}\n"
    "Root:\n"
    "    Name: Root\n"
    "    Children:\n"
    "        - Name: Eye\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 1, Z: 4}}\n"
    "              Camera: {FOV: 40, Render Width (px): 16, Render Height (px): 12,\n"
    "                       Trace: {Monte Carlo: 2, Samples Per Pixel: 1, Shadows: 2, Reflections: true,\n"
    "                               Diffuse Reflection: true, Random Single Branching: false,\n"
    "                               Maximum Recursion Depth: 3}}\n"
    "        - Name: Panel\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 2, Z: 0}, Rotation: {X: 180}, Scale: {X: 2, Y: 1, Z: 2}}\n"
    "              AreaLight: {Color: {R: 1, G: 0.9, B: 0.8}, Const Atten: 1, Quad Atten: 0.1}\n"
    "        - Name: Ground\n"
    "          Components:\n"
    "              Transform: {Rotation: {X: -90}, Scale: {X: 8, Y: 8, Z: 8}}\n"
    "              Plane: {Material: Glossy}\n"
    "        - Name: Back\n"
    "          Components:\n"
    "              Transform: {Translation: {X: 0, Y: 0, Z: -3}, Scale: {X: 8, Y: 8, Z: 8}}\n"
    "              Plane: {Material: Wall}\n";

static void write_scene(char *path, size_t size, const char *name, const char *text)
{
    snprintf(path, size, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

static void setup(void)
{
    cr_assert(tmpdir_make(dir, sizeof dir, "debug"), "cannot create a scratch folder");
    write_scene(tiny_path, sizeof tiny_path, "tiny.yaml", tiny_scene);
    write_scene(mc_path, sizeof mc_path, "mc.yaml", mc_scene);
    cr_redirect_stderr();
}

static void teardown(void)
{
    rtp_pixel_trace_free(&pt);
    if (built_open) rtp_scene_close(&built);
    tmpdir_remove(dir);
}

TestSuite(debug, .init = setup, .fini = teardown);

static const char *corpus(const char *name)
{
    static char path[4096];
    snprintf(path, sizeof path, "%s/simple/%s", rt_test_trace_dir(), name);
    return path;
}

static void open_scene(const char *path)
{
    if (built_open) rtp_scene_close(&built);
    rtp_scene_options opt = {.max_memory = (size_t)1 << 30, .depth = -1, .aa = -1};
    char err[RTP_ERR_SIZE];
    cr_assert_eq(rtp_scene_open(path, &opt, &built, err, sizeof err), RTP_EXIT_OK, "%s", err);
    built_open = true;
}

static void trace(uint32_t x, uint32_t y, uint32_t sample)
{
    rtp_pixel_trace_free(&pt);
    cr_assert(rtp_pixel_trace_run(&pt, &built, x, y, sample, CAPACITY));
    cr_assert_not(pt.log.overflow);
}

static const rt_ray_record *root(void)
{
    cr_assert_neq(pt.first_root, RT_NO_PARENT, "no camera ray logged");
    return &pt.log.rays[pt.first_root];
}

static void expect_vec(rt_vec3 v, double x, double y, double z, double tol, const char *what)
{
    double gx = rt_to_double(v.x), gy = rt_to_double(v.y), gz = rt_to_double(v.z);
    cr_expect(fabs(gx - x) <= tol && fabs(gy - y) <= tol && fabs(gz - z) <= tol,
              "%s: got (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)", what, gx, gy, gz, x, y, z);
}

/* v as doubles, for expect_vec. */
#define XYZ(v) rt_to_double((v).x), rt_to_double((v).y), rt_to_double((v).z)

/* ---- Known hits ---- */

Test(debug, cylinder_at_the_image_centre)
{
    open_scene(corpus("cyl_diffuse.yaml"));
    trace(256, 256, RTP_PIXEL_ALL_SAMPLES);
    const rt_ray_record *r = root();
    cr_assert(r->hit);
    rtp_hit_names n = rtp_pixel_trace_names(&pt, r);
    cr_expect_str_eq(n.node, "Cylinder");
    cr_expect_str_eq(n.primitive, "cylinder");
    cr_expect_str_eq(n.material, "Cylinder");
    cr_expect_eq(n.triangle, UINT32_MAX);
    /* The camera looks down the cylinder's tilted axis onto its top cap. The scene turns the
     * axis by X 1.673 then Z -28.648 degrees: (-cos a sin c, cos a cos c, sin a). */
    cr_assert_str_eq(n.part, "top cap");
    double a = 1.673 * M_PI / 180, c = -28.648 * M_PI / 180;
    double ax = -cos(a) * sin(c), ay = cos(a) * cos(c), az = sin(a);
    expect_vec(r->surface.geometric_normal, ax, ay, az, 1e-9, "cap normal");
    expect_vec(r->normal_used, ax, ay, az, 1e-9, "normal used");
    cr_expect(r->entering);
    /* The top cap's centre is the origin (Translation Y -0.5 under a height of 1), radius 1. */
    double px = rt_to_double(r->surface.point.x), py = rt_to_double(r->surface.point.y),
           pz = rt_to_double(r->surface.point.z);
    cr_expect(fabs(px * ax + py * ay + pz * az) < 1e-9, "point off the cap plane");
    cr_expect(px * px + py * py + pz * pz <= 1.0);
    expect_vec(r->ray.origin, 5, 0, 0, 0, "eye");
}

Test(debug, floor_box_near_the_bottom)
{
    open_scene(corpus("box_cyl_opaque_shadow.yaml"));
    trace(256, 400, RTP_PIXEL_ALL_SAMPLES);
    const rt_ray_record *r = root();
    cr_assert(r->hit);
    rtp_hit_names n = rtp_pixel_trace_names(&pt, r);
    cr_expect_str_eq(n.node, "Box");
    cr_expect_str_eq(n.primitive, "triangle");
    cr_expect_null(n.part);
    cr_expect_lt(n.triangle, 12u, "the Cube has 12 triangles");
    /* The Cube scaled (15, 1, 15) at y = -2: its top face is y = -1.5, normal +Y. */
    expect_vec(r->surface.geometric_normal, 0, 1, 0, 1e-12, "geometric normal");
    expect_vec(r->normal_used, 0, 1, 0, 1e-12, "normal used");
    cr_expect_float_eq(rt_to_double(r->surface.point.y), -1.5, 1e-12);
    /* Lit: the light's shadow ray reaches it unblocked. */
    cr_assert_neq(pt.first_light[pt.first_root], RT_NO_PARENT);
    const rt_light_record *l = &pt.log.lights[pt.first_light[pt.first_root]];
    expect_vec(l->shadow_attenuation, 1, 1, 1, 0, "shadow attenuation");
    uint32_t s = pt.first_shadow[pt.first_light[pt.first_root]];
    cr_assert_neq(s, RT_NO_PARENT);
    cr_expect_not(pt.log.rays[s].hit);
    cr_expect_eq(pt.log.rays[s].kind, RT_RAY_SHADOW);
    /* The Box has no specular colour: the render skips N.H there, the log still shows it
     * (the half vector of the shadow ray's direction and the view, dotted with +Y). */
    expect_vec(l->specular, 0, 0, 0, 0, "specular");
    rt_vec3 h = rt_v3_normalize(rt_v3_sub(rt_v3_normalize(pt.log.rays[s].ray.direction), r->ray.direction));
    cr_expect_float_eq(rt_to_double(l->n_dot_h), rt_to_double(h.y), 1e-6, "N.H %g", rt_to_double(l->n_dot_h));
    cr_expect_gt(rt_to_double(l->n_dot_h), 0.5);
}

Test(debug, floor_in_the_cylinders_shadow)
{
    open_scene(corpus("box_cyl_opaque_shadow.yaml"));
    trace(256, 290, RTP_PIXEL_ALL_SAMPLES);
    cr_assert_str_eq(rtp_pixel_trace_names(&pt, root()).node, "Box");
    uint32_t j = pt.first_light[pt.first_root];
    cr_assert_neq(j, RT_NO_PARENT);
    const rt_light_record *l = &pt.log.lights[j];
    expect_vec(l->shadow_attenuation, 0, 0, 0, 0, "shadow attenuation");
    expect_vec(l->contribution, 0, 0, 0, 0, "contribution (no ambient)");
    const rt_ray_record *s = &pt.log.rays[pt.first_shadow[j]];
    cr_assert(s->hit);
    rtp_hit_names n = rtp_pixel_trace_names(&pt, s);
    cr_expect_str_eq(n.node, "Cylinder");
    cr_expect_str_eq(n.part, "bottom cap");
    cr_expect_float_eq(rt_to_double(s->surface.point.y), 1.0, 1e-9, "the cylinder's bottom is at y = 1");
    expect_vec(s->color, 0, 0, 0, 0, "shadow ray attenuation");
    cr_expect_arr_eq(pt.rgb, ((uint8_t[]){0, 0, 0}), 3);
}

Test(debug, refraction_through_the_lens)
{
    open_scene(corpus("sphere_refract.yaml"));
    trace(200, 250, RTP_PIXEL_ALL_SAMPLES);
    const rt_ray_record *r = root();
    cr_assert(r->hit);
    cr_expect_str_eq(rtp_pixel_trace_names(&pt, r).node, "Sphere 1");
    cr_expect_str_eq(rtp_pixel_trace_names(&pt, r).material, "Lens");
    cr_expect(rtp_pixel_trace_material(&pt, r).kt.x > RT_ZERO);
    uint32_t c = pt.first_child[pt.first_root];
    while (c != RT_NO_PARENT && pt.log.rays[c].kind != RT_RAY_REFRACTION) c = pt.next_sibling[c];
    cr_assert_neq(c, RT_NO_PARENT, "no refraction ray");
    const rt_ray_record *inside = &pt.log.rays[c];
    cr_expect_eq(inside->depth, 1u);
    cr_expect_eq(inside->parent, pt.first_root);
    cr_assert(inside->hit);
    /* Inside the glass the ray leaves through the far side: the normal is flipped. */
    cr_expect_str_eq(rtp_pixel_trace_names(&pt, inside).node, "Sphere 1");
    cr_expect_not(inside->entering);
    expect_vec(inside->normal_used, XYZ(rt_v3_neg(inside->surface.normal)), 0, "flipped normal");
}

/* ---- The colour is the render's ---- */

static void expect_pixels_match_render(const char *path, const uint32_t (*pixels)[2], int count)
{
    rtp_image img;
    char err[RTP_ERR_SIZE];
    cr_assert(rt_test_render(path, 2, true, &img, err, sizeof err), "%s", err);
    open_scene(path);
    for (int i = 0; i < count; i++) {
        uint32_t x = pixels[i][0], y = pixels[i][1];
        trace(x, y, RTP_PIXEL_ALL_SAMPLES);
        const uint8_t *want = img.rgb + 3 * ((size_t)y * img.width + x);
        cr_expect_arr_eq(pt.rgb, want, 3, "%s (%u, %u): debug %u %u %u, render %u %u %u", path, x, y, pt.rgb[0],
                         pt.rgb[1], pt.rgb[2], want[0], want[1], want[2]);
    }
    rtp_image_free(&img);
}

Test(debug, bytes_equal_the_render_on_corpus_scenes)
{
    static const uint32_t cyl[][2] = {{256, 256}, {10, 10}, {300, 200}, {511, 511}};
    static const uint32_t shadow[][2] = {{256, 290}, {256, 400}, {256, 215}, {0, 0}, {100, 300}};
    static const uint32_t refract[][2] = {{200, 250}, {256, 256}, {180, 60}, {150, 220}, {300, 400}};
    static const uint32_t mirror[][2] = {{256, 256}, {200, 300}, {256, 150}};
    expect_pixels_match_render(corpus("cyl_diffuse.yaml"), cyl, 4);
    expect_pixels_match_render(corpus("box_cyl_opaque_shadow.yaml"), shadow, 5);
    expect_pixels_match_render(corpus("sphere_refract.yaml"), refract, 5);
    expect_pixels_match_render(corpus("box_cyl_reflect.yaml"), mirror, 3);
    expect_pixels_match_render(corpus("texture_reflection.yaml"), mirror, 3);
}

Test(debug, every_pixel_of_an_anti_aliased_scene)
{
    rtp_image img;
    char err[RTP_ERR_SIZE];
    cr_assert(rt_test_render(tiny_path, 1, true, &img, err, sizeof err), "%s", err);
    open_scene(tiny_path);
    cr_assert_eq(img.width * img.height, 12u * 9u);
    for (uint32_t y = 0; y < img.height; y++)
        for (uint32_t x = 0; x < img.width; x++) {
            trace(x, y, RTP_PIXEL_ALL_SAMPLES);
            cr_expect_arr_eq(pt.rgb, img.rgb + 3 * (y * img.width + x), 3, "pixel (%u, %u)", x, y);
            /* Four camera rays whose colours average, in order, to the pixel's. */
            rt_vec3 sum = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
            uint32_t n = 0;
            for (uint32_t id = pt.first_root; id != RT_NO_PARENT; id = pt.next_sibling[id], n++)
                sum = rt_v3_add(sum, pt.log.rays[id].color);
            cr_expect_eq(n, 4u);
            rt_real four = rt_from_int(4);
            rt_vec3 mean = rt_v3(rt_div(sum.x, four), rt_div(sum.y, four), rt_div(sum.z, four));
            expect_vec(pt.color, XYZ(mean), 0, "average of the samples");
        }
    rtp_image_free(&img);
}

Test(debug, one_sample_is_that_samples_camera_ray)
{
    open_scene(tiny_path);
    trace(6, 4, RTP_PIXEL_ALL_SAMPLES);
    uint32_t id = pt.first_root;
    for (int k = 0; k < 2; k++) id = pt.next_sibling[id];
    rt_ray_record third = pt.log.rays[id];
    rt_vec3 all = pt.color;
    trace(6, 4, 2);
    cr_assert_eq(pt.next_sibling[pt.first_root], RT_NO_PARENT, "one camera ray");
    const rt_ray_record *r = root();
    expect_vec(r->ray.direction, XYZ(third.ray.direction), 0, "direction");
    expect_vec(r->color, XYZ(third.color), 0, "colour");
    expect_vec(pt.color, XYZ(all), 0, "the pixel's colour is still the average");
}

/* Every hit's colour is its emission, plus each light's contribution, plus k_s times the
 * reflected (or glossy), k_t times the refracted and k_d times the diffuse colour; each
 * light's contribution is its ambient plus shadow * distance attenuation * the light's
 * cosine * light colour * (diffuse + specular). Without single branching. */
static void expect_terms_add_up(void)
{
    const rt_scene *scene = &built.scene;
    for (uint32_t i = 0; i < pt.log.ray_count; i++) {
        const rt_ray_record *r = &pt.log.rays[i];
        if (!r->hit || r->kind == RT_RAY_SHADOW) continue;
        rtp_hit_material m = rtp_pixel_trace_material(&pt, r);
        rt_vec3 sum = r->emissive;
        for (uint32_t j = pt.first_light[i]; j != RT_NO_PARENT; j = pt.next_light[j]) {
            const rt_light_record *l = &pt.log.lights[j];
            rt_vec3 light = rt_v3_scale(rt_v3_mul(l->shadow_attenuation, scene->lights[l->light].color),
                                        rt_mul(l->distance_attenuation, l->light_cosine));
            rt_vec3 want = rt_v3_add(l->ambient, rt_v3_mul(light, rt_v3_add(l->diffuse, l->specular)));
            expect_vec(l->contribution, XYZ(want), 1e-12, "light contribution");
            sum = rt_v3_add(sum, l->contribution);
        }
        for (uint32_t c = pt.first_child[i]; c != RT_NO_PARENT; c = pt.next_sibling[c]) {
            const rt_ray_record *child = &pt.log.rays[c];
            rt_vec3 weight = child->kind == RT_RAY_REFRACTION ? m.kt : child->kind == RT_RAY_DIFFUSE ? m.kd : m.ks;
            sum = rt_v3_add(sum, rt_v3_mul(weight, child->color));
        }
        expect_vec(r->color, XYZ(sum), 1e-12, "a ray's colour from its terms");
    }
}

Test(debug, the_terms_add_up)
{
    open_scene(tiny_path);
    for (uint32_t y = 0; y < 9; y += 2)
        for (uint32_t x = 0; x < 12; x += 3) {
            trace(x, y, RTP_PIXEL_ALL_SAMPLES);
            expect_terms_add_up();
        }
    open_scene(corpus("sphere_refract.yaml"));
    trace(200, 250, RTP_PIXEL_ALL_SAMPLES);
    expect_terms_add_up();
    open_scene(mc_path);
    for (uint32_t y = 3; y < 12; y += 2)
        for (uint32_t x = 0; x < 16; x += 3) {
            trace(x, y, RTP_PIXEL_ALL_SAMPLES);
            expect_terms_add_up();
        }
}

/* ---- Monte Carlo rays (format.md §11.4) ---- */

Test(debug, monte_carlo_pixels_equal_the_render)
{
    static const uint32_t pixels[][2] = {{8, 1}, {2, 1}, {8, 9}, {0, 11}, {15, 3}, {12, 2}};
    expect_pixels_match_render(mc_path, pixels, 6);
}

/* A camera ray on the light's square ends there and brings back 64 x its Color. */
Test(debug, camera_ray_ends_on_the_light)
{
    open_scene(mc_path);
    trace(8, 1, RTP_PIXEL_ALL_SAMPLES);
    uint32_t n = 0;
    for (uint32_t id = pt.first_root; id != RT_NO_PARENT; id = pt.next_sibling[id], n++) {
        const rt_ray_record *r = &pt.log.rays[id];
        cr_assert(r->on_light, "sample %u missed the light", n);
        cr_expect_not(r->hit);
        cr_expect_eq(r->light, 0u);
        cr_expect_eq(pt.first_child[id], RT_NO_PARENT, "a ray on a light spawns nothing");
        cr_expect_eq(pt.first_light[id], RT_NO_PARENT, "a ray on a light is not lit");
        expect_vec(r->color, 64, 57.6, 51.2, 1e-12, "the light's emission");
        /* It ends on the square: y = 2, |x| and |z| within 1. */
        rt_vec3 end = rt_v3_madd(r->ray.origin, r->ray.direction, r->ray.t_max);
        cr_expect(fabs(rt_to_double(end.y) - 2) < 1e-9 && fabs(rt_to_double(end.x)) <= 1 &&
                      fabs(rt_to_double(end.z)) <= 1,
                  "ends at (%g, %g, %g)", XYZ(end));
    }
    cr_expect_eq(n, 4u);
    cr_expect_arr_eq(pt.rgb, ((uint8_t[]){255, 255, 255}), 3);
}

/* On the floor: glossy rays about a unit half vector above the normal, mirrored about it
 * (or the mirror direction when that fell below); the area light's term carries its
 * cosine, -N_L . L, with L the shadow ray's direction. */
Test(debug, glossy_rays_and_the_lights_cosine)
{
    open_scene(mc_path);
    uint32_t glossy = 0, lit = 0;
    for (uint32_t x = 0; x < 16; x += 5) {
        trace(x, 9, RTP_PIXEL_ALL_SAMPLES);
        for (uint32_t i = 0; i < pt.log.ray_count; i++) {
            const rt_ray_record *r = &pt.log.rays[i];
            cr_expect_neq(r->kind, RT_RAY_REFLECTION, "a mirror ray in Monte Carlo mode");
            if (r->kind != RT_RAY_GLOSSY) continue;
            glossy++;
            const rt_ray_record *parent = &pt.log.rays[r->parent];
            rt_vec3 n = parent->normal_used, v = rt_v3_neg(parent->ray.direction), h = r->half_vector;
            cr_expect(fabs(rt_to_double(rt_v3_length(h)) - 1) < 1e-9 && rt_v3_dot(h, n) >= RT_ZERO);
            rt_vec3 axis = r->mirror_fallback ? n : h;
            rt_vec3 want = rt_v3_sub(rt_v3_scale(axis, rt_mul(RT_C(2.0), rt_v3_dot(v, axis))), v);
            expect_vec(r->ray.direction, XYZ(want), 1e-9, "glossy direction");
        }
        for (uint32_t j = 0; j < pt.log.light_count; j++) {
            const rt_light_record *l = &pt.log.lights[j];
            uint32_t s = pt.first_shadow[j];
            if (s == RT_NO_PARENT) continue;
            lit++;
            rt_real want = rt_neg(rt_v3_dot(built.scene.lights[0].normal, pt.log.rays[s].ray.direction));
            cr_expect(fabs(rt_to_double(rt_sub(l->light_cosine, want))) < 1e-9, "light cosine %g, want %g",
                      rt_to_double(l->light_cosine), rt_to_double(want));
            cr_expect(l->light_cosine > RT_ZERO && l->light_cosine < RT_ONE);
        }
    }
    cr_expect_gt(glossy, 0u, "no glossy ray");
    cr_expect_gt(lit, 0u, "no shadow ray reached the light");
}

Test(debug, a_full_log_cuts_the_tree_not_the_colour)
{
    open_scene(corpus("sphere_refract.yaml"));
    trace(200, 250, RTP_PIXEL_ALL_SAMPLES);
    rt_vec3 full = pt.color;
    cr_assert_gt(pt.log.ray_count, 3u);
    rtp_pixel_trace_free(&pt);
    cr_assert(rtp_pixel_trace_run(&pt, &built, 200, 250, RTP_PIXEL_ALL_SAMPLES, 3));
    cr_expect(pt.log.overflow);
    cr_expect_eq(pt.log.ray_count, 3u);
    expect_vec(pt.color, XYZ(full), 0, "colour");
}

/* ---- The command ---- */

/* Runs `rtk debug` with the arguments up to NULL; its output in *out. */
static int debug_cmd(char **out, ...)
{
    char *argv[24] = {"debug"};
    int argc = 1;
    va_list ap;
    va_start(ap, out);
    for (const char *s; argc < 23 && (s = va_arg(ap, const char *)) != NULL;) argv[argc++] = (char *)s;
    va_end(ap);
    return capture_stdout(rtp_cmd_debug, argc, argv, out);
}

Test(debug, text_names_what_was_hit)
{
    char *out;
    cr_assert_eq(debug_cmd(&out, corpus("box_cyl_opaque_shadow.yaml"), "--pixel", "256,290", NULL), RTP_EXIT_OK);
    cr_assert_not_null(out);
    cr_expect(strstr(out, "camera ray, depth 0") != NULL, "%s", out);
    cr_expect(strstr(out, "hit 'Box': triangle ") != NULL, "%s", out);
    cr_expect(strstr(out, "normal: geometric (0, 1, 0)") != NULL, "%s", out);
    cr_expect(strstr(out, "material 'Box'") != NULL, "%s", out);
    cr_expect(strstr(out, "light 0 (point)") != NULL, "%s", out);
    cr_expect(strstr(out, "shadow ray, depth 0, towards light 0") != NULL, "%s", out);
    cr_expect(strstr(out, "hit 'Cylinder': cylinder bottom cap") != NULL, "%s", out);
    cr_expect(strstr(out, "pixel (256, 290): colour (0, 0, 0) -> bytes 0 0 0\n") != NULL, "%s", out);
    free(out);
}

Test(debug, json_parses)
{
    static const char *const pixels[] = {"200,250", "0,0", "256,256", "100,400"};
    for (int i = 0; i < 4; i++) {
        char *out;
        cr_assert_eq(debug_cmd(&out, corpus("sphere_refract.yaml"), "--json", "--pixel", pixels[i], NULL), RTP_EXIT_OK);
        cr_assert_not_null(out);
        cr_expect(json_is_valid(out), "pixel %s: not JSON:\n%s", pixels[i], out);
        free(out);
    }
    char *out;
    cr_assert_eq(debug_cmd(&out, tiny_path, "--json", "--pixel", "6,4", "--sample", "3", NULL), RTP_EXIT_OK);
    cr_expect(json_is_valid(out), "%s", out);
    cr_expect(strstr(out, "\"sample\": 3") != NULL, "%s", out);
    cr_expect(strstr(out, "\"samples_per_pixel\": 4") != NULL, "%s", out);
    free(out);
    cr_assert_eq(debug_cmd(&out, corpus("sphere_refract.yaml"), "--pixel", "200,250", "--json", NULL), RTP_EXIT_OK);
    cr_expect(strstr(out, "\"node\": \"Sphere 1\"") != NULL, "%s", out);
    cr_expect(strstr(out, "\"kind\": \"refraction\"") != NULL, "%s", out);
    free(out);
}

Test(debug, json_checker_rejects_what_it_should)
{
    static const char *const bad[] = {"", "{", "{\"a\" 1}", "[1,]", "nan", "[01]", "{\"a\": 1} x", "\"\\q\"", "[1.]"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) cr_expect_not(json_is_valid(bad[i]), "%s", bad[i]);
    cr_expect(json_is_valid(" {\"a\": [1, -2.5e-3, true, null, \"\\u00e9\"]} "));
}

Test(debug, monte_carlo_text_and_json)
{
    char *out;
    cr_assert_eq(debug_cmd(&out, mc_path, "--pixel", "8,1", "--sample", "0", NULL), RTP_EXIT_OK);
    cr_expect(strstr(out, "ends on light 0 (area), t ") != NULL, "%s", out);
    cr_expect(strstr(out, "returns (64, 57.6, 51.2)") != NULL, "%s", out);
    free(out);
    cr_assert_eq(debug_cmd(&out, mc_path, "--pixel", "8,1", "--sample", "0", "--json", NULL), RTP_EXIT_OK);
    cr_expect(json_is_valid(out), "%s", out);
    cr_expect(strstr(out, "\"hit\": null, \"light_hit\": {\"light\": 0, \"kind\": \"area\", \"t\": ") != NULL, "%s",
              out);
    cr_expect(strstr(out, "\"emission\": [64, 57.6") != NULL, "%s", out);
    free(out);
    cr_assert_eq(debug_cmd(&out, mc_path, "--pixel", "8,9", NULL), RTP_EXIT_OK);
    cr_expect(strstr(out, "glossy ray, depth 1") != NULL, "%s", out);
    cr_expect(strstr(out, "half vector (") != NULL, "%s", out);
    cr_expect(strstr(out, "light 0 (area)") != NULL, "%s", out);
    cr_expect(strstr(out, "light cosine 0.") != NULL, "%s", out);
    free(out);
    cr_assert_eq(debug_cmd(&out, mc_path, "--pixel", "8,9", "--json", NULL), RTP_EXIT_OK);
    cr_expect(json_is_valid(out), "%s", out);
    cr_expect(strstr(out, "\"kind\": \"glossy\"") != NULL, "%s", out);
    cr_expect(strstr(out, "\"half_vector\": [") != NULL, "%s", out);
    cr_expect(strstr(out, "\"mirror_fallback\": ") != NULL, "%s", out);
    cr_expect(strstr(out, "\"light_cosine\": 0.") != NULL, "%s", out);
    cr_expect(strstr(out, "\"light_hit\": null") != NULL, "%s", out);
    free(out);
    char svg_path[160];
    snprintf(svg_path, sizeof svg_path, "%s/mc.svg", dir);
    cr_assert_eq(debug_cmd(&out, mc_path, "--pixel", "8,9", "--svg", svg_path, NULL), RTP_EXIT_OK);
    free(out);
    FILE *f = fopen(svg_path, "rb");
    cr_assert_not_null(f);
    static char svg[1 << 21];
    svg[fread(svg, 1, sizeof svg - 1, f)] = '\0';
    fclose(f);
    cr_expect(strstr(svg, "class=\"ray glossy\"") != NULL, "the glossy rays");
    cr_expect(strstr(svg, "<path class=\"light\"") != NULL, "the light's square");
}

/* The base64 between `data:image/png;base64,` and the closing quote, decoded. */
static size_t embedded_png(const char *svg, uint8_t *out, size_t cap)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char *p = strstr(svg, "data:image/png;base64,");
    cr_assert_not_null(p);
    p += strlen("data:image/png;base64,");
    size_t n = 0;
    uint32_t acc = 0;
    int bits = 0;
    for (; *p && *p != '"' && *p != '='; p++) {
        const char *d = strchr(digits, *p);
        cr_assert(d && *d, "not base64: %c", *p);
        acc = (acc << 6) | (uint32_t)(d - digits);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            cr_assert_lt(n, cap);
            out[n++] = (uint8_t)(acc >> bits);
        }
    }
    return n;
}

Test(debug, svg_embeds_the_render_and_draws_the_rays)
{
    char svg_path[160], png_path[160], err[RTP_ERR_SIZE];
    snprintf(svg_path, sizeof svg_path, "%s/tree.svg", dir);
    snprintf(png_path, sizeof png_path, "%s/embedded.png", dir);
    char *out;
    cr_assert_eq(debug_cmd(&out, corpus("sphere_refract.yaml"), "--pixel", "200,250", "--svg", svg_path, NULL),
                 RTP_EXIT_OK);
    free(out);
    FILE *f = fopen(svg_path, "rb");
    cr_assert_not_null(f);
    static char svg[1 << 22];
    size_t n = fread(svg, 1, sizeof svg - 1, f);
    fclose(f);
    svg[n] = '\0';
    cr_expect(strncmp(svg, "<?xml", 5) == 0);
    cr_expect(strstr(svg, "</svg>\n") == svg + n - 7, "the document ends with </svg>");
    cr_expect(strstr(svg, "class=\"ray camera\"") != NULL);
    cr_expect(strstr(svg, "class=\"ray refraction\"") != NULL);
    cr_expect(strstr(svg, "class=\"ray shadow\"") != NULL);
    cr_expect(strstr(svg, "<ellipse class=\"quadric\"") != NULL, "the lens's outline");
    static uint8_t png[1 << 21];
    size_t png_size = embedded_png(svg, png, sizeof png);
    f = fopen(png_path, "wb");
    cr_assert_eq(fwrite(png, 1, png_size, f), png_size);
    fclose(f);
    rtp_image shown, rendered;
    cr_assert(rtp_image_read(png_path, &shown, err, sizeof err), "%s", err);
    cr_assert(rt_test_render(corpus("sphere_refract.yaml"), 2, true, &rendered, err, sizeof err), "%s", err);
    cr_assert(shown.width == rendered.width && shown.height == rendered.height);
    cr_expect_arr_eq(shown.rgb, rendered.rgb, (size_t)shown.width * shown.height * 3, "the embedded image");
    rtp_image_free(&shown);
    rtp_image_free(&rendered);
}

Test(debug, mesh_scene_svg_draws_triangle_edges)
{
    char svg_path[160];
    snprintf(svg_path, sizeof svg_path, "%s/tiny.svg", dir);
    char *out;
    cr_assert_eq(debug_cmd(&out, tiny_path, "--pixel", "6,6", "--svg", svg_path, NULL), RTP_EXIT_OK);
    free(out);
    FILE *f = fopen(svg_path, "rb");
    cr_assert_not_null(f);
    static char svg[1 << 20];
    svg[fread(svg, 1, sizeof svg - 1, f)] = '\0';
    fclose(f);
    cr_expect(strstr(svg, "<path class=\"mesh\" d=\"M") != NULL, "the floor's triangles");
    cr_expect(strstr(svg, "<circle class=\"light\"") != NULL, "the lamp");
}

Test(debug, bad_arguments_are_usage_errors)
{
    static const char *const pixels[] = {"512,0", "0,512", "-1,0", "1", "1,2,3", "a,b", "", ",", "1,", "4294967296,1"};
    const char *scene = corpus("cyl_diffuse.yaml");
    char *out;
    for (size_t i = 0; i < sizeof pixels / sizeof pixels[0]; i++) {
        cr_expect_eq(debug_cmd(&out, scene, "--pixel", pixels[i], NULL), RTP_EXIT_USAGE, "--pixel '%s'", pixels[i]);
        free(out);
    }
    cr_expect_eq(debug_cmd(&out, scene, "--pixel", "511,511", NULL), RTP_EXIT_OK);
    free(out);
    cr_expect_eq(debug_cmd(&out, scene, "--pixel", "600,10", "--width", "601", NULL), RTP_EXIT_OK, "--width widens");
    free(out);
    cr_expect_eq(debug_cmd(&out, scene, NULL), RTP_EXIT_USAGE, "no --pixel");
    free(out);
    cr_expect_eq(debug_cmd(&out, "--pixel", "1,1", NULL), RTP_EXIT_USAGE, "no scene");
    free(out);
    cr_expect_eq(debug_cmd(&out, scene, "--pixel", "1,1", "--sample", "1", NULL), RTP_EXIT_USAGE, "1 sample only");
    free(out);
    cr_expect_eq(debug_cmd(&out, tiny_path, "--pixel", "1,1", "--sample", "3", NULL), RTP_EXIT_OK);
    free(out);
    cr_expect_eq(debug_cmd(&out, scene, "--pixel", "1,1", "--bogus", NULL), RTP_EXIT_USAGE);
    free(out);
}

Test(debug, unreadable_scene_and_unwritable_svg)
{
    char missing[160], bad_svg[160];
    snprintf(missing, sizeof missing, "%s/none.yaml", dir);
    snprintf(bad_svg, sizeof bad_svg, "%s/no/such/folder/tree.svg", dir);
    char *out;
    cr_expect_eq(debug_cmd(&out, missing, "--pixel", "1,1", NULL), RTP_EXIT_INPUT);
    free(out);
    cr_expect_eq(debug_cmd(&out, tiny_path, "--pixel", "1,1", "--svg", bad_svg, NULL), RTP_EXIT_OUTPUT);
    free(out);
    cr_expect_eq(tmpdir_count(dir), 2, "only tiny.yaml and mc.yaml: no partial SVG left behind");
}

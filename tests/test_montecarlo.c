/* Monte Carlo rendering (core/rng.c, sample.c, path_trace.c, area_light.c, render_pixel.c):
 * the random numbers, the estimators' expected values (white furnace, caustics rule,
 * single branching, soft shadows), the conventions of format.md §11.4 and §11.6 (Lambertian area
 * lights, lights seen by camera rays only, the Blinn-Phong lobe of glossy rays),
 * convergence as 1/sqrt(spp), the energy bound, the sample count types, the thin lens,
 * and independence from tiles and threads. */
#include "area_light.h"
#include "builtin_mesh.h"
#include "cli/cli.h"
#include "load/scene_open.h"
#include "path_trace.h"
#include "raylog.h"
#include "reference.h"
#include "render.h"
#include "thread/threads.h"
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Helpers ---- */

/* What "equal" allows in geometric checks: the fixed build rounds every step to 2^-32. */
#ifdef RT_REAL_FIXED
#define EXACT 1e-6
#else
#define EXACT 1e-9
#endif

static rt_vec3 v3(double x, double y, double z)
{
    return rt_v3(rt_from_double(x), rt_from_double(y), rt_from_double(z));
}

static rt_material material(rt_vec3 kd, rt_vec3 ks, rt_vec3 ke)
{
    rt_material m;
    memset(&m, 0, sizeof m);
    m.diffuse.color = kd;
    m.specular.color = ks;
    m.emissive.color = ke;
    m.diffuse.texture = m.specular.texture = m.emissive.texture = m.transmittance.texture = RT_NO_TEXTURE;
    m.shininess = RT_C(10.0);
    m.index_of_refraction = RT_ONE;
    return m;
}

/* A Monte Carlo camera at `world` (looking down its -Z), size x size pixels. */
static rt_camera_desc mc_camera(rt_affine world, uint32_t size, double fov)
{
    rt_camera_desc c;
    memset(&c, 0, sizeof c);
    c.world = world;
    c.fov_degrees = rt_from_double(fov);
    c.perspective = true;
    c.width = c.height = size;
    c.trace.max_depth = 5;
    c.trace.reflections = c.trace.refractions = true;
    c.trace.monte_carlo = 2;
    c.trace.diffuse_reflection = true;
    c.trace.focus_distance = RT_ONE;
    return c;
}

typedef struct {
    void *memory;
    rt_scene scene;
} built_scene;

static void build(const rt_scene_desc *d, built_scene *b)
{
    size_t size = (size_t)16 << 20;
    b->memory = malloc(size);
    cr_assert(b->memory);
    rt_arena arena;
    rt_arena_init(&arena, b->memory, size);
    rt_build_error err;
    cr_assert_eq(rt_scene_build(d, &arena, NULL, &b->scene, &err), RT_OK, "build: %s", err.what);
}

/* The inside of a sphere of radius 5 around a camera at the origin: every camera ray
 * and every bounce hits it. */
static built_scene furnace(const rt_material *m, rt_trace_settings trace, uint32_t size)
{
    static rt_object_desc sphere;
    sphere.kind = RT_SHAPE_SPHERE;
    sphere.world = rt_affine_trs(v3(0, 0, 0), v3(0, 0, 0), v3(10, 10, 10));
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.materials = m;
    d.material_count = 1;
    d.objects = &sphere;
    d.object_count = 1;
    d.camera = mc_camera(rt_affine_identity(), size, 90);
    d.camera.trace = trace;
    built_scene b;
    build(&d, &b);
    return b;
}

static rt_trace_settings furnace_trace(uint32_t depth)
{
    rt_trace_settings t = mc_camera(rt_affine_identity(), 1, 90).trace;
    t.max_depth = depth;
    return t;
}

/* Per channel: e * (1 + w + ... + w^depth), the radiance when every bounce has weight w. */
static double finite_sum(double e, double w, uint32_t depth)
{
    double s = 0, p = 1;
    for (uint32_t d = 0; d <= depth; d++, p *= w) s += e * p;
    return s;
}

/* A corpus scene built at size x size (its own settings otherwise). */
static rtp_scene open_corpus(const char *name, uint32_t size)
{
    char path[4096], err[1024];
    snprintf(path, sizeof path, "%s/%s", rt_test_trace_dir(), name);
    rtp_scene_options opt;
    memset(&opt, 0, sizeof opt);
    opt.max_memory = (size_t)1 << 30;
    opt.depth = opt.aa = -1;
    opt.width = opt.height = size;
    rtp_scene b;
    cr_assert_eq(rtp_scene_open(path, &opt, &b, err, sizeof err), 0, "%s", err);
    return b;
}

/* Unclamped pixel colours, row-major. */
static rt_vec3 *render_colors(const rt_scene *scene)
{
    rt_tracer tr = {.scene = scene, .use_bvh = true};
    uint32_t w = scene->camera.width, h = scene->camera.height;
    rt_vec3 *c = malloc(sizeof *c * w * h);
    cr_assert(c);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) c[y * w + x] = rt_render_pixel(&tr, x, y);
    return c;
}

/* ---- Random numbers ---- */

Test(montecarlo, rng_is_a_pure_function_of_its_key)
{
    cr_expect_eq(rt_rng_hash(1, 2), rt_rng_hash(1, 2));
    cr_expect_neq(rt_rng_hash(1, 2), rt_rng_hash(2, 1));
    cr_expect_neq(rt_rng_hash(0, 0), 0u);
    cr_expect_neq(rt_rng_pixel_key(3, 4), rt_rng_pixel_key(4, 3));
    cr_expect_neq(rt_rng_child(7, 1), rt_rng_child(7, 2));
    /* The conversion is exact: the top 32 bits over 2^32. */
    cr_expect_eq(rt_to_double(rt_rng_unit(0)), 0.0);
    cr_expect_eq(rt_to_double(rt_rng_unit(1ull << 63)), 0.5);
    cr_expect_eq(rt_to_double(rt_rng_unit(0x0000000100000000ull)), ldexp(1.0, -32));
    cr_expect(rt_to_double(rt_rng_unit(~0ull)) < 1.0);
    rt_sampler s = {rt_rng_pixel_key(10, 20), 5, 2};
    rt_vec2 a = rt_sample_2d(&s, 9, RT_PURPOSE_LENS), b = rt_sample_2d(&s, 9, RT_PURPOSE_LENS);
    cr_expect(a.u == b.u && a.v == b.v);
}

/* 2^16 numbers in 64 bins: chi-square with 63 degrees of freedom below its 0.999
 * quantile (103.4), for the 1D numbers and for (u, v) pairs on an 8 x 8 grid. */
Test(montecarlo, rng_is_uniform_chi_square)
{
    enum { N = 1 << 16, BINS = 64 };
    uint32_t one[BINS] = {0}, two[BINS] = {0};
    for (uint32_t i = 0; i < N; i++) {
        uint64_t bits = rt_rng_hash(rt_rng_pixel_key(i % 256, i / 256), 12345);
        double u = rt_to_double(rt_rng_unit(bits)), v = rt_to_double(rt_rng_unit(bits << 32));
        one[(int)(u * BINS)]++;
        two[(int)(u * 8) * 8 + (int)(v * 8)]++;
    }
    double expect = (double)N / BINS, chi1 = 0, chi2 = 0;
    for (int b = 0; b < BINS; b++) {
        chi1 += (one[b] - expect) * (one[b] - expect) / expect;
        chi2 += (two[b] - expect) * (two[b] - expect) / expect;
    }
    cr_expect(chi1 < 103.4, "1D chi-square %.1f", chi1);
    cr_expect(chi2 < 103.4, "2D chi-square %.1f", chi2);
}

Test(montecarlo, permutation_is_a_bijection)
{
    static uint8_t seen[1 << 12];
    for (uint32_t bits = 0; bits <= 12; bits++)
        for (uint64_t key = 0; key < 3; key++) {
            memset(seen, 0, sizeof seen);
            for (uint32_t i = 0; i < 1u << bits; i++) {
                uint32_t p = rt_rng_permute(i, bits, key * 977);
                cr_assert(p < 1u << bits);
                cr_assert_not(seen[p], "bits %u key %u: %u taken twice", bits, (unsigned)key, p);
                seen[p] = 1;
            }
        }
}

/* The 4^k samples of a pixel fall one in each stratum, for every purpose and node. */
Test(montecarlo, stratified_draws_cover_every_stratum)
{
    for (uint32_t log = 1; log <= 3; log++) {
        uint32_t side = 1u << log, n = side * side;
        for (uint32_t purpose = 0; purpose < 6; purpose++) {
            uint8_t seen[64] = {0};
            for (uint32_t k = 0; k < n; k++) {
                rt_sampler s = {rt_rng_pixel_key(1, 2), k, log};
                rt_vec2 p = rt_sample_2d(&s, rt_rng_child(0, 4), purpose);
                double u = rt_to_double(p.u), v = rt_to_double(p.v);
                cr_assert(u >= 0 && u < 1 && v >= 0 && v < 1);
                uint32_t cell = (uint32_t)(v * side) * side + (uint32_t)(u * side);
                cr_assert_not(seen[cell], "strata 4^%u purpose %u: cell %u twice", log, purpose, cell);
                seen[cell] = 1;
            }
        }
    }
}

Test(montecarlo, cosine_directions_lie_in_the_hemisphere_with_mean_cosine_two_thirds)
{
    rt_vec3 n = rt_v3_normalize(v3(0.3, -0.5, 0.8));
    double mean = 0;
    enum { N = 4096 };
    for (uint32_t k = 0; k < N; k++) {
        rt_sampler s = {rt_rng_pixel_key(0, 0), k, 6};
        rt_vec3 d = rt_sample_cosine_hemisphere(rt_sample_2d(&s, 0, RT_PURPOSE_DIFFUSE), n);
        double c = rt_to_double(rt_v3_dot(d, n));
        cr_assert(c >= -EXACT, "direction below the surface");
        cr_assert(fabs(rt_to_double(rt_v3_length(d)) - 1) < EXACT);
        mean += c / N;
    }
    /* E[cos] under the density cos/pi is 2/3. */
    cr_expect(fabs(mean - 2.0 / 3.0) < 2e-3, "mean cosine %.5f", mean);
}

/* The Blinn-Phong lobe's half vectors: unit, above n, with E[cos] = (n + 1) / (n + 2)
 * for a density proportional to cos^n (within 4 standard errors of 4096 draws). */
Test(montecarlo, half_vectors_follow_the_blinn_phong_lobe)
{
    rt_vec3 nrm = rt_v3_normalize(v3(-0.2, 0.9, 0.4));
    double exponents[3] = {0, 20, 128};
    enum { N = 4096 };
    for (int e = 0; e < 3; e++) {
        double n = exponents[e], mean = 0;
        for (uint32_t k = 0; k < N; k++) {
            rt_sampler s = {rt_rng_pixel_key(3, 1), k, 6};
            rt_vec3 h = rt_sample_blinn_half_vector(rt_sample_2d(&s, 0, RT_PURPOSE_GLOSSY), nrm, rt_from_double(n));
            double c = rt_to_double(rt_v3_dot(h, nrm));
            cr_assert(c >= -EXACT, "n = %g: half vector below the surface", n);
            cr_assert(fabs(rt_to_double(rt_v3_length(h)) - 1) < EXACT);
            mean += c / N;
        }
        double want = (n + 1) / (n + 2), se = sqrt(((n + 1) / (n + 3) - want * want) / N);
        cr_expect(fabs(mean - want) < 4 * se, "n = %g: mean cosine %.5f, want %.5f (se %.5f)", n, mean, want, se);
    }
}

/* ---- Estimators ---- */

/* A closed diffuse enclosure with emission e and albedo rho: every path gathers e at
 * each of its depth + 1 hits with weight rho^bounce, so each pixel is exactly the
 * finite sum, which tends to e / (1 - rho). */
Test(montecarlo, white_furnace_gives_the_finite_bounce_sum)
{
    rt_material m = material(v3(0.5, 0.5, 0.5), v3(0, 0, 0), v3(0.25, 0.25, 0.25));
    uint32_t depths[3] = {0, 3, 40};
    for (int i = 0; i < 3; i++)
        for (uint32_t mode = 1; mode <= 2; mode++) {
            rt_trace_settings t = furnace_trace(depths[i]);
            t.monte_carlo = mode;
            t.samples_per_pixel_index = 1;
            built_scene b = furnace(&m, t, 4);
            rt_vec3 *c = render_colors(&b.scene);
            double want = finite_sum(0.25, 0.5, depths[i]);
            for (int p = 0; p < 16; p++)
                cr_expect(fabs(rt_to_double(c[p].y) - want) < 1e-6, "depth %u mode %u: %.9f, want %.9f", depths[i],
                          mode, rt_to_double(c[p].y), want);
            if (depths[i] == 40) cr_expect(fabs(rt_to_double(c[0].x) - 0.5) < 1e-6, "not e / (1 - rho)");
            free(c);
            free(b.memory);
        }
}

/* Diffuse (0.6, 0.1, 0.1) and mirror (0.1, 0.1, 0.5) at once; e = 0.1.
 * Caustics in effect (it needs shadows on): every bounce weighs kd + ks.
 * Caustics off, or shadows off: after a diffuse bounce only diffuse bounces follow,
 * so L(d) = e + kd L_diffuse(d + 1) + ks L(d + 1), L_diffuse(d) = e + kd L_diffuse(d + 1). */
Test(montecarlo, caustics_rule_in_a_furnace)
{
    double kd[3] = {0.6, 0.1, 0.1}, ks[3] = {0.1, 0.1, 0.5}, e = 0.1;
    rt_material m = material(v3(kd[0], kd[1], kd[2]), v3(ks[0], ks[1], ks[2]), v3(e, e, e));
    const uint32_t depth = 6;
    for (int variant = 0; variant < 3; variant++) {
        rt_trace_settings t = furnace_trace(depth);
        t.random_single_branching = false;
        t.caustics = variant != 1;
        t.shadows = variant == 2 ? 0 : 1;
        bool caustics = variant == 0;
        built_scene b = furnace(&m, t, 2);
        rt_vec3 *c = render_colors(&b.scene);
        for (int ch = 0; ch < 3; ch++) {
            double l = e, l_diffuse = e; /* at the last depth */
            for (uint32_t d = 0; d < depth; d++) {
                double next = e + kd[ch] * l_diffuse + ks[ch] * l;
                l_diffuse = e + kd[ch] * l_diffuse;
                l = caustics ? finite_sum(e, kd[ch] + ks[ch], d + 1) : next;
            }
            double got = rt_to_double(ch == 0 ? c[0].x : ch == 1 ? c[0].y : c[0].z);
            cr_expect(fabs(got - l) < 1e-6, "variant %d channel %d: %.9f, want %.9f", variant, ch, got, l);
        }
        free(c);
        free(b.memory);
    }
}

/* Random single branching follows one of the two branches, weighted by the inverse of
 * its probability: per-sample values now vary, but their mean is still the finite sum
 * with weight kd + ks. 16 x 16 pixels x 64 samples; within 4 standard errors. */
Test(montecarlo, random_single_branching_is_unbiased)
{
    double kd[3] = {0.6, 0.1, 0.1}, ks[3] = {0.1, 0.1, 0.5}, e = 0.1;
    rt_material m = material(v3(kd[0], kd[1], kd[2]), v3(ks[0], ks[1], ks[2]), v3(e, e, e));
    rt_trace_settings t = furnace_trace(6);
    t.random_single_branching = true;
    t.caustics = true;
    t.shadows = 1;
    t.samples_per_pixel_index = 3;
    built_scene b = furnace(&m, t, 16);
    rt_vec3 *c = render_colors(&b.scene);
    for (int ch = 0; ch < 3; ch++) {
        double mean = 0, sq = 0, v;
        for (int p = 0; p < 256; p++) {
            v = rt_to_double(ch == 0 ? c[p].x : ch == 1 ? c[p].y : c[p].z);
            mean += v / 256;
            sq += v * v / 256;
        }
        double se = sqrt((sq - mean * mean) / 255), want = finite_sum(e, kd[ch] + ks[ch], 6);
        cr_expect(se > 0, "channel %d: no variance, so no branching happened", ch);
        cr_expect(fabs(mean - want) < 4 * se + 1e-9, "channel %d: mean %.5f, want %.5f (se %.5f)", ch, mean, want, se);
    }
    free(c);
    free(b.memory);
}

/* A floor (k_d 0.8, or with mirror = true k_s 1 and Shininess 10^6) lit by a size x size
 * area light 2 above it, turned by light_rotation_x degrees about X (180: facing down);
 * a 1-pixel camera 0.5 above the floor looks straight down (look_up: straight up, at
 * the light). With a blocker, an opaque half-plane halfway up hides the half x < 0 of
 * the light. Returns the pixel's red channel. */
typedef struct {
    bool blocker, mirror, look_up;
    double size, light_rotation_x;
    uint32_t spp_index;
} floor_scene;

static double floor_under_light(floor_scene f)
{
    static rt_material mats[1];
    mats[0] = f.mirror ? material(v3(0, 0, 0), v3(1, 1, 1), v3(0, 0, 0))
                       : material(v3(0.8, 0.8, 0.8), v3(0, 0, 0), v3(0, 0, 0));
    if (f.mirror) mats[0].shininess = RT_C(1e6);
    static rt_mesh_desc mesh;
    mesh = rt_builtin_mesh_square();
    static rt_object_desc objs[2];
    objs[0].kind = objs[1].kind = RT_SHAPE_MESH;
    objs[0].world = rt_affine_trs(v3(0, 0, 0), v3(-90, 0, 0), v3(20, 20, 1));
    objs[1].world = rt_affine_trs(v3(-5, 1, 0), v3(90, 0, 0), v3(10, 10, 1));
    static rt_light_desc light;
    memset(&light, 0, sizeof light);
    light.kind = RT_LIGHT_AREA;
    light.world = rt_affine_trs(v3(0, 2, 0), v3(f.light_rotation_x, 0, 0), v3(f.size, 1, f.size));
    light.color = v3(1, 1, 1);
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.materials = mats;
    d.material_count = 1;
    d.meshes = &mesh;
    d.mesh_count = 1;
    d.objects = objs;
    d.object_count = f.blocker ? 2 : 1;
    d.lights = &light;
    d.light_count = 1;
    d.camera = mc_camera(rt_affine_trs(v3(0, 0.5, 0), v3(f.look_up ? 90 : -90, 0, 0), v3(1, 1, 1)), 1, 1);
    d.camera.trace.shadows = 1;
    d.camera.trace.reflections = f.mirror; /* else direct light only */
    d.camera.trace.diffuse_reflection = false;
    d.camera.trace.samples_per_pixel_index = f.spp_index;
    built_scene b;
    build(&d, &b);
    rt_vec3 *c = render_colors(&b.scene);
    double v = rt_to_double(c[0].x);
    free(c);
    free(b.memory);
    return v;
}

Test(montecarlo, area_light_soft_shadow_and_one_sided_emission)
{
    floor_scene f = {.size = 1, .light_rotation_x = 180, .spp_index = 4};
    double full = floor_under_light(f);
    f.blocker = true;
    double half = floor_under_light(f);
    cr_expect(full > 0.5 && full <= 0.8 + 1e-9, "unshadowed floor %.4f", full);
    cr_expect(fabs(half / full - 0.5) < 0.02, "half-covered light gives %.4f of %.4f", half, full);
    f.blocker = false;
    f.light_rotation_x = 0;
    cr_expect_eq(floor_under_light(f), 0.0, "a light facing away still lights");
}

/* An area light is a Lambertian emitter (format.md §11.4): a small light straight above
 * the floor gives k_d = 0.8; turned by 60 degrees it sends cos 60 = half of that. */
Test(montecarlo, area_light_is_lambertian)
{
    floor_scene f = {.size = 0.01, .light_rotation_x = 180, .spp_index = 1};
    double facing = floor_under_light(f);
    f.light_rotation_x = 240;
    double turned = floor_under_light(f);
    cr_expect(fabs(facing - 0.8) < 1e-4, "light facing the floor: %.6f", facing);
    cr_expect(fabs(turned - 0.4) < 1e-3, "light turned by 60 degrees: %.6f", turned);
}

/* A camera ray that meets a light's square from its emitting side brings back the
 * light's emission, RT_AREA_LIGHT_EMISSION x Color (format.md §11.4); from behind it
 * passes through. A reflected ray that meets the square does not: the direct term
 * already counts that light. */
Test(montecarlo, camera_rays_see_area_lights_and_later_rays_do_not)
{
    floor_scene f = {.size = 1, .light_rotation_x = 180, .look_up = true};
    cr_expect_eq(floor_under_light(f), rt_to_double(RT_AREA_LIGHT_EMISSION), "the light's face");
    f.light_rotation_x = 0;
    cr_expect_eq(floor_under_light(f), 0.0, "the light's back");
    /* Looking down at a sharp mirror: the reflected ray goes straight up into the light. */
    f = (floor_scene){.size = 1, .light_rotation_x = 180, .mirror = true, .spp_index = 2};
    double mirror = floor_under_light(f);
    cr_expect(mirror < 1.0, "a reflected ray collected the light's emission: %.4f", mirror);
}

/* The glossy branch mirrors the view vector about half vectors drawn from the
 * Blinn-Phong lobe of exponent Shininess (format.md §11.6): for a density proportional to
 * cos^n, E[cos] = (n + 1) / (n + 2). Read from the ray log of 256 samples of a glossy
 * floor (k_s 1, k_d 0, Shininess 20) seen at 45 degrees. */
Test(montecarlo, glossy_rays_sample_the_blinn_phong_lobe)
{
    static rt_material m;
    m = material(v3(0, 0, 0), v3(1, 1, 1), v3(0, 0, 0));
    m.shininess = RT_C(20.0);
    static rt_mesh_desc mesh;
    mesh = rt_builtin_mesh_square();
    static rt_object_desc floor;
    floor.kind = RT_SHAPE_MESH;
    floor.world = rt_affine_trs(v3(0, 0, 0), v3(-90, 0, 0), v3(20, 20, 1));
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.materials = &m;
    d.material_count = 1;
    d.meshes = &mesh;
    d.mesh_count = 1;
    d.objects = &floor;
    d.object_count = 1;
    d.camera = mc_camera(rt_affine_trs(v3(0, 1, 1), v3(-45, 0, 0), v3(1, 1, 1)), 1, 1);
    d.camera.trace.max_depth = 1;
    d.camera.trace.samples_per_pixel_index = 4;
    built_scene b;
    build(&d, &b);
    static rt_ray_record rays[1 << 12];
    static rt_light_record lights[1 << 12];
    rt_ray_log log = {.rays = rays, .ray_capacity = 1 << 12, .lights = lights, .light_capacity = 1 << 12};
    rt_tracer tr = {.scene = &b.scene, .use_bvh = true, .log = &log};
    rt_render_pixel(&tr, 0, 0);
    cr_assert_not(log.overflow);
    double mean = 0, n = 20;
    uint32_t count = 0, fallbacks = 0;
    for (uint32_t i = 0; i < log.ray_count; i++) {
        const rt_ray_record *r = &rays[i];
        cr_assert_neq(r->kind, RT_RAY_REFLECTION, "a mirror ray in Monte Carlo mode");
        if (r->kind != RT_RAY_GLOSSY) continue;
        const rt_ray_record *parent = &rays[r->parent];
        rt_vec3 nrm = parent->normal_used, v = rt_v3_neg(parent->ray.direction), h = r->half_vector;
        double cos_h = rt_to_double(rt_v3_dot(nrm, h));
        cr_expect(fabs(rt_to_double(rt_v3_length(h)) - 1) < EXACT && cos_h >= 0, "not a unit half vector above N");
        rt_vec3 about_h = rt_v3_sub(rt_v3_scale(h, rt_mul(RT_C(2.0), rt_v3_dot(v, h))), v);
        rt_vec3 mirror = rt_v3_sub(rt_v3_scale(nrm, rt_mul(RT_C(2.0), rt_v3_dot(v, nrm))), v);
        rt_vec3 want = r->mirror_fallback ? mirror : about_h;
        cr_expect(rt_to_double(rt_v3_length(rt_v3_sub(r->ray.direction, want))) < 1e-6, "direction not R(h)");
        cr_expect(r->mirror_fallback || rt_v3_dot(r->ray.direction, nrm) > RT_ZERO);
        fallbacks += r->mirror_fallback;
        mean += cos_h;
        count++;
    }
    cr_assert_eq(count, 256u, "one glossy ray per sample");
    mean /= count;
    /* Var(cos) = (n + 1) / (n + 3) - E[cos]^2; 256 samples, within 4 standard errors. */
    double want = (n + 1) / (n + 2), se = sqrt(((n + 1) / (n + 3) - want * want) / count);
    fprintf(stderr, "montecarlo: glossy n = 20: mean cos(theta_H) %.5f, want %.5f (se %.5f), %u fallbacks\n", mean,
            want, se, fallbacks);
    cr_expect(fabs(mean - want) < 4 * se, "mean cos(theta_H) %.5f, want %.5f", mean, want);
    free(b.memory);
}

/* ---- Convergence and energy on the corpus Cornell box ---- */

static double channel(rt_vec3 c, int ch) { return rt_to_double(ch == 0 ? c.x : ch == 1 ? c.y : c.z); }

/* Over colours clamped to [0, 1] as the image stores them: the lights' squares, which
 * camera rays see far above 1, count as the white they show. */
static double rms_error(const rt_vec3 *a, const rt_vec3 *b, uint32_t n)
{
    double s = 0;
    for (uint32_t i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++) {
            double d = fmin(fmax(channel(a[i], ch), 0), 1) - fmin(fmax(channel(b[i], ch), 0), 1);
            s += d * d;
        }
    return sqrt(s / (3.0 * n));
}

/* Uniform random sampling (mode 1) at 1, 4, 16 and 64 spp against 4096 spp on 8 x 8
 * pixels: the least-squares slope of log RMS error over log spp is -0.5 +- 0.1. */
Test(montecarlo, error_falls_as_one_over_sqrt_spp, .timeout = 120)
{
    rtp_scene b = open_corpus("more/cornell_ray.yaml", 8);
    b.scene.camera.trace.monte_carlo = 1;
    b.scene.camera.trace.samples_per_pixel_index = 6;
    rt_vec3 *ref = render_colors(&b.scene);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (uint32_t i = 0; i < 4; i++) {
        b.scene.camera.trace.samples_per_pixel_index = i;
        rt_vec3 *c = render_colors(&b.scene);
        double x = log(pow(4, i)), y = log(rms_error(c, ref, 64));
        fprintf(stderr, "montecarlo: cornell 8x8 uniform %4.0f spp: RMS error %.4f\n", pow(4, i), exp(y));
        sx += x, sy += y, sxx += x * x, sxy += x * y;
        free(c);
    }
    double slope = (4 * sxy - sx * sy) / (4 * sxx - sx * sx);
    cr_expect(fabs(slope + 0.5) < 0.1, "slope %.3f", slope);
    free(ref);
    rtp_scene_close(&b);
}

/* No sample is brighter than a path can carry, except a camera ray that ends on a
 * light's square: it brings back exactly that light's emission (format.md §11.4). Per
 * channel, each of the depth + 1 hits adds at most E = max k_e + sum over lights of
 * (max k_d * ambient + colour * A * (max k_d + max k_s)), A = min(1, 1 / Const Atten)
 * bounding the distance attenuation and cosines (N.L, the light's, the lobe's) <= 1,
 * and each bounce weighs at most W = max (k_d + k_s + k_t), the maxima over the
 * materials objects use. */
static bool is_a_lights_emission(const rt_scene *s, rt_vec3 c)
{
    for (uint32_t i = 0; i < s->light_count; i++) {
        rt_vec3 e = rt_v3_scale(s->lights[i].color, RT_AREA_LIGHT_EMISSION);
        if (s->lights[i].kind == RT_LIGHT_AREA && rt_v3_equal(c, e)) return true;
    }
    return false;
}

Test(montecarlo, no_sample_brighter_than_the_bound)
{
    rtp_scene b = open_corpus("more/cornell_ray.yaml", 16);
    const rt_scene *s = &b.scene;
    b.scene.camera.trace.samples_per_pixel_index = 2;
    double bound[3], brightest[3] = {0, 0, 0};
    for (int ch = 0; ch < 3; ch++) {
        double ke = 0, kd = 0, ks = 0, w = 0;
        for (uint32_t i = 0; i < s->object_count; i++) {
            const rt_material *m = &s->materials[s->objects[i].material];
            ke = fmax(ke, channel(m->emissive.color, ch));
            kd = fmax(kd, channel(m->diffuse.color, ch));
            ks = fmax(ks, channel(m->specular.color, ch));
            w = fmax(w, channel(m->diffuse.color, ch) + channel(m->specular.color, ch) +
                            channel(m->transmittance.color, ch));
        }
        double e = ke;
        for (uint32_t i = 0; i < s->light_count; i++) {
            const rt_light *l = &s->lights[i];
            double a = rt_to_double(l->atten_const) > 1 ? 1 / rt_to_double(l->atten_const) : 1;
            e += kd * channel(l->ambient, ch) + channel(l->color, ch) * a * (kd + ks);
        }
        bound[ch] = finite_sum(e, w, s->camera.trace.max_depth);
    }
    rt_tracer tr = {.scene = s, .use_bvh = true};
    uint32_t on_light = 0;
    for (uint32_t y = 0; y < 16; y++)
        for (uint32_t x = 0; x < 16; x++)
            for (uint32_t k = 0; k < 16; k++) {
                rt_vec3 c = rt_render_sample(&tr, x, y, k);
                if (is_a_lights_emission(s, c)) {
                    on_light++;
                    continue;
                }
                for (int ch = 0; ch < 3; ch++) {
                    cr_expect(channel(c, ch) <= bound[ch], "pixel (%u, %u) sample %u channel %d: %.4f above %.4f", x, y,
                              k, ch, channel(c, ch), bound[ch]);
                    brightest[ch] = fmax(brightest[ch], channel(c, ch));
                }
            }
    for (int ch = 0; ch < 3; ch++) {
        fprintf(stderr, "montecarlo: cornell 16x16 channel %d: brightest sample %.4f, bound %.4f\n", ch, brightest[ch],
                bound[ch]);
        cr_expect(brightest[ch] > 0.3, "the box is dark: %.4f", brightest[ch]);
    }
    fprintf(stderr, "montecarlo: cornell 16x16: %u of 4096 samples end on a light\n", on_light);
    cr_expect(on_light > 0, "no camera ray saw the lights' squares");
    rtp_scene_close(&b);
}

/* ---- Sample count types ---- */

/* Camera rays the pixel took, counted in the debugger's log. */
static uint32_t camera_rays(const rt_scene *scene, uint32_t x, uint32_t y)
{
    static rt_ray_record rays[1 << 16];
    static rt_light_record lights[1 << 16];
    rt_ray_log log = {.rays = rays, .ray_capacity = 1 << 16, .lights = lights, .light_capacity = 1 << 16};
    rt_tracer tr = {.scene = scene, .use_bvh = true, .log = &log};
    rt_render_pixel(&tr, x, y);
    cr_assert_not(log.overflow);
    uint32_t n = 0;
    for (uint32_t i = 0; i < log.ray_count; i++) n += rays[i].kind == RT_RAY_CAMERA;
    return n;
}

/* A white diffuse sphere before a black background, lit by a point light at the camera. */
static built_scene sphere_scene(uint32_t monte_carlo, uint32_t count_type)
{
    static rt_material m;
    m = material(v3(1, 1, 1), v3(0, 0, 0), v3(0, 0, 0));
    static rt_object_desc sphere;
    sphere.kind = RT_SHAPE_SPHERE;
    sphere.world = rt_affine_trs(v3(0, 0, -3), v3(0, 0, 0), v3(2, 2, 2));
    static rt_light_desc light;
    memset(&light, 0, sizeof light);
    light.kind = RT_LIGHT_POINT;
    light.world = rt_affine_identity();
    light.color = v3(1, 1, 1);
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.materials = &m;
    d.material_count = 1;
    d.objects = &sphere;
    d.object_count = 1;
    d.lights = &light;
    d.light_count = 1;
    d.camera = mc_camera(rt_affine_identity(), 16, 60);
    d.camera.trace.monte_carlo = monte_carlo;
    d.camera.trace.sample_count_type = count_type;
    d.camera.trace.min_samples_index = 0;
    d.camera.trace.max_samples_index = 2; /* at most 64 */
    d.camera.trace.difference_threshold = RT_C(0.02);
    d.camera.trace.std_error_threshold = RT_C(0.02);
    built_scene b;
    build(&d, &b);
    return b;
}

Test(montecarlo, adaptive_recursion_refines_only_where_corners_differ)
{
    built_scene b = sphere_scene(0, 1);
    /* Background corner: 4 corner rays. Silhouette: subdivided down to 8 x 8 squares at
     * most, 5 new points per split: 4 + 5 (1 + 4 + 16) rays. */
    cr_expect_eq(camera_rays(&b.scene, 0, 0), 4u);
    uint32_t edge = 0;
    for (uint32_t x = 0; x < 16; x++) {
        uint32_t n = camera_rays(&b.scene, x, 8);
        cr_expect(n <= 109u, "pixel %u: %u rays", x, n);
        if (n > edge) edge = n;
    }
    cr_expect(edge > 4u, "no pixel on row 8 was subdivided");
    /* In Monte Carlo mode the skeleton falls back to the constant count. */
    b.scene.camera.trace.monte_carlo = 2;
    b.scene.camera.trace.samples_per_pixel_index = 1;
    cr_expect_eq(camera_rays(&b.scene, 0, 0), 4u);
    cr_expect_eq(camera_rays(&b.scene, 8, 8), 4u);
    free(b.memory);
}

Test(montecarlo, std_error_sampling_stops_when_the_mean_is_certain)
{
    for (uint32_t mc = 0; mc <= 2; mc++) {
        built_scene b = sphere_scene(mc, 2);
        /* Black background: no variance, so the first two samples decide. */
        cr_expect_eq(camera_rays(&b.scene, 0, 0), 2u, "mode %u", mc);
        b.scene.camera.trace.min_samples_index = 2;
        cr_expect_eq(camera_rays(&b.scene, 0, 0), 16u, "mode %u: minimum ignored", mc);
        /* The silhouette is uncertain: more samples, never above the maximum. */
        b.scene.camera.trace.min_samples_index = 0;
        uint32_t most = 0;
        for (uint32_t x = 0; x < 16; x++) {
            uint32_t n = camera_rays(&b.scene, x, 8);
            cr_expect(n <= 64u);
            if (n > most) most = n;
        }
        cr_expect(most > 2u, "mode %u: the silhouette took %u samples", mc, most);
        free(b.memory);
    }
}

/* ---- Camera ---- */

/* Every lens point aims at the same point of the plane in focus; without aperture
 * the lens ray is the pinhole ray. */
Test(montecarlo, thin_lens_rays_meet_in_the_focal_plane)
{
    rt_camera_desc cd = mc_camera(rt_affine_trs(v3(1, 2, 3), v3(-20, 30, 0), v3(1, 1, 1)), 64, 45);
    cd.trace.focus_distance = RT_C(3.5);
    cd.trace.aperture_size = RT_C(0.6);
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.camera = cd;
    built_scene b;
    build(&d, &b);
    const rt_camera *cam = &b.scene.camera;
    rt_real x = RT_C(0.3), y = RT_C(0.8);
    rt_ray pin = rt_camera_ray(cam, x, y);
    /* The pinhole ray reaches the focal plane (distance 3.5 along forward) at t = 3.5 / cos. */
    rt_real t = rt_div(RT_C(3.5), rt_v3_dot(pin.direction, cam->forward));
    rt_vec3 focus = rt_v3_madd(pin.origin, pin.direction, t);
    for (uint32_t k = 0; k < 16; k++) {
        rt_sampler s = {rt_rng_pixel_key(0, 0), k, 2};
        rt_ray r = rt_camera_lens_ray(cam, x, y, rt_sample_2d(&s, 0, RT_PURPOSE_LENS));
        rt_vec3 off = rt_v3_sub(r.origin, cam->eye);
        cr_expect(rt_to_double(rt_v3_length(off)) <= 0.3 + EXACT, "origin off the lens");
        cr_expect(fabs(rt_to_double(rt_v3_dot(off, cam->forward))) < EXACT, "lens not across the view");
        rt_real tk = rt_div(rt_v3_dot(rt_v3_sub(focus, r.origin), cam->forward), rt_v3_dot(r.direction, cam->forward));
        rt_vec3 miss = rt_v3_sub(rt_v3_madd(r.origin, r.direction, tk), focus);
        cr_expect(rt_to_double(rt_v3_length(miss)) < EXACT, "lens sample %u misses the focal point", k);
    }
    b.scene.camera.trace.aperture_size = RT_ZERO;
    rt_vec2 lens = {RT_C(0.7), RT_C(0.2)};
    rt_ray same = rt_camera_lens_ray(&b.scene.camera, x, y, lens);
    cr_expect(memcmp(&same, &pin, sizeof pin) == 0, "no aperture, yet not the pinhole ray");
    free(b.memory);
}

/* ---- Determinism ---- */

/* The same bytes whatever the tile shape and order, and on 1 or 2 threads. */
Test(montecarlo, image_does_not_depend_on_tiles_or_threads)
{
    rtp_scene b = open_corpus("more/chess_mcpt.yaml", 24);
    b.scene.camera.trace.samples_per_pixel_index = 1;
    rt_tracer tr = {.scene = &b.scene, .use_bvh = true};
    size_t bytes = 24 * 24 * 3;
    uint8_t *rows = calloc(bytes, 1), *tiles = calloc(bytes, 1), *one = calloc(bytes, 1), *two = calloc(bytes, 1);
    rt_render_region(&tr, 0, 0, 24, 24, rows);
    /* 5 x 7 tiles from the last to the first. */
    for (int ty = 3; ty >= 0; ty--)
        for (int tx = 4; tx >= 0; tx--) {
            uint32_t x0 = tx * 5, y0 = ty * 7, x1 = x0 + 5 < 24 ? x0 + 5 : 24, y1 = y0 + 7 < 24 ? y0 + 7 : 24;
            rt_render_region(&tr, x0, y0, x1, y1, tiles);
        }
    rtp_threads_options p1 = {1, 8, false, NULL}, p2 = {2, 3, false, NULL};
    cr_assert(rtp_threads_render(&tr, &p1, one));
    cr_assert(rtp_threads_render(&tr, &p2, two));
    cr_expect(memcmp(rows, tiles, bytes) == 0, "tile order changed the image");
    cr_expect(memcmp(rows, one, bytes) == 0, "1 thread changed the image");
    cr_expect(memcmp(rows, two, bytes) == 0, "2 threads changed the image");
    free(rows), free(tiles), free(one), free(two);
    rtp_scene_close(&b);
}

/* ---- Command line ---- */

/* --spp N is --aa log4(N); other counts are usage errors. */
Test(montecarlo, spp_option_takes_powers_of_four)
{
    const char *good[4][2] = {{"1", "0"}, {"4", "1"}, {"64", "3"}, {"16384", "7"}};
    for (int k = 0; k < 4; k++) {
        char *argv[2] = {"--spp", (char *)good[k][0]};
        int i = 0;
        rtp_scene_options o = rtp_scene_default_options();
        cr_expect_eq(rtp_cli_scene_option("render", 2, argv, &i, &o), 1);
        cr_expect_eq(o.aa, atoi(good[k][1]), "--spp %s", good[k][0]);
        cr_expect_eq(i, 1);
    }
    const char *bad[6] = {"0", "2", "8", "100", "65536", "x"};
    for (int k = 0; k < 6; k++) {
        char *argv[2] = {"--spp", (char *)bad[k]};
        int i = 0;
        rtp_scene_options o = rtp_scene_default_options();
        cr_expect(rtp_cli_scene_option("render", 2, argv, &i, &o) < 0, "--spp %s accepted", bad[k]);
    }
}

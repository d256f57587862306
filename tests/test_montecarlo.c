/* Monte Carlo rendering (core/rng.c, sample.c, path_trace.c, render_pixel.c): the random
 * numbers, the estimators' expected values (white furnace, caustics rule, single
 * branching, soft shadows), convergence as 1/sqrt(spp), the energy bound, the
 * sample count types, the thin lens, and independence from tiles and threads. */
#include "builtin_mesh.h"
#include "cli/cli.h"
#include "load/scene_open.h"
#include "path_trace.h"
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

/* A floor lit by a 1 x 1 area light 2 above it; a pinhole camera sees the floor point
 * under the light's centre. An opaque half-plane halfway up hides the half x < 0 of the
 * light, which by symmetry halves the light: soft shadows from area sampling. With the
 * light turned to face up, the floor gets nothing. */
static double floor_under_light(bool blocker, double light_rotation_x)
{
    static rt_material mats[1];
    mats[0] = material(v3(0.8, 0.8, 0.8), v3(0, 0, 0), v3(0, 0, 0));
    static rt_mesh_desc mesh;
    mesh = rt_builtin_mesh_square();
    static rt_object_desc objs[2];
    objs[0].kind = objs[1].kind = RT_SHAPE_MESH;
    objs[0].world = rt_affine_trs(v3(0, 0, 0), v3(-90, 0, 0), v3(20, 20, 1));
    objs[1].world = rt_affine_trs(v3(-5, 1, 0), v3(90, 0, 0), v3(10, 10, 1));
    static rt_light_desc light;
    memset(&light, 0, sizeof light);
    light.kind = RT_LIGHT_AREA;
    light.world = rt_affine_trs(v3(0, 2, 0), v3(light_rotation_x, 0, 0), v3(1, 1, 1));
    light.color = v3(1, 1, 1);
    rt_scene_desc d;
    memset(&d, 0, sizeof d);
    d.materials = mats;
    d.material_count = 1;
    d.meshes = &mesh;
    d.mesh_count = 1;
    d.objects = objs;
    d.object_count = blocker ? 2 : 1;
    d.lights = &light;
    d.light_count = 1;
    d.camera = mc_camera(rt_affine_trs(v3(0, 0.5, 0), v3(-90, 0, 0), v3(1, 1, 1)), 1, 1);
    d.camera.trace.shadows = 1;
    d.camera.trace.reflections = false; /* direct light only */
    d.camera.trace.samples_per_pixel_index = 4;
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
    double full = floor_under_light(false, 180), half = floor_under_light(true, 180);
    cr_expect(full > 0.5 && full <= 0.8 + 1e-9, "unshadowed floor %.4f", full);
    cr_expect(fabs(half / full - 0.5) < 0.02, "half-covered light gives %.4f of %.4f", half, full);
    cr_expect_eq(floor_under_light(false, 0), 0.0, "a light facing away still lights");
}

/* ---- Convergence and energy on the corpus Cornell box ---- */

static double rms_error(const rt_vec3 *a, const rt_vec3 *b, uint32_t n)
{
    double s = 0;
    for (uint32_t i = 0; i < n; i++) {
        rt_vec3 d = rt_v3_sub(a[i], b[i]);
        s += rt_to_double(rt_v3_dot(d, d));
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

/* No pixel is brighter than a path can carry. Per channel, each of the depth + 1 hits
 * adds at most E = max k_e + sum over lights of (max k_d * ambient + colour * A *
 * (max k_d + max k_s)), A = min(1, 1 / Const Atten) bounding the distance attenuation
 * and cosines <= 1, and each bounce weighs at most W = max (k_d + k_s + k_t), the
 * maxima over the materials objects use. */
static double channel(rt_vec3 c, int ch) { return rt_to_double(ch == 0 ? c.x : ch == 1 ? c.y : c.z); }

Test(montecarlo, no_pixel_brighter_than_the_bound)
{
    rtp_scene b = open_corpus("more/cornell_ray.yaml", 16);
    const rt_scene *s = &b.scene;
    b.scene.camera.trace.samples_per_pixel_index = 2;
    rt_vec3 *c = render_colors(s);
    for (int ch = 0; ch < 3; ch++) {
        double ke = 0, kd = 0, ks = 0, w = 0, brightest = 0;
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
        double bound = finite_sum(e, w, s->camera.trace.max_depth);
        for (uint32_t p = 0; p < 256; p++) {
            cr_expect(channel(c[p], ch) <= bound, "pixel %u channel %d: %.4f above %.4f", p, ch, channel(c[p], ch),
                      bound);
            brightest = fmax(brightest, channel(c[p], ch));
        }
        fprintf(stderr, "montecarlo: cornell 16x16 channel %d: brightest %.4f, bound %.4f\n", ch, brightest, bound);
        cr_expect(brightest > 0.3, "the box is dark: %.4f", brightest);
    }
    free(c);
    rtp_scene_close(&b);
}

/* ---- Sample count types ---- */

/* Camera rays the pixel took, counted in the debugger's log. */
static uint32_t camera_rays(const rt_scene *scene, uint32_t x, uint32_t y)
{
    static rt_ray_record rays[1 << 16];
    static rt_light_record lights[1 << 16];
    rt_ray_log log = {rays, 0, 1 << 16, lights, 0, 1 << 16, false};
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

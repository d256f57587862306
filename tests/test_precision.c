/* Precision cases the fixed-point fuzzers found (fuzz/, docs/robustness.md). They run in
 * both builds, with tolerances in units of each build's rounding (ULP, and ABS for the
 * fixed build's absolute lsb), a few times what each build measures: the double build
 * is held to its own precision, not to Q32.32's (each double bound is below the error
 * the fixed build has on the same case). */
#include <criterion/criterion.h>
#include <math.h>

#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "bvh.h"
#include "intersect.h"
#include "scene_query.h"
#include "surface.h"
#include "vec.h"

/* The build's unit roundoff, for bounds that scale with it, and its absolute one. */
#ifdef RT_REAL_FIXED
#define ULP 0x1p-32L
#define ABS 0x1p-32L
#else
#define ULP 0x1p-52L
#define ABS 0.0L
#endif

static long double len_of(rt_vec3 v)
{
    long double x = rt_to_double(v.x), y = rt_to_double(v.y), z = rt_to_double(v.z);
    return sqrtl(x * x + y * y + z * z);
}

static rt_vec3 v3d(double x, double y, double z)
{
    return rt_v3(rt_from_double(x), rt_from_double(y), rt_from_double(z));
}

/* fuzz_triangle: a sliver's cross product is about 1e-6 long, and its squared length kept
 * a few significant bits in Q32.32, so its "unit" normal came out 6e-5 too long; the
 * cross product (27556, -27556, -27556) of a large triangle squared to beyond 2^31 and
 * came out 3% too long. Vectors are now scaled by powers of two first. */
Test(precision, vectors_of_any_length_normalise_to_unit_length)
{
    for (int e = -24; e <= 14; e++) {
        double s = ldexp(1.0, e);
        rt_vec3 v = v3d(0.3 * s, -0.1 * s, 0.5 * s);
        long double len = len_of(rt_v3_normalize(v));
        /* Measured at most 0.3 ULP (double), 4.3 ULP (fixed). */
        cr_assert(fabsl(len - 1) <= 16 * ULP, "2^%d: length %.17Lg", e, len);
        if (e >= -12) {
            long double want = len_of(v), got = rt_to_double(rt_v3_length(v));
            cr_assert(fabsl(got - want) <= 16 * ULP * want + ABS, "2^%d: |v| = %.17Lg, want %.17Lg", e, got, want);
        }
    }
    long double len = len_of(rt_v3_normalize(v3d(27556, -27556, -27556)));
    cr_assert(fabsl(len - 1) <= 16 * ULP, "length %.17Lg", len);
}

/* fuzz_cylinder: a ray along the axis grazing the side. The quarter discriminant a w^2 was
 * about 1e-7, and rounding the product to 2^-32 before its root moved t by 1.2e-5; the
 * root now comes from the exact product (rt_sqrt_mul). */
Test(precision, grazing_cylinder_hit_keeps_its_digits)
{
    rt_vec3 o = v3d(0.33989918511360884, -0.018693170743063092, 0.36738856416195631);
    rt_vec3 d = rt_v3_normalize(v3d(0.081130814272910357, 3.4868155245203525, -0.082855044398456812));
    rt_prim_hit h;
    cr_assert(rt_intersect_cylinder(o, d, RT_ZERO, RT_C(100.0), &h));
    cr_assert_eq(h.part, RT_PART_SURFACE);
    long double want = 0.436093757290318911142801471666L; /* mpmath, 30 digits */
    /* A grazing hit is ill-conditioned: measured 103 ULP (double), 1037 ULP (fixed). */
    cr_assert(fabsl(rt_to_double(h.t) - want) <= 2048 * ULP, "t = %.17g, want %.17Lg", rt_to_double(h.t), want);
}

/* fuzz_bvh: a triangle 1000 across seen from 9000 away. The sum of u az + v bz + w cz
 * passed 2^31 and saturated in Q32.32, and t came out hundreds of units short; it is now
 * one exact sum divided once (rt_dot3_div). */
Test(precision, far_large_triangle_gets_its_distance)
{
    rt_vec3 a = v3d(-600, -500, 400), b = v3d(700, -400, 300), c = v3d(-100, 800, 200);
    rt_vec3 centroid = v3d(0, -100.0 / 3, 300);
    rt_vec3 dir = rt_v3_normalize(v3d(-0.7, -0.4, -0.59));
    long double dist = 9000;
    rt_ray ray = {rt_v3_madd(centroid, dir, rt_from_double(-9000.0)), dir, RT_HIT_EPSILON, RT_REAL_MAX};
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_prim_hit h;
    cr_assert(rt_intersect_triangle(&rs, a, b, c, &h));
    /* Measured: t exact (double), 0.06 ULP of 9000 (fixed); barycentrics within 2.2 ULP. */
    cr_assert(fabsl(rt_to_double(h.t) - dist) <= 16 * ULP * dist, "t = %.17g, want 9000", rt_to_double(h.t));
    cr_assert(fabsl(rt_to_double(h.b1) - 1.0L / 3) <= 16 * ULP && fabsl(rt_to_double(h.b2) - 1.0L / 3) <= 16 * ULP,
              "b1 = %.17g, b2 = %.17g, want 1/3", rt_to_double(h.b1), rt_to_double(h.b2));
}

/* fuzz_bvh: the inverse of a uniform scale of 939. In Q32.32 1 / det = 1 / 939^3 is about
 * five lsb, and the object-space cylinder came out 3.7% off the bounds the BVH holds;
 * each column is now scaled by a power of two before the matrix is inverted, which also
 * keeps uneven scales (0.25 by 1000) exact to 1e-6. */
Test(precision, inverse_of_large_and_small_scales)
{
    const double scales[][3] = {{939.01305310451426, 939.01305310451426, 939.01305310451426},
                                {1.0 / 939, 1.0 / 939, 1.0 / 939},
                                {512, 1, 512},
                                {0.25, 1000, 7}};
    for (int i = 0; i < 4; i++) {
        rt_affine m = rt_affine_trs(v3d(469.5, -12, 3), v3d(10, 20, 30), v3d(scales[i][0], scales[i][1], scales[i][2]));
        rt_affine inv;
        cr_assert(rt_affine_inverse(&m, &inv));
        /* The matrices' own rounding: entries as small as 1 / scale, or as large as scale. */
        double big = fmax(fmax(scales[i][0], scales[i][1]), scales[i][2]);
        double small = fmin(fmin(scales[i][0], scales[i][1]), scales[i][2]);
        long double bound = 8 * ULP * (big + 1 / small);
        for (int k = 0; k < 3; k++) {
            rt_vec3 axis = rt_v3(k == 0 ? RT_ONE : RT_ZERO, k == 1 ? RT_ONE : RT_ZERO, k == 2 ? RT_ONE : RT_ZERO);
            rt_vec3 back = rt_affine_vector(&inv, rt_affine_vector(&m, axis));
            long double err = len_of(rt_v3_sub(back, axis));
            cr_assert(err <= bound, "scale %d, axis %d: inverse off by %.3Lg", i, k, err);
        }
        rt_vec3 p = v3d(1.5, -2.25, 0.125);
        long double err = len_of(rt_v3_sub(rt_affine_point(&inv, rt_affine_point(&m, p)), p));
        /* The translation (469.5 scaled by up to 939) adds its own rounding: measured up
         * to 35 bounds (double, scale 1/939) and 1.6 (fixed). */
        cr_assert(err <= 64 * bound, "scale %d: point off by %.3Lg", i, err);
    }
}

/* BVH boxes are stored in four bytes per coordinate (rt_bound): each stored plane must lie
 * outside the exact one (or on it), and at most one step of the format away. */
Test(precision, bounds_round_outwards_by_at_most_one_step)
{
    const double limits[] = {0.75, 40, 30000, 2e9};
    for (int l = 0; l < 4; l++) {
        rt_real limit = rt_from_double(limits[l]);
        int grid = rt_bound_grid(limit);
        uint64_t state = 12345;
        for (int i = 0; i < 100000; i++) {
            state = state * 6364136223846793005u + 1442695040888963407u;
            double unit = (double)(state >> 11) * 0x1p-53 * 2 - 1; /* in [-1, 1) */
            rt_real x = rt_from_double(unit * limits[l] * ldexp(1.0, -(int)(state % 24)));
            if (i < 4) x = i == 0 ? limit : i == 1 ? rt_neg(limit) : i == 2 ? RT_ZERO : rt_from_double(-1e-30);
            rt_real lo = rt_bound_value(rt_bound_below(x, grid), grid),
                    hi = rt_bound_value(rt_bound_above(x, grid), grid);
            cr_assert(lo <= x && x <= hi, "limit %g: %.17g stored as [%.17g, %.17g]", limits[l], rt_to_double(x),
                      rt_to_double(lo), rt_to_double(hi));
#ifdef RT_REAL_FIXED
            long double step = ldexpl(1.0L, grid - 32);
#else
            long double step = fabsl(rt_to_double(x)) * 0x1p-23L + 0x1p-149L;
#endif
            cr_assert(rt_to_double(hi) - rt_to_double(lo) <= 2 * step, "limit %g: %.17g stored as [%.17g, %.17g]",
                      limits[l], rt_to_double(x), rt_to_double(lo), rt_to_double(hi));
        }
    }
}

/* Builds the scene of one object (with its mesh, or none) in a plain material, in
 * `size` bytes at `memory`. */
static void build_one_object(const rt_object_desc *obj, const rt_mesh_desc *mesh, void *memory, size_t size,
                             rt_scene *scene)
{
    static const rt_material material = {.diffuse = {.texture = RT_NO_TEXTURE},
                                         .specular = {.texture = RT_NO_TEXTURE},
                                         .emissive = {.texture = RT_NO_TEXTURE},
                                         .transmittance = {.texture = RT_NO_TEXTURE},
                                         .index_of_refraction = RT_ONE};
    rt_scene_desc d = {0};
    d.materials = &material;
    d.material_count = 1;
    d.meshes = mesh;
    d.mesh_count = mesh ? 1 : 0;
    d.objects = obj;
    d.object_count = 1;
    d.camera.world = rt_affine_identity();
    d.camera.fov_degrees = RT_C(50.0);
    d.camera.width = d.camera.height = 4;
    rt_arena arena;
    rt_arena_init(&arena, memory, size);
    rt_build_error err;
    cr_assert_eq(rt_scene_build(&d, &arena, NULL, scene, &err), RT_OK, "%s", err.what);
}

/* fuzz_triangle (CI, fixed build): a sliver 2e-3 by 7.6e-6 whose cross product, 5.8e-11
 * in y, rounds to 0 in Q32.32, so the smooth normals and the geometric normal were all
 * zero. The geometric normal now takes the cross product of the edges scaled by powers
 * of two, which keeps its direction (exactly, in double). */
Test(precision, a_slivers_normals_are_unit_length)
{
    static const uint32_t idx[3] = {0, 1, 2};
    rt_vec3 pos[3] = {v3d(0.25, 0.25, 0.25), v3d(0.24999237060546875, 0.25, 0.24804684519767761),
                      v3d(0.25, 0.25, 0.24999237060546875)};
    rt_mesh_desc mesh = {pos, NULL, NULL, 3, idx, 1};
    rt_object_desc obj = {.kind = RT_SHAPE_MESH, .world = rt_affine_identity()};
    size_t size = 1 << 20;
    void *memory = malloc(size);
    rt_scene scene;
    build_one_object(&obj, &mesh, memory, size, &scene);
    rt_ray ray = {v3d(0.2499, 1.0, 0.2495), v3d(0, -1, 0), RT_HIT_EPSILON, RT_REAL_MAX};
    rt_scene_hit hit = {0};
    hit.prim = 0;
    hit.hit.t = RT_C(0.75);
    rt_surface surf = rt_surface_at(&scene, &ray, &hit, true);
    long double gn = len_of(surf.geometric_normal), n = len_of(surf.normal);
    cr_assert(fabsl(gn - 1) <= 16 * ULP && fabsl(n - 1) <= 16 * ULP, "normal lengths %.17Lg, %.17Lg", gn, n);
    cr_assert(rt_to_double(surf.geometric_normal.y) < -0.999999, "the sliver lies in y = 0.25, wound towards -y");
    free(memory);
}

/* The fixed build transforms rotation-free objects by their matrices' diagonals alone
 * (rt_object_point and its kin): the same bits as the whole product, zeros, saturated
 * and one-lsb values included. In double the same holds for nonzero finite values. */
Test(precision, a_diagonal_matrix_transforms_by_its_diagonal_alone)
{
#ifdef RT_REAL_FIXED
    const rt_real values[] = {RT_ZERO,      RT_C(1.0),  RT_C(-2.5), RT_C(3.0e-9), RT_REAL_MAX,
                              -RT_REAL_MAX, (rt_real)1, RT_C(1e5),  RT_C(-7e4),   RT_C(0.4)};
#else
    const rt_real values[] = {RT_C(1.0),     RT_C(-2.5), RT_C(3.0e-9), RT_C(1e300),
                              RT_C(-1e-300), RT_C(1e5),  RT_C(-7e4),   RT_C(0.4)};
#endif
    const int n = (int)(sizeof values / sizeof values[0]);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            rt_affine a = rt_affine_identity();
            a.linear.m[0][0] = values[i];
            a.linear.m[1][1] = values[j];
            a.linear.m[2][2] = values[(i + j) % n];
            a.translation = rt_v3(values[(i + 1) % n], values[(j + 2) % n], values[(i * j) % n]);
            rt_vec3 p = rt_v3(values[(i + 3) % n], values[j], values[(i + 5 * j) % n]);
            rt_vec3 full = rt_affine_point(&a, p), diag = rt_affine_point_diagonal(&a, p);
            cr_assert(!memcmp(&full, &diag, sizeof full), "point %d %d differs", i, j);
            full = rt_mat3_apply(&a.linear, p);
            diag = rt_mat3_apply_diagonal(&a.linear, p);
            cr_assert(!memcmp(&full, &diag, sizeof full), "vector %d %d differs", i, j);
        }
}

/* The quadric test's early miss (rt_line_clears_ball): over random lines from inside
 * the ball to past its margin, up to its range limits, it answers true only where the
 * full test, run as bvh_leaf.h runs it (direction normalised), misses; lines past the
 * margin are cleared. */
Test(precision, a_cleared_line_misses_the_shape)
{
    uint64_t state = 0x9e3779b97f4a7c15u;
    const rt_real t_lo = RT_C(-1.0e9), t_hi = RT_C(1.0e9);
    int cleared = 0, trials = 200000;
    for (int i = 0; i < trials; i++) {
        double r[8];
        for (int k = 0; k < 8; k++) {
            state ^= state << 13, state ^= state >> 7, state ^= state << 17;
            r[k] = (double)(state >> 11) * 0x1p-53;
        }
        bool sphere = i % 2 == 0;
        double r2 = sphere ? 0.25 : 0.5;
        /* A unit direction u, a unit w across it, and the line's closest point w * dist. */
        double z = 2 * r[0] - 1, phi = 6.283185307179586 * r[1], s = sqrt(1 - z * z);
        double u[3] = {s * cos(phi), s * sin(phi), z};
        double a[3] = {fabs(u[0]) < 0.6 ? 1 : 0, fabs(u[0]) < 0.6 ? 0 : 1, 0};
        double w[3] = {u[1] * a[2] - u[2] * a[1], u[2] * a[0] - u[0] * a[2], u[0] * a[1] - u[1] * a[0]};
        double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        bool near_margin = i % 4 < 2;
        /* Near: from inside the ball to just past the margin (a factor sqrt(1.0625)). */
        double dist = sqrt(r2) * (near_margin ? 0.97 + 0.07 * r[2] : 1.06 + r[2]);
        double scale = exp2(-8 + 12 * r[3]), along = 440 * (r[4] - 0.5);
        double o[3], d[3];
        for (int k = 0; k < 3; k++) {
            o[k] = w[k] / wl * dist - u[k] * along;
            d[k] = u[k] * scale;
        }
        rt_vec3 ov = v3d(o[0], o[1], o[2]), dv = v3d(d[0], d[1], d[2]);
        bool in_range = fabs(o[0]) < 255 && fabs(o[1]) < 255 && fabs(o[2]) < 255;
        if (!rt_line_clears_ball(ov, dv, sphere ? RT_C(0.25) : RT_C(0.5))) {
            cr_assert(near_margin || !in_range, "line %d, %.3f from the centre, not cleared", i, dist);
            continue;
        }
        cleared++;
        rt_real len = rt_v3_length(dv);
        rt_vec3 unit = rt_v3_scale(dv, rt_div(RT_ONE, len));
        rt_prim_hit h;
        bool hit =
            sphere ? rt_intersect_sphere(ov, unit, t_lo, t_hi, &h) : rt_intersect_cylinder(ov, unit, t_lo, t_hi, &h);
        cr_assert_not(hit, "line %d, %.6f from the centre, cleared but hits", i, dist);
    }
    cr_assert_gt(cleared, trials / 3);
}

/* fuzz_render: a ray nearly in a triangle's plane, passing 8 triangle widths outside it
 * (it meets the plane at t = 0.297). In Q32.32 its edge functions and det came out 0, 1,
 * 1 and 1 lsb, the sign test accepted, and the "hit" was at t = 0.0057, off the
 * triangle's box: the BVH, culling by that box, did not find it and brute force did. */
Test(precision, a_ray_nearly_in_a_triangles_plane_misses_it)
{
    const double q = 0x1p-32; /* the coordinates are multiples of 2^-32, exact in both builds */
    rt_vec3 a = v3d(2921693987 * q, 8875850643 * q, 5640640963 * q);
    rt_vec3 b = v3d(3143043230 * q, 8904232056 * q, 5462784796 * q);
    rt_vec3 c = v3d(2880040811 * q, 8793859269 * q, 5471806110 * q);
    rt_ray ray = {v3d(4221476255 * q, 9382297604 * q, 5493056827 * q),
                  v3d(2079356978 * q, -511006516 * q, -3723156049 * q), rt_from_double(0.001), RT_REAL_MAX};
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_prim_hit h = {0};
    cr_assert_not(rt_intersect_triangle(&rs, a, b, c, &h), "hit at t = %.17g", rt_to_double(h.t));
}

/* fuzz_plane (fixed): a ray along -y, 2.4e-5 beyond the x edge of a small square seen
 * almost edge-on (its z spans 3e-6), met the square's plane at t = 4: in Q32.32 the
 * edge function of the near edge, about 0.3 lsb, rounded to 0 and put the ray on the
 * edge, so brute force found a hit that the BVH (rightly) culled. No triangle of the
 * square's corners may be hit. */
Test(precision, a_ray_beyond_an_edge_of_a_triangle_seen_edge_on_misses_it)
{
    const double q = 0x1p-32;
    rt_vec3 v[4] = {v3d(-34493956099 * q, -34183576963 * q, -34175179745 * q),
                    v3d(-34225520643 * q, -34183576957 * q, -34175179739 * q),
                    v3d(-34225520637 * q, -34452012413 * q, -34175192607 * q),
                    v3d(-34493956093 * q, -34452012419 * q, -34175192613 * q)};
    rt_ray ray = {v3d(-34494059110 * q, -17263532288 * q, -34175192200 * q), v3d(0, -1, 0), rt_from_double(0.001),
                  RT_REAL_MAX};
    rt_ray_setup rs = rt_intersect_prepare(ray);
    static const int corners[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};
    for (int i = 0; i < 4; i++) {
        rt_prim_hit h = {0};
        const int *k = corners[i];
        cr_assert_not(rt_intersect_triangle(&rs, v[k[0]], v[k[1]], v[k[2]], &h), "triangle %d hit at t = %.17g", i,
                      rt_to_double(h.t));
        cr_assert_not(rt_intersect_triangle(&rs, v[k[0]], v[k[2]], v[k[1]], &h), "triangle %d reversed hit", i);
    }
}

/* fuzz_bvh (fixed, finding 16): two spheres of radius about 583 seen from 8,450 away.
 * The inverse transform's entries are rounded (2^-33 in Q32.32), so the object-space
 * image of so far an origin was off by about 1e-3 world units, beyond the 2^-20 padding
 * of the sphere's box (5.6e-4): the walk culled a box its sphere's hit lay before. The
 * test now starts from the ray's point nearest the centre, and the fixed build pads a
 * large quadric's box by more (the error left grows as the scale squared). Each hit
 * must lie within half its box's padding of the exact one, for scales to 65,000:
 * measured at most 0.15 of it in the fixed build (21.5 before the fix at a scale of
 * 1166, 75 at 65,000 with the shift alone), 2.6e-8 in the double build. */
Test(precision, a_far_large_sphere_is_hit_within_its_boxs_padding)
{
    static const double scales[] = {1166.37, 4100.3, 16411.7, 65000.9};
    static char memory[1 << 20];
    for (int n = 0; n < 4; n++) {
        double scale = scales[n];
        rt_object_desc sphere = {.kind = RT_SHAPE_SPHERE};
        sphere.world = rt_affine_trs(v3d(123.25, -40.5, 77), v3d(0, 0, 0), v3d(scale, scale, scale));
        rt_scene scene;
        build_one_object(&sphere, NULL, memory, sizeof memory, &scene);
        const rt_affine *w = &scene.objects[scene.quadric_objects[0]].to_world;
        long double c[3] = {rt_to_double(w->translation.x), rt_to_double(w->translation.y),
                            rt_to_double(w->translation.z)};
        long double r = rt_to_double(w->linear.m[0][0]) / 2;
        long double padding = rt_to_double(rt_bvh_prim_bounds(&scene, 0).hi.x) - (c[0] + r);
        unsigned seed = 7;
        for (int i = 0; i < 2000; i++) {
            double u[6];
            for (int k = 0; k < 6; k++) u[k] = (seed = seed * 1103515245u + 12345u) / 4294967296.0 * 2 - 1;
            /* From 4 to 17 scales away, aimed within 0.95 r of the centre. */
            rt_vec3 target = v3d(c[0] + 0.55 * scale * u[0], c[1] + 0.55 * scale * u[1], c[2] + 0.55 * scale * u[2]);
            rt_vec3 away = rt_v3_normalize(v3d(u[3], u[4], u[5] + 2));
            rt_vec3 origin = rt_v3_add(target, rt_v3_scale(away, rt_from_double(scale * (4 + 6.5 * (u[0] + 1)))));
            rt_ray ray = {origin, rt_v3_neg(away), rt_from_double(0.001), RT_REAL_MAX};
            long double o[3] = {rt_to_double(origin.x), rt_to_double(origin.y), rt_to_double(origin.z)};
            long double d[3] = {rt_to_double(ray.direction.x), rt_to_double(ray.direction.y),
                                rt_to_double(ray.direction.z)};
            long double a = 0, h = 0, f = 0;
            for (int k = 0; k < 3; k++) {
                a += d[k] * d[k];
                h += (o[k] - c[k]) * d[k];
                f += (o[k] - c[k]) * (o[k] - c[k]);
            }
            long double disc = h * h - a * (f - r * r);
            rt_ray_setup rs = rt_intersect_prepare(ray);
            rt_scene_hit hit;
            bool found = rt_scene_nearest(&scene, &rs, false, &hit);
            if (disc < 0.01L * r * r) continue; /* near grazing: hit or miss may go either way */
            cr_assert(found, "scale %g, ray %d missed", scale, i);
            long double t = (-h - sqrtl(disc)) / a, off = fabsl(rt_to_double(hit.hit.t) - t) * sqrtl(a);
            cr_assert(off <= padding / 2, "scale %g, ray %d: hit %.3Lg from the exact one, padding %.3Lg", scale, i,
                      off, padding);
        }
    }
}

/* fuzz_sphere (CI, fixed build, finding 19): rotations near 150 degrees on every axis
 * under scales near 0.65. The column-scaled matrix has det 1327, whose reciprocal kept 22
 * significant bits in Q32.32: the inverse was 742 lsb off the matrix's exact inverse,
 * and the harness saw the object-space ray 1.5 times its bound off. det is now scaled
 * like the columns first. Measured against the exact inverse (long double adjugate over
 * determinant of the same entries): 0.86 lsb (fixed; 742 before), 0.97 ulp (double). */
Test(precision, a_rotated_small_scale_inverts_to_its_exact_inverse)
{
    rt_affine m =
        rt_affine_trs(v3d(0.62, 2.97, 6.73), v3d(-148.60059510194696, -48.639963378431275, 163.78942549787462),
                      v3d(0.77110541262663901, 0.64841977739706635, 0.64841977739706635));
    rt_affine inv;
    cr_assert(rt_affine_inverse(&m, &inv));
    long double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = rt_to_double(m.linear.m[r][c]);
    long double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                      a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                      a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    long double worst = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            /* (A^-1)[r][c] = cofactor of a[c][r] / det, from the rows other than c and columns other than r. */
            int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
            long double want = (a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / det;
            worst = fmaxl(worst, fabsl(rt_to_double(inv.linear.m[r][c]) - want));
        }
    cr_assert(worst <= 8 * ULP, "inverse off the exact one by %.3Lg", worst);
}

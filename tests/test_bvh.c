/* The BVH returns exactly what testing every primitive returns (core/bvh.c), and its
 * tree does not depend on the build's plan or workers. */
#include "bvh.h"
#include "same_hit.h"
#include "scene_query.h"
#include "thread/kernel.h"
#include "thread/pool.h"
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

static uint64_t lcg_state;
static double next_unit(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg_state >> 11) / 9007199254740992.0;
}
static double next_range(double lo, double hi) { return lo + (hi - lo) * next_unit(); }

/* A random soup of triangles and spheres, the spheres' centres scaled by spread; memory
 * from a malloc'd arena. */
static void random_scene(rt_scene *s, void **memory, uint32_t triangles, uint32_t spheres, double spread)
{
    size_t size = 64u << 20;
    *memory = malloc(size);
    rt_arena arena;
    rt_arena_init(&arena, *memory, size);
    static rt_material material;
    rt_vec3 *pos = malloc(sizeof(rt_vec3) * triangles * 3);
    uint32_t *idx = malloc(sizeof(uint32_t) * triangles * 3);
    for (uint32_t i = 0; i < triangles * 3; i++) {
        idx[i] = i;
        if (i % 3 == 0)
            pos[i] = rt_v3(next_range(-10, 10), next_range(-10, 10), next_range(-10, 10));
        else
            pos[i] = rt_v3_add(pos[i - i % 3], rt_v3(next_range(-1, 1), next_range(-1, 1), next_range(-1, 1)));
    }
    rt_mesh_desc mesh = {pos, NULL, NULL, triangles * 3, idx, triangles};
    rt_object_desc *objs = calloc(spheres + 1, sizeof *objs);
    objs[0].kind = RT_SHAPE_MESH;
    objs[0].world = rt_affine_identity();
    for (uint32_t i = 1; i <= spheres; i++) {
        objs[i].kind = RT_SHAPE_SPHERE;
        rt_real r = next_range(0.2, 2);
        rt_vec3 centre =
            rt_v3(next_range(-10, 10) * spread, next_range(-10, 10) * spread, next_range(-10, 10) * spread);
        objs[i].world = rt_affine_trs(centre, rt_v3(0, 0, 0), rt_v3(r, r * 0.5, r));
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

/* A ray from inside [-15, 15]^3 in a random direction, over (epsilon, infinity). */
static rt_ray random_ray(void)
{
    rt_vec3 o = rt_v3(next_range(-15, 15), next_range(-15, 15), next_range(-15, 15));
    rt_vec3 d = rt_v3_normalize(rt_v3(next_range(-1, 1), next_range(-1, 1), next_range(-1, 1)));
    rt_ray r = {o, d, RT_HIT_EPSILON, RT_REAL_MAX};
    return r;
}

/* The whole hit record, t and barycentrics bit for bit: the leaves test triangles several
 * per vector (core/bvh_leaf_lanes.h), testing every primitive takes the scalar test. */
Test(bvh, nearest_hit_equals_brute_force)
{
    rt_scene s;
    void *memory;
    lcg_state = 42;
    random_scene(&s, &memory, 2000, 50, 1);
    cr_assert_gt(s.bvh.node_count, 100);
    cr_assert_leq(s.bvh.depth, RT_BVH_MAX_DEPTH);
    uint64_t first_ray = lcg_state; /* every kernel gets the same rays */
    for (rt_kernel k = RT_KERNEL_PORTABLE; k <= RT_KERNEL_AVX512; k++) {
        if (!rtp_kernel_runs(k)) continue;
        cr_assert(rt_bvh_set_kernel(&s.bvh, k));
        lcg_state = first_ray;
        int hits = 0;
        for (int i = 0; i < 20000; i++) {
            rt_ray r = random_ray();
            rt_ray_setup rs = rt_intersect_prepare(r);
            rt_scene_hit a, b;
            bool ha = rt_scene_nearest(&s, &rs, true, &a), hb = rt_scene_nearest(&s, &rs, false, &b);
            cr_assert_eq(ha, hb, "%s, ray %d: BVH %s, brute force %s", rtp_kernel_name(k), i, ha ? "hit" : "missed",
                         hb ? "hit" : "missed");
            if (!ha) continue;
            hits++;
            cr_assert_eq(a.prim, b.prim, "%s, ray %d: primitive %u vs %u", rtp_kernel_name(k), i, a.prim, b.prim);
            cr_assert(same_hit(&a.hit, &b.hit), "%s, ray %d: hit records differ", rtp_kernel_name(k), i);
        }
        cr_assert_gt(hits, 2000, "the test scene should be hit often (%d hits)", hits);
    }
    free(memory);
}

/* The any-hit query finds a hit exactly when the nearest-hit query does, with and without
 * the BVH, for segments of every length (shadow rays end at the light). */
Test(bvh, any_hit_agrees_with_nearest)
{
    lcg_state = 5;
    rt_scene s;
    void *memory;
    random_scene(&s, &memory, 2000, 50, 1);
    int hits = 0, misses = 0;
    for (int i = 0; i < 20000; i++) {
        rt_ray r = random_ray();
        if (i % 4 != 0) r.t_max = next_range(0.01, 20);
        if (i % 7 == 0) r.direction.y = 0; /* a zero component: the general slab test */
        rt_ray_setup rs = rt_intersect_prepare(r);
        rt_scene_hit h;
        bool want = rt_scene_nearest(&s, &rs, false, &h);
        cr_assert_eq(rt_scene_any(&s, &rs, true), want, "ray %d: BVH any-hit differs", i);
        cr_assert_eq(rt_scene_any(&s, &rs, false), want, "ray %d: brute-force any-hit differs", i);
        want ? hits++ : misses++;
    }
    cr_assert(hits > 2000 && misses > 2000, "%d hits, %d misses", hits, misses);
    free(memory);
}

/* Directions with zero components take the general slab test (core/bvh.c); origins on
 * a coarse lattice put them in the planes of the quadrics' boxes and on triangle edges. */
Test(bvh, axis_aligned_rays_equal_brute_force)
{
    lcg_state = 99;
    rt_scene s;
    void *memory;
    random_scene(&s, &memory, 1000, 30, 1);
    static const double dirs[][3] = {{1, 0, 0},  {-1, 0, 0},    {0, 1, 0},      {0, -1, 0},     {0, 0, 1},
                                     {0, 0, -1}, {0.6, 0.8, 0}, {0, -0.6, 0.8}, {-0.8, 0, -0.6}};
    int hits = 0;
    for (int i = 0; i < 20000; i++) {
        const double *d = dirs[i % 9];
        rt_vec3 o = rt_v3(rt_from_int((int)(next_unit() * 31) - 15), rt_from_double(next_range(-15, 15)),
                          rt_from_int((int)(next_unit() * 31) - 15));
        rt_ray r = {o, rt_v3(rt_from_double(d[0]), rt_from_double(d[1]), rt_from_double(d[2])), RT_HIT_EPSILON,
                    RT_REAL_MAX};
        rt_ray_setup rs = rt_intersect_prepare(r);
        rt_scene_hit a, b;
        bool ha = rt_scene_nearest(&s, &rs, true, &a), hb = rt_scene_nearest(&s, &rs, false, &b);
        cr_assert_eq(ha, hb, "ray %d: BVH %s, brute force %s", i, ha ? "hit" : "missed", hb ? "hit" : "missed");
        if (!ha) continue;
        hits++;
        cr_assert_eq(a.prim, b.prim, "ray %d: primitive %u vs %u", i, a.prim, b.prim);
        cr_assert(a.hit.t == b.hit.t);
    }
    cr_assert_gt(hits, 1000, "the test scene should be hit often (%d hits)", hits);
    free(memory);
}

Test(bvh, every_reference_appears_once)
{
    lcg_state = 7;
    rt_scene s;
    void *memory;
    random_scene(&s, &memory, 500, 20, 1);
    uint8_t *seen = calloc(s.prim_count, 1);
    for (uint32_t n = 0; n < s.bvh.node_count; n++) {
        const rt_bvh_node *node = &s.bvh.nodes[n];
        for (int c = 0; c < RT_BVH_WIDTH; c++) {
            if (node->count[c] == RT_BVH_NO_CHILD) continue;
            for (uint32_t i = node->child[c]; i < node->child[c] + node->count[c]; i++) seen[s.bvh.prim_refs[i]]++;
        }
    }
    for (uint32_t p = 0; p < s.prim_count; p++) cr_assert_eq(seen[p], 1, "primitive %u in %u leaves", p, seen[p]);
    free(seen);
    free(memory);
}

/* Workers that run a job set backwards, every job on a different worker index than the
 * last: the order no platform uses, so results that depended on order would show. */
static void run_backwards(const rt_workers *w, rt_job_fn *job, void *arg, uint32_t jobs)
{
    for (uint32_t i = jobs; i-- > 0;) job(arg, i, i % w->count);
}

/* Rebuilds s's tree with the plan and workers and asserts it equals s's, byte for byte. */
static void assert_same_tree(const rt_scene *s, rt_bvh_plan plan, const rt_workers *w, const char *what)
{
    size_t size = 32u << 20;
    void *memory = malloc(size);
    rt_arena arena;
    rt_arena_init(&arena, memory, size);
    rt_scene copy = *s;
    cr_assert_eq(rt_bvh_build_planned(&copy, &arena, w, plan), RT_OK, "%s", what);
    cr_assert_eq(copy.bvh.node_count, s->bvh.node_count, "%s, plan %u/%u: node count", what, plan.split_above,
                 plan.chunk);
    cr_assert_eq(copy.bvh.depth, s->bvh.depth, "%s: depth", what);
    cr_assert_eq(copy.bvh.grid, s->bvh.grid, "%s: grid", what);
    cr_assert(!memcmp(copy.bvh.nodes, s->bvh.nodes, s->bvh.node_count * sizeof(rt_bvh_node)),
              "%s, plan %u/%u: nodes differ", what, plan.split_above, plan.chunk);
    cr_assert(!memcmp(copy.bvh.prim_refs, s->bvh.prim_refs, s->prim_count * sizeof(uint32_t)),
              "%s, plan %u/%u: references differ", what, plan.split_above, plan.chunk);
    free(memory);
}

/* Asserts that s's tree is built, byte for byte, under each plan: on this thread,
 * backwards, and on a pool of each of the worker counts. */
static void assert_same_tree_under_plans(const rt_scene *s, const rt_bvh_plan *plans, size_t plan_count,
                                         const uint32_t *workers, size_t worker_count)
{
    rtp_pool *pools[8];
    cr_assert_leq(worker_count, 8);
    for (size_t t = 0; t < worker_count; t++) {
        pools[t] = rtp_pool_open(workers[t]);
        cr_assert_eq(rt_workers_count(rtp_pool_workers(pools[t])), workers[t], "a pool of %u workers", workers[t]);
    }
    rt_workers backwards = {5, run_backwards};
    for (size_t p = 0; p < plan_count; p++) {
        assert_same_tree(s, plans[p], NULL, "on this thread");
        assert_same_tree(s, plans[p], &backwards, "backwards");
        for (size_t t = 0; t < worker_count; t++) assert_same_tree(s, plans[p], rtp_pool_workers(pools[t]), "threads");
    }
    for (size_t t = 0; t < worker_count; t++) rtp_pool_close(pools[t]);
}

/* The scene build (default plan; 3050 references are built as one job) is the reference:
 * splitting the top of the tree level by level, bounding in chunks of any size, and
 * running the jobs on threads or backwards give the same tree. */
Test(bvh, tree_does_not_depend_on_plan_or_workers)
{
    lcg_state = 11;
    rt_scene s;
    void *memory;
    random_scene(&s, &memory, 3000, 50, 1);
    cr_assert_gt(s.bvh.node_count, 200);
    static const rt_bvh_plan plans[] = {{1, 1}, {4, 3}, {9, 1000}, {64, 64}, {300, 17}, {1000, 5000}, {3049, 1}};
    static const uint32_t workers[] = {1, 2, 3, 7};
    assert_same_tree_under_plans(&s, plans, sizeof plans / sizeof plans[0], workers,
                                 sizeof workers / sizeof workers[0]);
    free(memory);
}

/* Above 16,384 references (8,192 with nodes of four children) the tree has wide roots
 * below its top (core/bvh_binary.h): the default plan collapses them in the jobs that
 * build them, while a plan that splits further down, or builds everything in one job,
 * leaves them to the final collapse. The trees are the same. */
Test(bvh, wide_roots_collapsed_in_their_jobs_or_at_the_end)
{
    lcg_state = 19;
    rt_scene s;
    void *memory;
    random_scene(&s, &memory, 50000, 0, 1);
    static const rt_bvh_plan plans[] = {{1000, 777}, {4000, 50000}, {60000, 5000}, {16384, 3000}};
    static const uint32_t workers[] = {2, 3};
    assert_same_tree_under_plans(&s, plans, sizeof plans / sizeof plans[0], workers,
                                 sizeof workers / sizeof workers[0]);
    free(memory);
}

/* One primitive, and 40 spheres about one centre (no axis to bin on: one leaf of 40),
 * under a plan that splits everything it can. */
Test(bvh, degenerate_scenes_under_every_plan)
{
    lcg_state = 3;
    rt_scene s;
    void *memory;
    rtp_pool *two = rtp_pool_open(2);
    random_scene(&s, &memory, 1, 0, 1);
    assert_same_tree(&s, (rt_bvh_plan){1, 1}, rtp_pool_workers(two), "one triangle");
    free(memory);
    random_scene(&s, &memory, 0, 40, 0);
    cr_assert_eq(s.bvh.node_count, 1);
    cr_assert_eq(s.bvh.nodes[0].count[0], 40, "one leaf of every sphere");
    assert_same_tree(&s, (rt_bvh_plan){2, 3}, rtp_pool_workers(two), "coincident spheres");
    free(memory);
    rtp_pool_close(two);
}

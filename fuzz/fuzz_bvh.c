/* libFuzzer target: BVH build and traversal (core/bvh.c) against testing every
 * primitive. For a soup of triangles, spheres and cylinders from the bytes,
 * rt_scene_nearest with and without the BVH must agree on hit or miss, on the
 * primitive (ties go to the lower reference) and on t, bit for bit; the stream queries
 * (packets) and the one-ray queries under every kernel the CPU runs must give each of
 * those rays, each of them again from the first one's origin, and segments from their
 * origins to one end, what the build's own kernel gives it; and a build under a plan
 * that splits the top of the tree level by level and bounds in small chunks must give
 * the same tree, byte for byte. */
#include <math.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "scene_query.h"

#define MAX_TRIANGLES 48
#define MAX_QUADRICS 16

typedef enum { COORD_RANGE, COORD_LATTICE } coord_mode;

/* A coordinate in [-range, range], or on a small lattice there (exact ties, shared
 * edges, axis-aligned faces). */
static rt_real coord(fz_bytes *in, coord_mode mode, double range)
{
    if (mode == COORD_LATTICE) return rt_mul(rt_from_int((int)fz_below(in, 9) - 4), rt_from_double(range / 4));
    return rt_from_double(fz_range(in, -range, range));
}

static rt_vec3 point(fz_bytes *in, coord_mode mode, double range)
{
    rt_real x = coord(in, mode, range), y = coord(in, mode, range);
    return rt_v3(x, y, coord(in, mode, range));
}

static bool box_inside(const rt_aabb *inner, const rt_aabb *outer)
{
    return outer->lo.x <= inner->lo.x && outer->lo.y <= inner->lo.y && outer->lo.z <= inner->lo.z &&
           inner->hi.x <= outer->hi.x && inner->hi.y <= outer->hi.y && inner->hi.z <= outer->hi.z;
}

/* Every reference sits in exactly one leaf, inside the leaf's box; every node but the
 * root is one slot's child, and its children lie inside that slot's box. */
static void check_tree(const rt_scene *s)
{
    const rt_bvh *bvh = &s->bvh;
    static uint8_t seen[MAX_TRIANGLES + MAX_QUADRICS], parents[MAX_TRIANGLES + MAX_QUADRICS];
    memset(seen, 0, sizeof seen);
    memset(parents, 0, sizeof parents);
    FZ_CHECK(bvh->node_count >= 1 && bvh->node_count <= (s->prim_count > 1 ? s->prim_count - 1 : 1) &&
                 bvh->depth <= RT_BVH_MAX_DEPTH,
             "%u nodes, depth %u for %u primitives", bvh->node_count, bvh->depth, s->prim_count);
    FZ_CHECK(s->prim_count == 0 || bvh->nodes[0].count[0] != RT_BVH_NO_CHILD, "the root has no children");
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const rt_bvh_node *n = &bvh->nodes[i];
        for (int c = 0; c < RT_BVH_WIDTH; c++) {
            if (n->count[c] == RT_BVH_NO_CHILD) {
                FZ_CHECK(c == RT_BVH_WIDTH - 1 || n->count[c + 1] == RT_BVH_NO_CHILD, "node %u skips slot %d", i, c);
                /* The walks test unused slots like the others: their box must hold nothing. */
                rt_aabb empty = rt_bvh_child_box(bvh, n, c);
                FZ_CHECK(empty.lo.x == rt_bound_value(rt_bound_below(RT_REAL_MAX, bvh->grid), bvh->grid) &&
                             empty.hi.x == rt_bound_value(rt_bound_above(rt_neg(RT_REAL_MAX), bvh->grid), bvh->grid) &&
                             empty.lo.y == empty.lo.x && empty.lo.z == empty.lo.x && empty.hi.y == empty.hi.x &&
                             empty.hi.z == empty.hi.x,
                         "node %u: unused slot %d has a box", i, c);
                continue;
            }
            rt_aabb box = rt_bvh_child_box(bvh, n, c);
            uint32_t first = n->child[c], count = n->count[c];
            if (count == 0) {
                FZ_CHECK(first > i && first < bvh->node_count && !parents[first]++, "node %u slot %d: child %u", i, c,
                         first);
                for (int g = 0; g < RT_BVH_WIDTH && bvh->nodes[first].count[g] != RT_BVH_NO_CHILD; g++) {
                    rt_aabb inner = rt_bvh_child_box(bvh, &bvh->nodes[first], g);
                    FZ_CHECK(box_inside(&inner, &box), "node %u slot %d pokes out of node %u slot %d", first, g, i, c);
                }
                continue;
            }
            FZ_CHECK(first + count <= s->prim_count, "node %u slot %d covers refs %u..%u", i, c, first, first + count);
            for (uint32_t k = first; k < first + count; k++) {
                uint32_t prim = bvh->prim_refs[k];
                FZ_CHECK(prim < s->prim_count && !seen[prim], "primitive %u referenced twice or out of range", prim);
                seen[prim] = 1;
                rt_aabb b = rt_bvh_prim_bounds(s, prim);
                FZ_CHECK(box_inside(&b, &box), "primitive %u pokes out of node %u slot %d", prim, i, c);
            }
        }
    }
    for (uint32_t i = 1; i < bvh->node_count; i++) FZ_CHECK(parents[i] == 1, "node %u has no parent", i);
    for (uint32_t p = 0; p < s->prim_count; p++) FZ_CHECK(seen[p], "primitive %u is in no leaf", p);
}

/* Runs a job set in order on this thread, as one of many workers would. */
static void run_in_order(const rt_workers *w, rt_job_fn *job, void *arg, uint32_t jobs)
{
    for (uint32_t i = 0; i < jobs; i++) job(arg, i, i % w->count);
}

/* Rebuilds s's tree under plan, as if on 16 workers (so that levels of fewer than 16
 * tasks are binned in chunks), and checks it is s's tree. */
static void check_plan(const rt_scene *s, rt_bvh_plan plan)
{
    static const rt_workers many = {16, run_in_order};
    static uint8_t memory[1u << 20];
    rt_arena arena;
    rt_arena_init(&arena, memory, sizeof memory);
    rt_scene copy = *s;
    FZ_CHECK(rt_bvh_build_planned(&copy, &arena, &many, plan) == RT_OK, "plan %u/%u: out of memory", plan.split_above,
             plan.chunk);
    FZ_CHECK(copy.bvh.node_count == s->bvh.node_count && copy.bvh.depth == s->bvh.depth &&
                 !memcmp(copy.bvh.nodes, s->bvh.nodes, s->bvh.node_count * sizeof(rt_bvh_node)) &&
                 !memcmp(copy.bvh.prim_refs, s->bvh.prim_refs, s->prim_count * sizeof(uint32_t)),
             "plan %u/%u builds another tree", plan.split_above, plan.chunk);
}

static void check_ray(const rt_scene *s, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    bool hit_a = rt_scene_nearest(s, &rs, true, &a), hit_b = rt_scene_nearest(s, &rs, false, &b);
    if ((hit_a && fz_grazing(s, a.prim, &ray)) || (hit_b && fz_grazing(s, b.prim, &ray))) return;
    FZ_CHECK(hit_a == hit_b, "BVH %s, brute force %s", hit_a ? "hits" : "misses", hit_b ? "hits" : "misses");
    if (!hit_a) return;
    fz_check_t(a.hit.t, ray.t_min, ray.t_max);
    FZ_CHECK(a.prim == b.prim, "BVH hits primitive %u at t = %.17g, brute force %u at t = %.17g", a.prim,
             rt_to_double(a.hit.t), b.prim, rt_to_double(b.hit.t));
    FZ_CHECK(memcmp(&a.hit.t, &b.hit.t, sizeof a.hit.t) == 0 && memcmp(&a.hit.b1, &b.hit.b1, sizeof a.hit.b1) == 0 &&
                 memcmp(&a.hit.b2, &b.hit.b2, sizeof a.hit.b2) == 0 && a.hit.part == b.hit.part,
             "same primitive %u, different hit records", a.prim);
    /* The documented tie rule: no lower reference hits at the same t. */
    for (uint32_t p = 0; p < a.prim; p++) {
        rt_prim_hit h;
        FZ_CHECK(!rt_scene_prim_intersect(s, p, &rs, &h) || h.t != a.hit.t,
                 "primitive %u ties with %u at t = %.17g and is lower", p, a.prim, rt_to_double(a.hit.t));
    }
}

/* The kernels this CPU runs (the core's own list, and for AVX2 and AVX-512 the CPU's word). */
static bool kernel_runs(rt_kernel k)
{
#if defined(__x86_64__) || defined(__i386__)
    if (k >= RT_KERNEL_AVX2 && !__builtin_cpu_supports("avx2")) return false;
    if (k == RT_KERNEL_AVX512 && !(__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")))
        return false;
#endif
    return rt_bvh_kernel_compiled(k);
}

#define MAX_STREAM 256

/* The answers for n rays to one kind of query under kernel k. */
typedef struct {
    rt_scene_hit hit[MAX_STREAM];
    bool found[MAX_STREAM], any[MAX_STREAM];
} answers;

/* got (kernel k's `how` queries) against want (the build's kernel, one ray at a time),
 * but where either hits a triangle edge-on (see check_ray). */
static void compare(const rt_scene *s, const rt_ray *rays, uint32_t n, rt_kernel k, const char *how, const answers *got,
                    const answers *want)
{
    for (uint32_t i = 0; i < n; i++) {
        if ((want->found[i] && fz_grazing(s, want->hit[i].prim, &rays[i])) ||
            (got->found[i] && fz_grazing(s, got->hit[i].prim, &rays[i])))
            continue;
        FZ_CHECK(want->found[i] == got->found[i] && want->any[i] == got->any[i],
                 "kernel %d, ray %u: %s %s/%s, build's kernel %s/%s", (int)k, i, how, got->found[i] ? "hit" : "miss",
                 got->any[i] ? "hit" : "miss", want->found[i] ? "hit" : "miss", want->any[i] ? "hit" : "miss");
        if (!want->found[i]) continue;
        const rt_prim_hit *a = &want->hit[i].hit, *b = &got->hit[i].hit;
        FZ_CHECK(
            want->hit[i].prim == got->hit[i].prim && !memcmp(&a->t, &b->t, sizeof a->t) &&
                !memcmp(&a->b1, &b->b1, sizeof a->b1) && !memcmp(&a->b2, &b->b2, sizeof a->b2) && a->part == b->part,
            "kernel %d, ray %u: %s hits primitive %u at t = %.17g, build's kernel %u at t = %.17g", (int)k, i, how,
            got->hit[i].prim, rt_to_double(got->hit[i].hit.t), want->hit[i].prim, rt_to_double(want->hit[i].hit.t));
    }
}

/* Under every kernel that runs here, the stream queries (packets where the kernel has
 * them) and the one-ray queries give each ray exactly what the build's own kernel gives
 * it one ray at a time. */
static void check_streams(const rt_scene *s, const rt_ray *rays, uint32_t n)
{
    static rt_ray_setup rs[MAX_STREAM];
    static answers want, got;
    for (uint32_t i = 0; i < n; i++) {
        rs[i] = rt_intersect_prepare(rays[i]);
        want.found[i] = rt_scene_nearest(s, &rs[i], true, &want.hit[i]);
        want.any[i] = rt_scene_any(s, &rs[i], true);
    }
    for (rt_kernel k = RT_KERNEL_PORTABLE; k <= RT_KERNEL_AVX512; k++) {
        if (!kernel_runs(k)) continue;
        rt_scene copy = *s;
        FZ_CHECK(rt_bvh_set_kernel(&copy.bvh, k), "kernel %d refused", (int)k);
        memset(&got, 0, sizeof got);
        rt_scene_nearest_stream(&copy, rs, n, got.hit, got.found);
        rt_scene_any_stream(&copy, rs, n, got.any);
        compare(s, rays, n, k, "stream", &got, &want);
        for (uint32_t i = 0; i < n; i++) {
            got.found[i] = rt_scene_nearest(&copy, &rs[i], true, &got.hit[i]);
            got.any[i] = rt_scene_any(&copy, &rs[i], true);
        }
        compare(s, rays, n, k, "one ray", &got, &want);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes in = fz_bytes_of(data, size);
    uint8_t layout = fz_u8(&in);
    coord_mode mode = (coord_mode)(layout % 2);
    /* Any scale from 2^-40 to 2^40 (fixed: 2^-2 to 2^10), but within one scene
     * objects are at most 2^8 smaller than the scene: far beyond that the quadrics'
     * own rounding (about eps |o|^2 / r, docs/robustness.md) exceeds the BVH's padding. */
    double range = fz_pow2(&in, FZ_SIZE_LOG2_MIN, FZ_SIZE_LOG2_MAX);
    uint32_t n_tri = fz_below(&in, MAX_TRIANGLES + 1), n_quad = fz_below(&in, MAX_QUADRICS + 1);
    static rt_vec3 pos[3 * MAX_TRIANGLES];
    static uint32_t idx[3 * MAX_TRIANGLES];
    for (uint32_t i = 0; i < 3 * n_tri; i++) {
        idx[i] = i;
        uint8_t how = fz_u8(&in);
        /* Repeats make exact ties: a whole triangle again, or a shared vertex. */
        if (i >= 3 && how % 8 == 0)
            pos[i] = pos[i - 3];
        else if (i >= 1 && how % 8 == 1)
            pos[i] = pos[fz_below(&in, i)];
        else
            pos[i] = point(&in, mode, range);
    }
    static const rt_material material = {.diffuse = {.texture = RT_NO_TEXTURE},
                                         .specular = {.texture = RT_NO_TEXTURE},
                                         .emissive = {.texture = RT_NO_TEXTURE},
                                         .transmittance = {.texture = RT_NO_TEXTURE},
                                         .index_of_refraction = RT_C(1.0)};
    rt_mesh_desc mesh = {pos, NULL, NULL, 3 * n_tri, idx, n_tri};
    rt_object_desc objects[1 + MAX_QUADRICS] = {{.kind = RT_SHAPE_MESH, .world = rt_affine_identity()}};
    for (uint32_t i = 1; i <= n_quad; i++) {
        uint8_t how = fz_u8(&in);
        objects[i].kind = how & 1 ? RT_SHAPE_CYLINDER : RT_SHAPE_SPHERE;
        if (i > 1 && how % 8 < 2) {
            objects[i].world = objects[i - 1].world;
            continue;
        }
        rt_vec3 rot = how & 2 ? fz_vec_range(&in, -180, 180) : rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
        double smallest = exp2(FZ_SIZE_LOG2_MIN);
        rt_real sx = rt_from_double(fmax(range * fz_pow2(&in, -8, 1), smallest));
        rt_real sy = how & 4 ? sx : rt_from_double(fmax(range * fz_pow2(&in, -8, 1), smallest));
        objects[i].world = rt_affine_trs(point(&in, mode, range), rot, rt_v3(sx, sy, sx));
    }
    rt_scene_desc desc = {0};
    desc.materials = &material;
    desc.material_count = 1;
    desc.meshes = &mesh;
    desc.mesh_count = 1;
    desc.objects = objects;
    desc.object_count = 1 + n_quad;
    desc.camera = fz_camera();
    rt_scene s;
    rt_build_error err;
    if (fz_build(&desc, &s, &err) != RT_OK) return 0; /* raw coordinates can overflow a transform */
    if (s.prim_count == 0) return 0;
    check_tree(&s);
    /* The plan comes from the layout byte's unused bits, so the seeds keep their rays. */
    check_plan(&s, (rt_bvh_plan){1 + (layout >> 1) % 8, 1 + (layout >> 4)});
    static rt_ray rays[MAX_STREAM];
    static rt_vec3 origins[MAX_STREAM];
    rt_vec3 end = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    uint32_t n_rays = 0;
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in) % 4;
        rt_vec3 target = kind == 0 || n_tri == 0 ? point(&in, mode, range) : s.positions[fz_below(&in, s.vertex_count)];
        /* Aimed at a point or a vertex (edges and ties), often along an axis. */
        rt_ray ray = kind == 2 ? fz_ray_axis(&in, target) : fz_ray_through(&in, target);
        ray.origin = rt_v3_madd(target, ray.direction, rt_from_double(-range * fz_pow2(&in, -3, 3)));
        check_ray(&s, ray);
        if (n_rays == 0) end = target;
        if (n_rays < MAX_STREAM) rays[n_rays++] = ray;
    }
    for (uint32_t i = 0; i < n_rays; i++) origins[i] = rays[i].origin;
    check_streams(&s, rays, n_rays);
    /* The same directions from the first ray's origin: packets from one origin take the
     * avx2 kernel's frustum walk. */
    for (uint32_t i = 1; i < n_rays; i++) rays[i].origin = rays[0].origin;
    check_streams(&s, rays, n_rays);
    /* Segments from each ray's own origin to the first one's target, as a point light's
     * shadow rays: packets of them take the frustum from their shared end. */
    uint32_t n_segments = 0;
    for (uint32_t i = 0; i < n_rays; i++) {
        rt_vec3 delta = rt_v3_sub(end, origins[i]);
        rt_real length = rt_v3_length(delta);
        if (!(length > RT_HIT_EPSILON)) continue;
        rays[n_segments++] = (rt_ray){origins[i], rt_v3_scale(delta, rt_div(RT_ONE, length)), RT_HIT_EPSILON, length};
    }
    check_streams(&s, rays, n_segments);
    return 0;
}

/* rtk-bench: the rtk side of `make bench`. Built once per scalar backend.
 *
 *   rtk-bench rays SCENE OUT [--assets DIR] [--size WxH]
 *       writes the workload (triangles + camera and shadow rays) for every kernel;
 *   rtk-bench run SCENE WORKLOAD [--assets DIR] [--repeats N]
 *       times the BVH build and the ray queries on the workload's rays and prints
 *       "key value" lines on stdout (progress on stderr).
 *
 * Camera rays are nearest-hit queries (rt_scene_nearest, as rtcIntersect1); shadow rays
 * are any-hit queries with t_max = the light distance (rt_scene_any, as rtcOccluded1),
 * which is what rtk's shader asks in opaque-shadow mode. */
#include "load/scene_open.h"
#include "rtk_rays.h"
#include "thread/threads.h"
#include "timing.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const rt_scene *scene;
    const rt_ray *rays;
    uint8_t *hit;
} query_job;

static void nearest_range(void *ctx, uint32_t begin, uint32_t end)
{
    query_job *q = ctx;
    for (uint32_t i = begin; i < end; i++) {
        rt_ray_setup rs = rt_intersect_prepare(q->rays[i]);
        rt_scene_hit h;
        q->hit[i] = rt_scene_nearest(q->scene, &rs, true, &h);
    }
}

static void any_range(void *ctx, uint32_t begin, uint32_t end)
{
    query_job *q = ctx;
    for (uint32_t i = begin; i < end; i++) {
        rt_ray_setup rs = rt_intersect_prepare(q->rays[i]);
        q->hit[i] = rt_scene_any(q->scene, &rs, true);
    }
}

static rt_ray from_bench(const bench_ray *b)
{
    rt_ray r;
    r.origin = rt_v3(rt_from_double(b->origin[0]), rt_from_double(b->origin[1]), rt_from_double(b->origin[2]));
    r.direction =
        rt_v3(rt_from_double(b->direction[0]), rt_from_double(b->direction[1]), rt_from_double(b->direction[2]));
    r.t_min = rt_from_double(b->t_min);
    r.t_max = isinf(b->t_max) ? RT_REAL_MAX : rt_from_double(b->t_max);
    return r;
}

/* Times the queries `fn` makes on `count` rays (see bench_time_rays). */
static bool time_queries(const char *name, bench_range_fn fn, const rt_scene *scene, const bench_ray *in,
                         uint32_t count, uint32_t repeats)
{
    rt_ray *rays = malloc((size_t)count * sizeof *rays + 1);
    uint8_t *hit = calloc((size_t)count + 1, 1);
    if (!rays || !hit) {
        free(rays);
        free(hit);
        fprintf(stderr, "rtk-bench: out of memory for %u rays\n", count);
        return false;
    }
    for (uint32_t i = 0; i < count; i++) rays[i] = from_bench(&in[i]);
    query_job q = {scene, rays, hit};
    bench_time_rays("rtk " RT_REAL_NAME, name, count, repeats, fn, &q, hit);
    free(rays);
    free(hit);
    return true;
}

/* Best-of-`repeats` wall time (and CPU time in *best_cpu) of rebuilding the BVH over the
 * built scene's primitives on `threads` threads, or a negative time on failure. */
static double time_build(const rt_scene *scene, uint32_t threads, uint32_t repeats, double *best_cpu)
{
    size_t n = scene->prim_count;
    size_t size =
        n * (2 * sizeof(rt_bvh_node) + sizeof(uint32_t) + sizeof(rt_aabb) + sizeof(rt_vec3)) + ((size_t)1 << 20);
    void *memory = malloc(size);
    if (!memory) {
        fprintf(stderr, "rtk-bench: cannot allocate %zu MiB for the BVH build\n", size >> 20);
        return -1.0;
    }
    rt_workers workers = rtp_threads_workers(threads);
    double best = 0.0;
    for (uint32_t r = 0; r < repeats; r++) {
        fprintf(stderr, "  rtk %s: BVH build, %u thread%s, %u/%u\n", RT_REAL_NAME, threads, threads > 1 ? "s" : "",
                r + 1, repeats);
        rt_arena arena;
        rt_arena_init(&arena, memory, size);
        rt_scene copy = *scene;
        double start = bench_now(), cpu = bench_cpu_now();
        rt_status st = rt_bvh_build(&copy, &arena, &workers);
        double s = bench_now() - start;
        cpu = bench_cpu_now() - cpu;
        if (st != RT_OK) {
            fprintf(stderr, "rtk-bench: BVH build failed: %s\n", rt_status_name(st));
            free(memory);
            return -1.0;
        }
        if (r == 0 || s < best) best = s;
        if (r == 0 || cpu < *best_cpu) *best_cpu = cpu;
    }
    free(memory);
    return best;
}

/* The BVH build on one thread and on all of them. */
static bool time_builds(const rt_scene *scene, uint32_t repeats)
{
    double cpu_1 = 0.0, cpu_all = 0.0;
    double one = time_build(scene, 1, repeats, &cpu_1);
    double all = one < 0.0 ? -1.0 : time_build(scene, bench_cpu_count(), repeats, &cpu_all);
    if (all < 0.0) return false;
    printf("build_s %.4f\nbuild_cpu_s %.4f\nbuild_all_s %.4f\n", one, cpu_1, all);
    return true;
}

/* Bytes the scene's mesh and BVH arrays take, per triangle (the node array is allocated
 * at the size built). */
static void print_memory(const rt_scene *s)
{
    double tris = s->triangle_count ? (double)s->triangle_count : 1.0;
    double mesh = (double)s->vertex_count * (2 * sizeof(rt_vec3) + (s->uvs ? sizeof(rt_vec2) : 0)) +
                  (double)s->triangle_count * sizeof(rt_triangle) + (double)s->object_count * sizeof(rt_object);
    double bvh = (double)s->bvh.node_count * sizeof(rt_bvh_node) + (double)s->prim_count * sizeof(uint32_t);
    printf("vertices %u\ntriangles %u\nbvh_nodes %u\nbvh_depth %u\n", s->vertex_count, s->triangle_count,
           s->bvh.node_count, s->bvh.depth);
    printf("mesh_bytes_per_tri %.1f\nbvh_bytes_per_tri %.1f\nbytes_per_tri %.1f\n", mesh / tris, bvh / tris,
           (mesh + bvh) / tris);
}

static int usage(void)
{
    fputs("usage: rtk-bench rays SCENE OUT [--assets DIR] [--size WxH]\n"
          "       rtk-bench run SCENE WORKLOAD [--assets DIR] [--repeats N]\n",
          stderr);
    return 2;
}

int main(int argc, char **argv)
{
    if (argc < 4 || (strcmp(argv[1], "rays") && strcmp(argv[1], "run"))) return usage();
    rtp_scene_options opt = {NULL, (size_t)4 << 30, 0, 0, -1, -1, 0};
    uint32_t width = 1024, height = 1024, repeats = 3;
    for (int i = 4; i < argc; i++) {
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!val) return usage();
        bool good = false;
        if (!strcmp(argv[i], "--assets"))
            opt.assets_root = val, good = true;
        else if (!strcmp(argv[i], "--size"))
            good = sscanf(val, "%ux%u", &width, &height) == 2 && width && height;
        else if (!strcmp(argv[i], "--repeats"))
            good = sscanf(val, "%u", &repeats) == 1 && repeats;
        if (!good) return usage();
        i++;
    }
    char err[RTP_ERR_SIZE];
    rtp_scene built;
    double start = bench_now();
    int rc = rtp_scene_open(argv[2], &opt, &built, err, sizeof err);
    if (rc != 0) {
        fprintf(stderr, "rtk-bench: %s\n", err);
        return rc;
    }
    double load_s = bench_now() - start;
    const rt_scene *scene = &built.scene;
    bench_workload w;
    bool ok;
    if (!strcmp(argv[1], "rays")) {
        ok = bench_make_workload(scene, width, height, &w) && bench_workload_write(argv[3], &w);
        if (ok)
            printf("triangles %u\nprimary_rays %u\nshadow_rays %u\n", w.triangle_count, w.primary_count,
                   w.shadow_count);
    } else {
        ok = bench_workload_read(argv[3], &w);
        if (ok && (w.triangle_count != scene->triangle_count || scene->prim_count != scene->triangle_count)) {
            fprintf(stderr, "rtk-bench: %s does not hold the triangles of %s\n", argv[3], argv[2]);
            ok = false;
        }
        if (ok) {
            printf("kernel rtk-%s\nload_and_build_s %.4f\nthreads_all %u\n", RT_REAL_NAME, load_s, bench_cpu_count());
            print_memory(scene);
            ok = time_builds(scene, repeats) &&
                 time_queries("primary", nearest_range, scene, w.primary, w.primary_count, repeats) &&
                 time_queries("shadow", any_range, scene, w.shadow, w.shadow_count, repeats);
        }
    }
    bench_workload_free(&w);
    rtp_scene_close(&built);
    return ok ? 0 : 1;
}

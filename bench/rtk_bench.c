/* rtk-bench: the rtk side of `make bench`. Built once per scalar backend.
 *
 *   rtk-bench rays SCENE OUT [--assets DIR] [--size WxH]
 *       writes the workload (triangles + camera and shadow rays) for every kernel;
 *   rtk-bench run SCENE WORKLOAD [--assets DIR] [--repeats N] [--results FILE]
 *       times the BVH build and the ray queries on the workload's rays, one ray at a
 *       time and in packets, and prints "key value" lines on stdout (progress on
 *       stderr); --results writes each ray's answer for `agree`;
 *   rtk-bench agree WORKLOAD RESULTS_A RESULTS_B [--min PERCENT]
 *       compares two result files ray by ray (hit or miss and the triangle hit for the
 *       camera rays, blocked or not for the shadow rays), prints the agreement and lists
 *       the rays that differ; fails below PERCENT (default 99.99) on either set.
 *
 * Camera rays are nearest-hit queries (rt_scene_nearest, as rtcIntersect1); shadow rays
 * are any-hit queries with t_max = the light distance (rt_scene_any, as rtcOccluded1),
 * which is what rtk's shader asks in opaque-shadow mode. The packet rows give the stream
 * queries one packet at a time (the camera rays of 4 x 2 pixels, the shadow rays of
 * their hits), as rtcIntersect8 and rtcOccluded8 get them. */
#include "cli/cli.h"
#include "debug/scene_stats.h"
#include "load/scene_open.h"
#include "results.h"
#include "rtk_rays.h"
#include "thread/kernel.h"
#include "thread/pool.h"
#include "timing.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

typedef struct {
    const rt_scene *scene;
    const rt_ray *rays;
    const bench_packets *packets; /* packet rows only */
    uint8_t *hit;
    uint32_t *prim; /* camera rays: the triangle hit, or BENCH_MISS */
} query_job;

static void nearest_range(void *ctx, uint32_t begin, uint32_t end)
{
    query_job *q = ctx;
    for (uint32_t i = begin; i < end; i++) {
        rt_ray_setup rs = rt_intersect_prepare(q->rays[i]);
        rt_scene_hit h;
        q->hit[i] = rt_scene_nearest(q->scene, &rs, true, &h);
        q->prim[i] = q->hit[i] ? h.prim : BENCH_MISS;
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

/* Packets [begin, end) through the stream queries, one packet per call. */
static void packet_range(void *ctx, uint32_t begin, uint32_t end, bool any)
{
    query_job *q = ctx;
    for (uint32_t p = begin; p < end; p++) {
        const uint32_t *ray = q->packets->ray + q->packets->start[p];
        uint32_t n = q->packets->start[p + 1] - q->packets->start[p];
        rt_ray_setup rs[BENCH_PACKET];
        rt_scene_hit h[BENCH_PACKET];
        bool found[BENCH_PACKET];
        for (uint32_t i = 0; i < n; i++) rs[i] = rt_intersect_prepare(q->rays[ray[i]]);
        if (any)
            rt_scene_any_stream(q->scene, rs, n, found);
        else
            rt_scene_nearest_stream(q->scene, rs, n, h, found);
        for (uint32_t i = 0; i < n; i++) {
            q->hit[ray[i]] = found[i];
            if (!any) q->prim[ray[i]] = found[i] ? h[i].prim : BENCH_MISS;
        }
    }
}

static void nearest_packets(void *ctx, uint32_t begin, uint32_t end) { packet_range(ctx, begin, end, false); }
static void any_packets(void *ctx, uint32_t begin, uint32_t end) { packet_range(ctx, begin, end, true); }

/* Whether the workload holds this scene's triangles: the same vertices and indices, the
 * positions equal up to the Q32.32 grid (the workload is written by the double build). */
static bool holds_scene(const bench_workload *w, const rt_scene *s)
{
    if (w->triangle_count != s->triangle_count || s->prim_count != s->triangle_count ||
        w->vertex_count != s->vertex_count)
        return false;
    for (uint32_t t = 0; t < w->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            if (w->indices[3 * t + k] != s->triangles[t].v[k]) return false;
    for (uint32_t v = 0; v < w->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            double ours = rt_to_double(rt_v3_get(s->positions[v], k)), theirs = w->positions[3 * v + k];
            if (!(fabs(ours - theirs) <= 1e-9 + 1e-12 * fabs(theirs))) return false;
        }
    return true;
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

/* Times the queries on `count` rays one at a time and in packets, keeping the first
 * set's answers in hit[] and prim[] (prim may be NULL: shadow rays); fails when the
 * packets' answers differ from them. */
static bool time_queries(const char *name, const rt_scene *scene, const bench_ray *in, uint32_t count,
                         const bench_packets *packets, uint32_t repeats, uint8_t *hit, uint32_t *prim)
{
    rt_ray *rays = malloc((size_t)count * sizeof *rays + 1);
    uint8_t *packet_hit = calloc((size_t)count + 1, 1);
    uint32_t *packet_prim = calloc((size_t)count + 1, sizeof *packet_prim);
    uint32_t *scratch = prim ? NULL : calloc((size_t)count + 1, sizeof *scratch);
    bool ok = rays && packet_hit && packet_prim && (prim || scratch);
    if (!ok) fprintf(stderr, "rtk-bench: out of memory for %u rays\n", count);
    for (uint32_t i = 0; ok && i < count; i++) rays[i] = from_bench(&in[i]);
    bool any = prim == NULL;
    query_job single = {scene, rays, NULL, hit, any ? scratch : prim};
    query_job grouped = {scene, rays, packets, packet_hit, packet_prim};
    char packet_name[64];
    snprintf(packet_name, sizeof packet_name, "%s_packets", name);
    if (ok) {
        bench_time_rays("rtk " RT_REAL_NAME, name, count, count, repeats, any ? any_range : nearest_range, &single,
                        hit);
        bench_time_rays("rtk " RT_REAL_NAME, packet_name, packets->count, count, repeats,
                        any ? any_packets : nearest_packets, &grouped, packet_hit);
    }
    for (uint32_t i = 0; ok && i < count; i++)
        if (packet_hit[i] != hit[i] || (!any && packet_prim[i] != prim[i])) {
            fprintf(stderr, "rtk-bench: %s ray %u: the packets answer %u/%u, one ray at a time %u/%u\n", name, i,
                    packet_hit[i], any ? 0 : packet_prim[i], hit[i], any ? 0 : prim[i]);
            ok = false;
        }
    free(rays);
    free(packet_hit);
    free(packet_prim);
    free(scratch);
    return ok;
}

#define HUGE_PAGE ((size_t)2 << 20)

/* Fresh memory for one build, as Embree's commit gets it: anonymous pages on a 2 MiB
 * boundary, with transparent huge pages asked for (Linux's default "madvise" mode gives
 * them only to who asks). Embree's does: about 39 page faults a commit (getrusage) for
 * some 70 MB, so 2 MiB pages. Unaligned, the first 2 MiB or less of the arena (where
 * the build starts) took 4 KiB faults: 261 faults a dense_mesh build instead of 40.
 * size: a multiple of HUGE_PAGE. NULL when mapping fails. */
static void *map_memory(size_t size)
{
    char *p = mmap(NULL, size + HUGE_PAGE, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    char *aligned = (char *)(((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1));
    if (aligned > p) munmap(p, (size_t)(aligned - p));
    munmap(aligned + size, (size_t)(p + HUGE_PAGE - aligned));
#ifdef MADV_HUGEPAGE
    madvise(aligned, size, MADV_HUGEPAGE);
#endif
    return aligned;
}

/* Best-of-`repeats` wall time (and CPU time in *best_cpu) of rebuilding the BVH over the
 * built scene's primitives on `threads` threads, or a negative time on failure. Like
 * Embree's commit, each build maps fresh memory inside the timed region. */
static double time_build(const rt_scene *scene, uint32_t threads, uint32_t repeats, double *best_cpu)
{
    size_t n = scene->prim_count;
    size_t size =
        n * (2 * sizeof(rt_bvh_node) + sizeof(uint32_t) + sizeof(rt_aabb) + sizeof(rt_vec3)) + ((size_t)1 << 20);
    size = (size + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    /* One pool for every build, as Embree's task scheduler keeps its threads between
     * commits: its threads start in the first build. */
    rtp_pool *pool = rtp_pool_open(threads);
    double best = 0.0;
    for (uint32_t r = 0; r < repeats; r++) {
        fprintf(stderr, "  rtk %s: BVH build, %u thread%s, %u/%u\n", RT_REAL_NAME, threads, threads > 1 ? "s" : "",
                r + 1, repeats);
        rt_scene copy = *scene;
        double start = bench_now(), cpu = bench_cpu_now();
        void *memory = map_memory(size);
        rt_status st = RT_ERR_NOMEM;
        if (memory) {
            rt_arena arena;
            rt_arena_init(&arena, memory, size);
            st = rt_bvh_build(&copy, &arena, rtp_pool_workers(pool));
        }
        double s = bench_now() - start;
        cpu = bench_cpu_now() - cpu;
        if (memory) munmap(memory, size);
        if (st != RT_OK) {
            fprintf(stderr, "rtk-bench: BVH build failed: %s\n", rt_status_name(st));
            best = -1.0;
            break;
        }
        if (r == 0 || s < best) best = s;
        if (r == 0 || cpu < *best_cpu) *best_cpu = cpu;
    }
    rtp_pool_close(pool);
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
 * at the size built), and the tree's shape. */
static void print_tree(const rt_scene *s)
{
    double tris = s->triangle_count ? (double)s->triangle_count : 1.0;
    double mesh = (double)s->vertex_count * (2 * sizeof(rt_vec3) + (s->uvs ? sizeof(rt_vec2) : 0)) +
                  (double)s->triangle_count * sizeof(rt_triangle) + (double)s->object_count * sizeof(rt_object);
    double bvh = (double)s->bvh.node_count * sizeof(rt_bvh_node) + (double)s->prim_count * sizeof(uint32_t);
    printf("vertices %u\ntriangles %u\nbvh_nodes %u\nbvh_depth %u\nsah_cost %.2f\nkernel_name %s\n", s->vertex_count,
           s->triangle_count, s->bvh.node_count, s->bvh.depth, rtp_scene_stats_sah_cost(&s->bvh, s->prim_count),
           rtp_kernel_name(s->bvh.kernel));
    printf("mesh_bytes_per_tri %.1f\nbvh_bytes_per_tri %.1f\nbytes_per_tri %.1f\n", mesh / tris, bvh / tris,
           (mesh + bvh) / tris);
}

/* Builds, times and (with a results path) records the answers of every ray. */
static bool run(const rt_scene *scene, const bench_workload *w, uint32_t repeats, const char *results)
{
    bench_packets primary_packets = {0}, shadow_packets = {0};
    bench_results r;
    bool ok = bench_results_alloc(w, &r) && bench_make_packets(w, false, &primary_packets) &&
              bench_make_packets(w, true, &shadow_packets);
    print_tree(scene);
    ok = ok && time_builds(scene, repeats) &&
         time_queries("primary", scene, w->primary, w->primary_count, &primary_packets, repeats, r.primary_hit,
                      r.primary_prim) &&
         time_queries("shadow", scene, w->shadow, w->shadow_count, &shadow_packets, repeats, r.shadow_blocked, NULL);
    if (ok && results) ok = bench_results_write(results, &r);
    bench_results_free(&r);
    bench_packets_free(&primary_packets);
    bench_packets_free(&shadow_packets);
    return ok;
}

static int usage(void)
{
    fputs("usage: rtk-bench rays SCENE OUT [--assets DIR] [--size WxH]\n"
          "       rtk-bench run SCENE WORKLOAD [--assets DIR] [--repeats N] [--results FILE]\n"
          "       rtk-bench agree WORKLOAD RESULTS_A RESULTS_B [--min PERCENT] [--neighbours]\n",
          stderr);
    return 2;
}

int main(int argc, char **argv)
{
    if (argc >= 5 && !strcmp(argv[1], "agree")) {
        double min = 99.99;
        bool neighbours = false;
        for (int i = 5; i < argc; i++) {
            if (!strcmp(argv[i], "--neighbours"))
                neighbours = true;
            else if (!(i + 1 < argc && !strcmp(argv[i], "--min") && sscanf(argv[++i], "%lf", &min) == 1))
                return usage();
        }
        return bench_agree(argv[2], argv[3], argv[4], min, neighbours);
    }
    if (argc < 4 || (strcmp(argv[1], "rays") && strcmp(argv[1], "run"))) return usage();
    rtp_scene_options opt = rtp_scene_default_options();
    uint32_t width = 1024, height = 1024, repeats = 3;
    const char *results = NULL;
    for (int i = 4; i < argc; i++) {
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!val) return usage();
        bool good = false;
        if (!strcmp(argv[i], "--assets"))
            opt.assets_root = val, good = true;
        else if (!strcmp(argv[i], "--results"))
            results = val, good = true;
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
        ok = bench_make_workload(argv[2], scene, width, height, &w) && bench_workload_write(argv[3], &w);
        if (ok)
            printf("triangles %u\nprimary_rays %u\nshadow_rays %u\n", w.triangle_count, w.primary_count,
                   w.shadow_count);
    } else {
        ok = bench_workload_read(argv[3], &w);
        if (ok && !holds_scene(&w, scene)) {
            fprintf(stderr, "rtk-bench: %s does not hold the triangles of %s\n", argv[3], argv[2]);
            ok = false;
        }
        if (ok) {
            printf("kernel rtk-%s\nload_and_build_s %.4f\nthreads_all %u\n", RT_REAL_NAME, load_s, bench_cpu_count());
            ok = run(scene, &w, repeats, results);
        }
    }
    bench_workload_free(&w);
    rtp_scene_close(&built);
    return ok ? 0 : 1;
}

/* embree-harness: the Embree 3 side of `make bench` (a bench-only dependency, never
 * linked into rtk).
 *
 *   embree-harness WORKLOAD [--repeats N] [--results FILE] [--no-high]
 *
 * Builds one triangle geometry from the workload's world-space triangles (converted to
 * float, Embree's only vertex format) and times rtcCommitScene on a 1-thread device and
 * on a default (all-threads) device, at the default build quality (MEDIUM) and at
 * RTC_BUILD_QUALITY_HIGH (unless --no-high). On the default-quality scene it times
 * rtcIntersect1 on the camera rays and rtcOccluded1 on the shadow rays, then the same
 * rays in packets through rtcIntersect8 and rtcOccluded8 (the camera rays of 4 x 2
 * pixels, the shadow rays of their hits; the coherent context flag); on the HIGH scene
 * the single-ray queries again. Every timing runs with 1 and with all threads, driven by
 * the same loop as rtk's harness. Prints "key value" lines on stdout, progress on
 * stderr; --results writes each single ray's answer for `rtk-bench agree`. */
#include "results.h"
#include "timing.h"
#include "workload.h"
#include <embree3/rtcore.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

typedef struct {
    float origin[3], direction[3];
    float t_min, t_max;
} float_ray;

typedef struct {
    RTCScene scene;
    const float_ray *rays;
    const bench_packets *packets; /* packet rows only */
    uint8_t *hit;
    uint32_t *prim; /* camera rays: the triangle hit, or BENCH_MISS */
} query_job;

/* Net bytes the device has allocated, from its memory monitor callback. */
static atomic_llong device_bytes;

static bool count_bytes(void *ptr, ssize_t bytes, bool post)
{
    (void)ptr;
    (void)post;
    atomic_fetch_add(&device_bytes, (long long)bytes);
    return true;
}

static void on_error(void *ptr, enum RTCError code, const char *message)
{
    (void)ptr;
    fprintf(stderr, "embree-harness: Embree error %d: %s\n", (int)code, message ? message : "");
    exit(1);
}

static RTCDevice new_device(const char *config)
{
    RTCDevice d = rtcNewDevice(config);
    if (!d) {
        fprintf(stderr, "embree-harness: rtcNewDevice(\"%s\") failed (error %d)\n", config ? config : "",
                (int)rtcGetDeviceError(NULL));
        exit(1);
    }
    rtcSetDeviceErrorFunction(d, on_error, NULL);
    rtcSetDeviceMemoryMonitorFunction(d, count_bytes, NULL);
    return d;
}

/* A scene holding the workload's triangles at build quality q, not yet committed. */
static RTCScene new_scene(RTCDevice device, const bench_workload *w, enum RTCBuildQuality q)
{
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, q);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, q);
    float *v =
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), w->vertex_count);
    unsigned *t =
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), w->triangle_count);
    for (size_t i = 0; i < 3 * (size_t)w->vertex_count; i++) v[i] = (float)w->positions[i];
    for (size_t i = 0; i < 3 * (size_t)w->triangle_count; i++) t[i] = w->indices[i];
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return scene;
}

/* Best-of-`repeats` wall seconds of rtcCommitScene on a fresh scene; *best_cpu gets the
 * smallest process CPU time of one commit. */
static double time_build(RTCDevice device, const bench_workload *w, enum RTCBuildQuality q, uint32_t repeats,
                         const char *label, double *best_cpu)
{
    double best = 0.0;
    for (uint32_t r = 0; r < repeats; r++) {
        fprintf(stderr, "  embree: BVH build (%s) %u/%u\n", label, r + 1, repeats);
        RTCScene scene = new_scene(device, w, q);
        double start = bench_now(), cpu = bench_cpu_now();
        rtcCommitScene(scene);
        double s = bench_now() - start;
        cpu = bench_cpu_now() - cpu;
        rtcReleaseScene(scene);
        if (r == 0 || s < best) best = s;
        if (r == 0 || cpu < *best_cpu) *best_cpu = cpu;
    }
    return best;
}

/* Flush-to-zero and denormals-are-zero, as Embree asks of every thread that traces. */
static void fast_denormals(void)
{
#if defined(__SSE2__)
    _mm_setcsr(_mm_getcsr() | 0x8040);
#endif
}

static void intersect_range(void *ctx, uint32_t begin, uint32_t end)
{
    query_job *q = ctx;
    fast_denormals();
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (uint32_t i = begin; i < end; i++) {
        const float_ray *r = &q->rays[i];
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        rh.ray.org_x = r->origin[0], rh.ray.org_y = r->origin[1], rh.ray.org_z = r->origin[2];
        rh.ray.dir_x = r->direction[0], rh.ray.dir_y = r->direction[1], rh.ray.dir_z = r->direction[2];
        rh.ray.tnear = r->t_min;
        rh.ray.tfar = r->t_max;
        rh.ray.mask = UINT32_MAX;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(q->scene, &context, &rh);
        q->hit[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        q->prim[i] = q->hit[i] ? rh.hit.primID : BENCH_MISS;
    }
}

static void occluded_range(void *ctx, uint32_t begin, uint32_t end)
{
    query_job *q = ctx;
    fast_denormals();
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (uint32_t i = begin; i < end; i++) {
        const float_ray *r = &q->rays[i];
        struct RTCRay ray;
        memset(&ray, 0, sizeof ray);
        ray.org_x = r->origin[0], ray.org_y = r->origin[1], ray.org_z = r->origin[2];
        ray.dir_x = r->direction[0], ray.dir_y = r->direction[1], ray.dir_z = r->direction[2];
        ray.tnear = r->t_min;
        ray.tfar = r->t_max;
        ray.mask = UINT32_MAX;
        rtcOccluded1(q->scene, &context, &ray);
        q->hit[i] = ray.tfar == -INFINITY; /* Embree's mark for "occluded" */
    }
}

/* Lane l of an 8-ray packet from ray r. */
static void set_lane(struct RTCRay8 *p, int l, const float_ray *r)
{
    p->org_x[l] = r->origin[0], p->org_y[l] = r->origin[1], p->org_z[l] = r->origin[2];
    p->dir_x[l] = r->direction[0], p->dir_y[l] = r->direction[1], p->dir_z[l] = r->direction[2];
    p->tnear[l] = r->t_min;
    p->tfar[l] = r->t_max;
    p->mask[l] = UINT32_MAX;
    p->time[l] = 0.0f;
    p->id[l] = 0;
    p->flags[l] = 0;
}

/* Packets [begin, end) through rtcIntersect8 (any = false) or rtcOccluded8. */
static void packet_range(void *ctx, uint32_t begin, uint32_t end, bool any)
{
    query_job *q = ctx;
    fast_denormals();
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (uint32_t p = begin; p < end; p++) {
        const uint32_t *ray = q->packets->ray + q->packets->start[p];
        uint32_t n = q->packets->start[p + 1] - q->packets->start[p];
        _Alignas(32) int valid[8];
        _Alignas(32) struct RTCRayHit8 rh;
        memset(&rh, 0, sizeof rh);
        for (uint32_t l = 0; l < 8; l++) {
            valid[l] = l < n ? -1 : 0;
            set_lane(&rh.ray, (int)l, &q->rays[ray[l < n ? l : 0]]);
            rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
        }
        if (any)
            rtcOccluded8(valid, q->scene, &context, &rh.ray);
        else
            rtcIntersect8(valid, q->scene, &context, &rh);
        for (uint32_t l = 0; l < n; l++) {
            q->hit[ray[l]] = any ? rh.ray.tfar[l] == -INFINITY : rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID;
            if (!any) q->prim[ray[l]] = q->hit[ray[l]] ? rh.hit.primID[l] : BENCH_MISS;
        }
    }
}

static void intersect_packets(void *ctx, uint32_t begin, uint32_t end) { packet_range(ctx, begin, end, false); }
static void occluded_packets(void *ctx, uint32_t begin, uint32_t end) { packet_range(ctx, begin, end, true); }

/* Times one query set (name, fn) on the rays: single rays when packets is NULL. The
 * answers land in hit[] and prim[]. */
static void time_set(const char *name, RTCScene scene, const float_ray *rays, uint32_t count,
                     const bench_packets *packets, uint32_t repeats, bench_range_fn fn, uint8_t *hit, uint32_t *prim)
{
    query_job q = {scene, rays, packets, hit, prim};
    bench_time_rays("embree", name, packets ? packets->count : count, count, repeats, fn, &q, hit);
}

static float_ray *float_rays(const bench_ray *in, uint32_t count)
{
    float_ray *rays = malloc((size_t)count * sizeof *rays + 1);
    for (uint32_t i = 0; rays && i < count; i++) {
        for (int k = 0; k < 3; k++) {
            rays[i].origin[k] = (float)in[i].origin[k];
            rays[i].direction[k] = (float)in[i].direction[k];
        }
        rays[i].t_min = (float)in[i].t_min;
        rays[i].t_max = isinf(in[i].t_max) ? INFINITY : (float)in[i].t_max;
    }
    return rays;
}

/* Committed scenes at default and HIGH quality: their bytes, and every query row. */
static bool time_queries(RTCDevice device, const bench_workload *w, uint32_t repeats, bool high, bench_results *r)
{
    float_ray *primary = float_rays(w->primary, w->primary_count), *shadow = float_rays(w->shadow, w->shadow_count);
    uint32_t *prim = calloc((size_t)w->primary_count + 1, sizeof *prim);
    uint8_t *hit = calloc((size_t)w->primary_count + w->shadow_count + 1, 1);
    bench_packets primary_packets = {0}, shadow_packets = {0};
    bool ok = primary && shadow && prim && hit && bench_make_packets(w, false, &primary_packets) &&
              bench_make_packets(w, true, &shadow_packets);
    if (!ok) fprintf(stderr, "embree-harness: out of memory for the rays\n");
    for (int q = 0; ok && q < (high ? 2 : 1); q++) {
        atomic_store(&device_bytes, 0);
        RTCScene scene = new_scene(device, w, q ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
        rtcCommitScene(scene);
        printf("bytes_per_tri%s %.1f\n", q ? "_high" : "",
               (double)atomic_load(&device_bytes) / (w->triangle_count ? w->triangle_count : 1));
        if (q == 0) {
            time_set("primary", scene, primary, w->primary_count, NULL, repeats, intersect_range, r->primary_hit,
                     r->primary_prim);
            time_set("primary_packets", scene, primary, w->primary_count, &primary_packets, repeats, intersect_packets,
                     hit, prim);
            time_set("shadow", scene, shadow, w->shadow_count, NULL, repeats, occluded_range, r->shadow_blocked, NULL);
            time_set("shadow_packets", scene, shadow, w->shadow_count, &shadow_packets, repeats, occluded_packets, hit,
                     NULL);
        } else {
            time_set("primary_high", scene, primary, w->primary_count, NULL, repeats, intersect_range, hit, prim);
            time_set("shadow_high", scene, shadow, w->shadow_count, NULL, repeats, occluded_range, hit, NULL);
        }
        rtcReleaseScene(scene);
    }
    free(primary);
    free(shadow);
    free(prim);
    free(hit);
    bench_packets_free(&primary_packets);
    bench_packets_free(&shadow_packets);
    return ok;
}

int main(int argc, char **argv)
{
    uint32_t repeats = 3;
    const char *results = NULL;
    bool high = true, usage = argc < 2;
    for (int i = 2; i < argc && !usage; i++) {
        if (!strcmp(argv[i], "--no-high"))
            high = false;
        else if (!strcmp(argv[i], "--repeats") && i + 1 < argc && sscanf(argv[i + 1], "%u", &repeats) == 1 && repeats)
            i++;
        else if (!strcmp(argv[i], "--results") && i + 1 < argc)
            results = argv[++i];
        else
            usage = true;
    }
    if (usage) {
        fputs("usage: embree-harness WORKLOAD [--repeats N] [--results FILE] [--no-high]\n", stderr);
        return 2;
    }
    bench_workload w;
    if (!bench_workload_read(argv[1], &w)) return 1;
    bench_results r;
    if (!bench_results_alloc(&w, &r)) return 1;
    double cpu_1, cpu_all, cpu_high_1, cpu_high_all;
    RTCDevice one = new_device("threads=1");
    double build_1 = time_build(one, &w, RTC_BUILD_QUALITY_MEDIUM, repeats, "1 thread", &cpu_1);
    double high_1 = high ? time_build(one, &w, RTC_BUILD_QUALITY_HIGH, repeats, "HIGH, 1 thread", &cpu_high_1) : 0.0;
    rtcReleaseDevice(one);
    RTCDevice all = new_device(NULL);
    double build_all = time_build(all, &w, RTC_BUILD_QUALITY_MEDIUM, repeats, "all threads", &cpu_all);
    double high_all =
        high ? time_build(all, &w, RTC_BUILD_QUALITY_HIGH, repeats, "HIGH, all threads", &cpu_high_all) : 0.0;
    ssize_t version = rtcGetDeviceProperty(all, RTC_DEVICE_PROPERTY_VERSION); /* e.g. 31305 for 3.13.5 */
    printf("kernel embree-%zd.%zd.%zd\nthreads_all %u\nvertices %u\ntriangles %u\n", version / 10000,
           version / 100 % 100, version % 100, bench_cpu_count(), w.vertex_count, w.triangle_count);
    printf("build_s %.4f\nbuild_cpu_s %.4f\nbuild_all_s %.4f\n", build_1, cpu_1, build_all);
    if (high) printf("build_high_s %.4f\nbuild_high_cpu_s %.4f\nbuild_high_all_s %.4f\n", high_1, cpu_high_1, high_all);
    bool ok = time_queries(all, &w, repeats, high, &r);
    if (ok && results) ok = bench_results_write(results, &r);
    rtcReleaseDevice(all);
    bench_results_free(&r);
    bench_workload_free(&w);
    return ok ? 0 : 1;
}

/* embree-harness: the Embree 3 side of `make bench` (a bench-only dependency, never
 * linked into rtk).
 *
 *   embree-harness WORKLOAD [--repeats N]
 *
 * Builds one triangle geometry from the workload's world-space triangles (converted to
 * float, Embree's only vertex format), times rtcCommitScene on a 1-thread device and on
 * a default (all-threads) device, then times rtcIntersect1 on the camera rays and
 * rtcOccluded1 on the shadow rays with 1 and with all threads, driven by the same loop
 * as rtk's harness. Prints "key value" lines on stdout, progress on stderr. */
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
    uint8_t *hit;
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

/* A scene holding the workload's triangles, not yet committed. */
static RTCScene new_scene(RTCDevice device, const bench_workload *w)
{
    RTCScene scene = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
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
static double time_build(RTCDevice device, const bench_workload *w, uint32_t repeats, const char *label,
                         double *best_cpu)
{
    double best = 0.0;
    for (uint32_t r = 0; r < repeats; r++) {
        fprintf(stderr, "  embree: BVH build (%s) %u/%u\n", label, r + 1, repeats);
        RTCScene scene = new_scene(device, w);
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

static bool time_queries(const char *name, RTCScene scene, const bench_ray *in, uint32_t count, uint32_t repeats,
                         bench_range_fn fn)
{
    float_ray *rays = malloc((size_t)count * sizeof *rays + 1);
    uint8_t *hit = calloc((size_t)count + 1, 1);
    if (!rays || !hit) {
        free(rays);
        free(hit);
        fprintf(stderr, "embree-harness: out of memory for %u rays\n", count);
        return false;
    }
    for (uint32_t i = 0; i < count; i++) {
        for (int k = 0; k < 3; k++) {
            rays[i].origin[k] = (float)in[i].origin[k];
            rays[i].direction[k] = (float)in[i].direction[k];
        }
        rays[i].t_min = (float)in[i].t_min;
        rays[i].t_max = isinf(in[i].t_max) ? INFINITY : (float)in[i].t_max;
    }
    query_job q = {scene, rays, hit};
    bench_time_rays("embree", name, count, repeats, fn, &q, hit);
    free(rays);
    free(hit);
    return true;
}

int main(int argc, char **argv)
{
    uint32_t repeats = 3;
    if (argc != 2 && !(argc == 4 && !strcmp(argv[2], "--repeats") && sscanf(argv[3], "%u", &repeats) == 1 && repeats)) {
        fputs("usage: embree-harness WORKLOAD [--repeats N]\n", stderr);
        return 2;
    }
    bench_workload w;
    if (!bench_workload_read(argv[1], &w)) return 1;
    RTCDevice one = new_device("threads=1");
    double build_1_cpu, build_all_cpu;
    double build_1 = time_build(one, &w, repeats, "1 thread", &build_1_cpu);
    rtcReleaseDevice(one);
    RTCDevice all = new_device(NULL);
    double build_all = time_build(all, &w, repeats, "all threads", &build_all_cpu);
    atomic_store(&device_bytes, 0);
    RTCScene scene = new_scene(all, &w);
    rtcCommitScene(scene);
    long long bytes = atomic_load(&device_bytes);
    ssize_t version = rtcGetDeviceProperty(all, RTC_DEVICE_PROPERTY_VERSION); /* e.g. 31305 for 3.13.5 */
    printf("kernel embree-%zd.%zd.%zd\nthreads_all %u\nvertices %u\ntriangles %u\n", version / 10000,
           version / 100 % 100, version % 100, bench_cpu_count(), w.vertex_count, w.triangle_count);
    printf("bytes_per_tri %.1f\nbuild_s %.4f\nbuild_cpu_s %.4f\nbuild_all_s %.4f\n",
           (double)bytes / (w.triangle_count ? w.triangle_count : 1), build_1, build_1_cpu, build_all);
    bool ok = time_queries("primary", scene, w.primary, w.primary_count, repeats, intersect_range) &&
              time_queries("shadow", scene, w.shadow, w.shadow_count, repeats, occluded_range);
    rtcReleaseScene(scene);
    rtcReleaseDevice(all);
    bench_workload_free(&w);
    return ok ? 0 : 1;
}

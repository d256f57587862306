/* The benchmark's shared input: world-space triangles and the rays to trace, in one
 * binary file written by the rtk double build and read by every kernel under test,
 * so rtk (double and fixed) and Embree see exactly the same geometry and rays.
 * Native byte order: the file lives only for one `make bench` run on one machine. */
#ifndef BENCH_WORKLOAD_H
#define BENCH_WORKLOAD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* t_max = INFINITY means "unbounded" (camera rays, rays towards a directional light). */
typedef struct {
    double origin[3], direction[3];
    double t_min, t_max;
} bench_ray;

typedef struct {
    uint32_t vertex_count, triangle_count;
    double *positions;      /* 3 per vertex, world space */
    uint32_t *indices;      /* 3 per triangle */
    uint32_t width, height; /* primary rays: one per pixel centre, row by row, row 0 at the top */
    uint32_t primary_count, shadow_count;
    bench_ray *primary;      /* camera rays */
    bench_ray *shadow;       /* from each primary hit towards the light, in the primary rays' order */
    uint32_t *shadow_source; /* the primary ray each shadow ray starts from */
} bench_workload;

/* Both print one line on stderr naming the file when they fail. */
bool bench_workload_write(const char *path, const bench_workload *w);
bool bench_workload_read(const char *path, bench_workload *w);
void bench_workload_free(bench_workload *w);

/* Rays in packets for the packet rows: the camera rays of each block of 4 x 2 pixels,
 * and the shadow rays that start from one block's hits. Packet p holds the rays
 * ray[start[p] .. start[p + 1]) (1 to 8 of them; indices into the primary or the
 * shadow array), in a malloc'd array that bench_packets_free releases. */
#define BENCH_PACKET 8
typedef struct {
    uint32_t count;  /* packets */
    uint32_t *start; /* count + 1 offsets */
    uint32_t *ray;
} bench_packets;

bool bench_make_packets(const bench_workload *w, bool shadow, bench_packets *out);
void bench_packets_free(bench_packets *p);

#endif

/* What a built scene holds and what it costs, for `rtk info`. */
#ifndef RTP_SCENE_STATS_H
#define RTP_SCENE_STATS_H

#include "load/scene_open.h"

typedef struct {
    uint32_t nodes;                      /* enabled nodes of the file */
    uint32_t spheres, cylinders, meshes; /* traced objects by kind (a Plane is a mesh) */
    uint64_t triangles_loaded;           /* mesh triangles before Loop subdivision */
    uint32_t triangles;                  /* after subdivision: what the BVH holds */
    uint32_t lights[3];                  /* by rt_light_kind */
    uint32_t bvh_nodes, bvh_leaves, bvh_depth;
    double sah_cost;
    size_t arena_used, arena_high_water, arena_capacity;
} rtp_scene_stats;

void rtp_scene_stats_compute(const rtp_scene *built, rtp_scene_stats *out);

/* The BVH's expected cost of a ray under the surface area heuristic, with a traversal
 * step and a primitive test both costing 1: the sum over inner nodes of A(n) / A(root)
 * plus the sum over leaves of count * A(n) / A(root), A the surface area. */
double rtp_scene_stats_sah_cost(const rt_bvh *bvh, uint32_t prim_count);

#endif

/* Makes the benchmark workload from a built rtk scene. */
#ifndef BENCH_RTK_RAYS_H
#define BENCH_RTK_RAYS_H

#include "bvh.h"
#include "scene_query.h"
#include "workload.h"

/* Fills w (malloc'd arrays; bench_workload_free releases them) with the scene's
 * world-space triangles, one camera ray per pixel centre of a width x height image
 * (as rtk render shoots them), and one shadow ray from every primary hit towards the
 * scene's first point light (else its first directional light). Fails with a line on
 * stderr naming `path` (the scene's file) when the scene has spheres or cylinders (the
 * comparison is triangles only) or no light, or when memory runs out. */
bool bench_make_workload(const char *path, const rt_scene *scene, uint32_t width, uint32_t height, bench_workload *w);

#endif

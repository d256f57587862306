/* Mesh processing in object space: generated normals and Loop subdivision. */
#ifndef RT_MESH_H
#define RT_MESH_H

#include "scene.h"

/* Area-weighted smooth vertex normals (format.md §6.6): for each vertex, the sum of the
 * unnormalised cross(b - a, c - a) of every triangle that has a vertex at exactly the
 * same position (compared bit for bit), normalised. Returns vertex_count normals. */
rt_status rt_mesh_smooth_normals(const rt_mesh_desc *mesh, rt_arena *arena, rt_vec3 **normals_out);

/* Loop subdivision as the format defines it (format.md §6.7), `levels` times (1..RT_MAX_SUBDIVISION):
 * the result has limit-surface positions, limit normals and midpoint uvs (when the input
 * has uvs). All arrays of *out live in the arena. */
rt_status rt_mesh_subdivide(const rt_mesh_desc *mesh, uint32_t levels, rt_arena *arena, rt_mesh_desc *out);

#endif

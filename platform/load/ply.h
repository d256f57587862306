/* PLY mesh reader: ASCII, binary_little_endian and binary_big_endian. */
#ifndef RTP_PLY_H
#define RTP_PLY_H

#include "scene.h"
#include <stddef.h>

/* A mesh as read from a file; all arrays are malloc'd and released by rtp_ply_free.
 * normals and uvs are NULL when the file has none. Polygons are fan-triangulated and
 * degenerate triangles (repeated index or zero area) are dropped. */
typedef struct {
    rt_vec3 *positions;
    rt_vec3 *normals;
    rt_vec2 *uvs;
    uint32_t vertex_count;
    uint32_t *indices;
    uint32_t triangle_count;
} rtp_ply_mesh;

/* Reads path. On failure returns false and writes one line to err (no newline):
 * "<path>: <place>: <what was wrong>", place being "line N" (header/ASCII) or
 * "byte N" (binary). */
bool rtp_ply_read(const char *path, rtp_ply_mesh *out, char *err, size_t err_size);
void rtp_ply_free(rtp_ply_mesh *mesh);
/* A borrowed view for rt_scene_desc. */
rt_mesh_desc rtp_ply_view(const rtp_ply_mesh *mesh);

#endif

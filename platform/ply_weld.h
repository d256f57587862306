/* Joining identical vertices of a mesh read from a PLY file. */
#ifndef RT_PLY_WELD_H
#define RT_PLY_WELD_H

#include "ply.h"

/* Merges vertices whose position, normal and uv are bit-identical, keeping the first of
 * each in file order and renumbering the triangles. False (mesh unchanged) when out of memory. */
bool rt_ply_weld(rt_ply_mesh *mesh);

#endif

/* The format's built-in meshes. */
#ifndef RT_BUILTIN_MESH_H
#define RT_BUILTIN_MESH_H

#include "scene.h"

/* The built-in meshes of the format: the Cube (24 vertices, 12 triangles) and the
 * Plane's unit square in XY. The arrays are constant tables. */
rt_mesh_desc rt_builtin_mesh_cube(void);
rt_mesh_desc rt_builtin_mesh_square(void);

#endif

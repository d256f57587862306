/* The format's built-in meshes (format.md §6.1 and §5.7) as constant tables. */
#include "builtin_mesh.h"

#define H RT_C(0.5)
#define N RT_C(-0.5)
#define O RT_ZERO
#define I RT_ONE

/* Faces in the order back, front, left, right, bottom, top; four corners each. */
static const rt_vec3 cube_positions[24] = {
    {N, N, N}, {N, H, N}, {H, N, N}, {H, H, N}, /* back, (x, y) at z = -0.5 */
    {N, N, H}, {N, H, H}, {H, N, H}, {H, H, H}, /* front, (x, y) at z = +0.5 */
    {N, N, N}, {N, N, H}, {N, H, N}, {N, H, H}, /* left, (y, z) at x = -0.5 */
    {H, N, N}, {H, N, H}, {H, H, N}, {H, H, H}, /* right, (y, z) at x = +0.5 */
    {N, N, H}, {N, N, N}, {H, N, H}, {H, N, N}, /* bottom, (x, z) at y = -0.5 */
    {N, H, H}, {N, H, N}, {H, H, H}, {H, H, N}, /* top, (x, z) at y = +0.5 */
};

static const rt_vec3 cube_normals[24] = {
    {O, O, -I}, {O, O, -I}, {O, O, -I}, {O, O, -I}, {O, O, I}, {O, O, I}, {O, O, I}, {O, O, I},
    {-I, O, O}, {-I, O, O}, {-I, O, O}, {-I, O, O}, {I, O, O}, {I, O, O}, {I, O, O}, {I, O, O},
    {O, -I, O}, {O, -I, O}, {O, -I, O}, {O, -I, O}, {O, I, O}, {O, I, O}, {O, I, O}, {O, I, O},
};

/* Every face lists its corners with uv (0,0), (0,1), (1,0), (1,1). */
static const rt_vec2 cube_uvs[24] = {
    {O, O}, {O, I}, {I, O}, {I, I}, {O, O}, {O, I}, {I, O}, {I, I}, {O, O}, {O, I}, {I, O}, {I, I},
    {O, O}, {O, I}, {I, O}, {I, I}, {O, O}, {O, I}, {I, O}, {I, I}, {O, O}, {O, I}, {I, O}, {I, I},
};

/* Per face, corners (0,1,2)(2,1,3) for back/left/bottom and (1,0,2)(1,2,3) for front/right/top. */
static const uint32_t cube_indices[36] = {
    0,  1,  2,  2,  1,  3,  5,  4,  6,  5,  6,  7,  8,  9,  10, 10, 9,  11,
    13, 12, 14, 13, 14, 15, 16, 17, 18, 18, 17, 19, 21, 20, 22, 21, 22, 23,
};

static const rt_vec3 square_positions[4] = {{N, N, O}, {H, N, O}, {H, H, O}, {N, H, O}};
static const rt_vec3 square_normals[4] = {{O, O, I}, {O, O, I}, {O, O, I}, {O, O, I}};
static const rt_vec2 square_uvs[4] = {{O, O}, {I, O}, {I, I}, {O, I}};
static const uint32_t square_indices[6] = {0, 1, 2, 0, 2, 3};

rt_mesh_desc rt_builtin_mesh_cube(void)
{
    rt_mesh_desc d = {cube_positions, cube_normals, cube_uvs, 24, cube_indices, 12};
    return d;
}

rt_mesh_desc rt_builtin_mesh_square(void)
{
    rt_mesh_desc d = {square_positions, square_normals, square_uvs, 4, square_indices, 2};
    return d;
}

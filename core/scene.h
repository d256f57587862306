/* The scene: what the platform loaders describe (rt_scene_desc, plain arrays the
 * caller owns) and what the kernel renders (rt_scene, built once into an arena by
 * rt_scene_build and read-only afterwards). */
#ifndef RT_SCENE_H
#define RT_SCENE_H

#include "aabb.h"
#include "arena.h"
#include "status.h"
#include "vec.h"
#include "workers.h"

#define RT_NO_TEXTURE UINT32_MAX

/* The limits of what a scene may ask for, in one place for the loaders, the build and
 * the blob reader. */
#define RT_MAX_SUBDIVISION 5
/* Rays recurse on the C stack: deeper scenes are rejected, not crashed. */
#define RT_MAX_RECURSION_DEPTH 64
/* Image sides, rendered or read as textures: a 16384 x 16384 RGB image is 768 MiB. */
#define RT_MAX_IMAGE_SIDE 16384u
/* Samples Per Pixel is an index: 4^index samples, index 0..7 (16384 samples). */
#define RT_MAX_SPP_INDEX 7
/* Minimum / Maximum Samples of the adaptive types: 4^min .. 4^(max+1). */
#define RT_MAX_MIN_SAMPLES_INDEX 4
#define RT_MAX_MAX_SAMPLES_INDEX 6

/* The Shadows setting (format.md §9.2). */
typedef enum {
    RT_SHADOWS_NONE,
    RT_SHADOWS_OPAQUE,
    RT_SHADOWS_COLOURED,
    RT_SHADOWS_LAST = RT_SHADOWS_COLOURED
} rt_shadow_mode;
/* The Monte Carlo setting (format.md §11): off (Whitted), uniform or stratified random samples. */
typedef enum {
    RT_MONTE_CARLO_OFF,
    RT_MONTE_CARLO_UNIFORM,
    RT_MONTE_CARLO_STRATIFIED,
    RT_MONTE_CARLO_LAST = RT_MONTE_CARLO_STRATIFIED
} rt_monte_carlo_mode;
/* The Sample Count Type setting (format.md §10). */
typedef enum {
    RT_SAMPLES_CONSTANT,
    RT_SAMPLES_ADAPTIVE,  /* recursive subdivision while corner colours differ */
    RT_SAMPLES_STD_ERROR, /* until the mean's standard error is small */
    RT_SAMPLES_LAST = RT_SAMPLES_STD_ERROR
} rt_sample_count_type;

/* ---- Description: filled in by a loader, consumed by rt_scene_build. ---- */

/* One material input: a solid colour, or a texture that replaces it. */
typedef struct {
    rt_vec3 color;    /* already quantised to byte/255 by the loader (format.md §4.5) */
    uint32_t texture; /* index into textures, or RT_NO_TEXTURE */
} rt_channel;

typedef struct {
    rt_channel diffuse, specular, emissive, transmittance;
    rt_real shininess;
    rt_real index_of_refraction;
} rt_material;

typedef struct {
    uint32_t width, height;
    const uint8_t *rgb; /* width * height * 3 bytes, row 0 = top of the image */
    bool bilinear;
} rt_texture;

/* A triangle mesh in object space. normals and uvs may be NULL. */
typedef struct {
    const rt_vec3 *positions;
    const rt_vec3 *normals;
    const rt_vec2 *uvs;
    uint32_t vertex_count;
    const uint32_t *indices; /* 3 per triangle */
    uint32_t triangle_count;
} rt_mesh_desc;

typedef enum { RT_SHAPE_SPHERE, RT_SHAPE_CYLINDER, RT_SHAPE_MESH } rt_shape_kind;

typedef struct {
    rt_shape_kind kind;
    rt_affine world;
    uint32_t material;
    uint32_t mesh;        /* RT_SHAPE_MESH: index into rt_scene_desc.meshes */
    uint32_t subdivision; /* RT_SHAPE_MESH: Loop subdivision levels, 0..RT_MAX_SUBDIVISION */
    uint32_t source;      /* caller's id for the node (reported by the debugger) */
} rt_object_desc;

typedef enum { RT_LIGHT_POINT, RT_LIGHT_DIRECTIONAL, RT_LIGHT_AREA } rt_light_kind;

typedef struct {
    rt_light_kind kind;
    rt_affine world;
    rt_vec3 color; /* directional: already multiplied by its Intensity Multiplier */
    rt_vec3 ambient;
    rt_real atten_const, atten_linear, atten_quad; /* point and area lights */
} rt_light_desc;

typedef struct {
    uint32_t max_depth;
    rt_shadow_mode shadows;
    bool reflections, refractions;
    uint32_t samples_per_pixel_index; /* samples = 4^index */
    rt_monte_carlo_mode monte_carlo;
    bool diffuse_reflection, caustics, random_single_branching;
    rt_real focus_distance, aperture_size;
    rt_sample_count_type sample_count_type;
    uint32_t min_samples_index;   /* adaptive types: at least 4^index samples */
    uint32_t max_samples_index;   /* adaptive types: at most 4^(index+1) samples */
    rt_real difference_threshold; /* type 1: split while corner colours differ by more */
    rt_real std_error_threshold;  /* type 2: stop once the mean's standard error is below */
} rt_trace_settings;

typedef struct {
    rt_affine world;
    rt_real fov_degrees; /* full vertical angle */
    bool perspective;
    rt_real ortho_width;
    uint32_t width, height;
    rt_trace_settings trace;
} rt_camera_desc;

typedef struct {
    const rt_material *materials;
    uint32_t material_count;
    const rt_texture *textures;
    uint32_t texture_count;
    const rt_mesh_desc *meshes;
    uint32_t mesh_count;
    const rt_object_desc *objects;
    uint32_t object_count;
    const rt_light_desc *lights;
    uint32_t light_count;
    rt_camera_desc camera;
} rt_scene_desc;

/* ---- Built scene: world space, ready to trace. ---- */

typedef struct {
    rt_shape_kind kind;
    uint32_t material;
    uint32_t source;
    rt_affine to_world, to_object;
    rt_mat3 normal_to_world; /* inverse transpose of to_world.linear */
    bool to_object_diagonal; /* to_object.linear is zero off its diagonal (no rotation) */
    /* A mesh's triangles are rt_scene.triangles[first_triangle .. + triangle_count). */
    uint32_t first_triangle, triangle_count;
} rt_object;

typedef struct {
    uint32_t v[3]; /* indices into rt_scene.positions / normals / uvs */
} rt_triangle;

typedef struct {
    rt_light_kind kind;
    rt_vec3 position;  /* point and area lights */
    rt_vec3 direction; /* directional: unit vector towards the light */
    rt_vec3 color, ambient;
    rt_real atten_const, atten_linear, atten_quad;
    /* Area lights: the node's unit square in local XZ is corner + u edge_u + v edge_v,
     * u, v in [0,1]; it emits to the side of normal (local +Y; zero if degenerate). */
    rt_vec3 corner, edge_u, edge_v, normal;
} rt_light;

typedef struct {
    rt_vec3 eye, forward, right, up;
    rt_real tan_half_fov, aspect;
    /* forward, right and up scaled to the image plane at Focus Distance (rt_camera_prepare) */
    rt_vec3 plane_forward, plane_right, plane_up;
    bool perspective;
    rt_real ortho_width;
    uint32_t width, height;
    rt_trace_settings trace;
} rt_camera;

/* A BVH node, 32 bytes a slot: up to RT_BVH_WIDTH children, each an inner node or a leaf.
 * Child c's box is box[k][c] for the planes k = lo x, y, z, hi x, y, z, rounded outwards
 * to four bytes (rt_bound, on the tree's grid). An inner child is nodes[child[c]] with
 * count[c] = 0; a leaf child covers prim_refs[child[c] .. child[c] + count[c]); an
 * unused slot has count[c] = RT_BVH_NO_CHILD. Slots are filled from 0. Eight slots where
 * the double build tests a node's boxes with vectors (x86: SSE2 and AVX2, bvh_float.h),
 * four where the test is scalar (the fixed build, other targets) and pays for every slot. */
#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
#define RT_BVH_WIDTH 8
#else
#define RT_BVH_WIDTH 4
#endif
#define RT_BVH_NO_CHILD UINT32_MAX
/* prim_refs ends with this many zeros past its last reference: a leaf's four-lane loads
 * (bvh_leaf.h) may read three entries past the leaf. */
#define RT_BVH_REF_PAD 3
typedef struct {
    rt_bound box[6][RT_BVH_WIDTH];
    uint32_t child[RT_BVH_WIDTH];
    uint32_t count[RT_BVH_WIDTH];
} rt_bvh_node;
_Static_assert(sizeof(rt_bvh_node) == 32 * RT_BVH_WIDTH, "a BVH node is whole 64-byte cache lines");

/* The query code the BVH runs: every kernel gives the same results. The build picks the
 * best one the compiler's target guarantees (SSE2 on x86-64); the platform may pick
 * another with rt_bvh_set_kernel after asking the CPU (the core never does). */
typedef enum {
    RT_KERNEL_PORTABLE, /* the general walk, one ray at a time */
    RT_KERNEL_SSE2,     /* float box tests (double build, x86), packets in 128-bit vectors */
    RT_KERNEL_AVX2,     /* the same with packets in 256-bit vectors */
    RT_KERNEL_AVX512    /* avx2's, with a packet's triangle tests in one 512-bit vector */
} rt_kernel;

typedef struct {
    rt_bvh_node *nodes;
    uint32_t node_count;
    uint32_t *prim_refs;
    uint32_t depth;
    int grid;       /* of the nodes' boxes (rt_bound_grid) */
    rt_real extent; /* the largest |coordinate| of the primitives' padded bounds (0 for none) */
    rt_kernel kernel;
} rt_bvh;

typedef struct {
    rt_material *materials;
    uint32_t material_count;
    rt_texture *textures;
    uint32_t texture_count;
    rt_object *objects;
    uint32_t object_count;
    rt_light *lights;
    uint32_t light_count;
    /* All mesh triangles, in world space. */
    rt_vec3 *positions;
    rt_vec3 *normals; /* world-space vertex normals, not renormalised */
    rt_vec2 *uvs;     /* NULL when no mesh has uvs (they are all 0 then) */
    uint32_t vertex_count;
    rt_triangle *triangles;
    uint32_t triangle_count;
    /* Primitive references: 0 .. triangle_count-1 are triangles, then one per
     * sphere/cylinder object (see rt_prim_*). */
    uint32_t *quadric_objects;
    uint32_t prim_count;
    /* The mesh objects in order, so in increasing first_triangle (see rt_scene_triangle_object). */
    uint32_t *mesh_objects;
    uint32_t mesh_object_count;
    rt_bvh bvh;
    rt_camera camera;
} rt_scene;

/* What went wrong in rt_scene_build, for the platform to report. */
typedef struct {
    rt_status status;
    const char *what; /* a short phrase: "transform is singular", ... */
    uint32_t object;  /* the offending object (or light) index, or UINT32_MAX */
} rt_build_error;

/* Copies desc into the arena, transforms meshes to world space, subdivides, builds the
 * BVH on the workers (NULL: on this thread; the scene is the same either way). */
rt_status rt_scene_build(const rt_scene_desc *desc, rt_arena *arena, const rt_workers *workers, rt_scene *out,
                         rt_build_error *err);

/* The unit direction towards a directional light whose node has this world transform
 * (its local +Y axis); zero when the transform flattens that axis, which the build refuses. */
rt_vec3 rt_scene_light_direction(const rt_affine *world);

#endif

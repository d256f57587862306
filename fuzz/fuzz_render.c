/* libFuzzer target: a whole render. A small scene description from the bytes
 * (spheres, cylinders, Cubes, Planes and a free mesh; materials, textures, lights,
 * camera and trace settings) goes through rt_scene_build, and, when accepted, a 4x4
 * image through rt_render_region. No crash, no UB, the same bytes tile by tile; for
 * bounded scenes also no NaN, infinite or (fixed build) saturated colour, and the same
 * bytes with or without the BVH. In raw mode some numbers are arbitrary bit patterns,
 * which the build must refuse or survive. */
#include <string.h>

#include "builtin_mesh.h"
#include "check.h"
#include "fixture.h"
#include "render.h"

#define SIDE 4

typedef struct {
    fz_bytes in;
    bool raw; /* some reals are raw bit patterns */
} source;

/* A real in [lo, hi]; in raw mode one in eight is any bit pattern at all. */
static rt_real real(source *s, double lo, double hi)
{
    if (s->raw && fz_u8(&s->in) % 8 == 0) return fz_raw(&s->in);
    return rt_from_double(fz_range(&s->in, lo, hi));
}

static rt_vec3 vec(source *s, double lo, double hi)
{
    rt_real x = real(s, lo, hi), y = real(s, lo, hi);
    return rt_v3(x, y, real(s, lo, hi));
}

/* An index below n, or (one in sixteen) exactly n: one past the end. */
static uint32_t index_or_bad(source *s, uint32_t n)
{
    uint16_t v = fz_u16(&s->in);
    return v % 16 == 0 ? n : n ? (v >> 4) % n : 0;
}

static rt_affine transform(source *s, double reach)
{
    rt_vec3 t = vec(s, -reach, reach), r = vec(s, -180, 180);
    rt_real sx = real(s, 0.25, 2), sy = real(s, 0.25, 2);
    return rt_affine_trs(t, r, rt_v3(sx, sy, real(s, 0.25, 2)));
}

static rt_channel channel(source *s, uint32_t textures)
{
    rt_channel c = {vec(s, 0, 1), RT_NO_TEXTURE};
    if (fz_u8(&s->in) % 4 == 0) c.texture = index_or_bad(s, textures);
    return c;
}

typedef struct {
    rt_material materials[3];
    uint8_t texels[2][4 * 4 * 3];
    rt_texture textures[2];
    rt_vec3 positions[6], normals[6];
    rt_vec2 uvs[6];
    uint32_t indices[18];
    rt_mesh_desc meshes[3];
    rt_object_desc objects[6];
    rt_light_desc lights[3];
} storage;

static void describe(source *s, storage *st, rt_scene_desc *d)
{
    memset(d, 0, sizeof *d);
    d->texture_count = fz_below(&s->in, 3);
    for (uint32_t i = 0; i < d->texture_count; i++) {
        rt_texture *t = &st->textures[i];
        t->width = fz_below(&s->in, 5);
        t->height = 1 + fz_below(&s->in, 4);
        for (size_t k = 0; k < sizeof st->texels[i]; k++) st->texels[i][k] = fz_u8(&s->in);
        t->rgb = st->texels[i];
        t->bilinear = fz_u8(&s->in) & 1;
    }
    d->material_count = 1 + fz_below(&s->in, 3);
    for (uint32_t i = 0; i < d->material_count; i++) {
        rt_material *m = &st->materials[i];
        m->diffuse = channel(s, d->texture_count);
        m->specular = channel(s, d->texture_count);
        m->emissive = channel(s, d->texture_count);
        m->transmittance = channel(s, d->texture_count);
        m->shininess = real(s, 0, 128);
        m->index_of_refraction = real(s, 0.5, 2.5);
    }
    /* Meshes: the Cube, the Plane and a free mesh of up to 6 vertices and 6 triangles. */
    st->meshes[0] = rt_builtin_mesh_cube();
    st->meshes[1] = rt_builtin_mesh_square();
    rt_mesh_desc *free_mesh = &st->meshes[2];
    free_mesh->vertex_count = 1 + fz_below(&s->in, 6);
    free_mesh->triangle_count = fz_below(&s->in, 7);
    for (uint32_t v = 0; v < free_mesh->vertex_count; v++) {
        st->positions[v] = vec(s, -1, 1);
        st->normals[v] = vec(s, -1, 1);
        st->uvs[v] = (rt_vec2){real(s, -1, 2), real(s, -1, 2)};
    }
    for (uint32_t k = 0; k < 3 * free_mesh->triangle_count; k++)
        st->indices[k] = index_or_bad(s, free_mesh->vertex_count);
    uint8_t attributes = fz_u8(&s->in);
    free_mesh->positions = st->positions;
    free_mesh->normals = attributes & 1 ? st->normals : NULL;
    free_mesh->uvs = attributes & 2 ? st->uvs : NULL;
    free_mesh->indices = st->indices;
    d->mesh_count = 3;
    d->object_count = fz_below(&s->in, 7);
    for (uint32_t i = 0; i < d->object_count; i++) {
        rt_object_desc *o = &st->objects[i];
        uint8_t kind = fz_u8(&s->in);
        o->kind = kind % 3 == 0 ? RT_SHAPE_SPHERE : kind % 3 == 1 ? RT_SHAPE_CYLINDER : RT_SHAPE_MESH;
        o->world = transform(s, 2);
        o->material = index_or_bad(s, d->material_count);
        o->mesh = index_or_bad(s, d->mesh_count);
        /* Mostly 0..2 levels; rarely one above the limit, which the build refuses. */
        uint8_t levels = fz_u8(&s->in);
        o->subdivision = levels % 64 == 0 ? RT_MAX_SUBDIVISION + 1 : levels % 4 == 3 ? 0 : levels % 4;
        o->source = i;
    }
    d->light_count = fz_below(&s->in, 4);
    for (uint32_t i = 0; i < d->light_count; i++) {
        rt_light_desc *l = &st->lights[i];
        l->kind = (rt_light_kind)fz_below(&s->in, 3);
        l->world = transform(s, 4);
        l->color = vec(s, 0, 2);
        l->ambient = vec(s, 0, 0.3);
        l->atten_const = real(s, 0, 1);
        l->atten_linear = real(s, 0, 1);
        l->atten_quad = real(s, 0, 1);
    }
    rt_camera_desc *c = &d->camera;
    c->world = rt_affine_trs(rt_v3_add(vec(s, -1, 1), rt_v3(RT_ZERO, RT_ZERO, RT_C(5.0))), vec(s, -20, 20),
                             rt_v3(RT_ONE, RT_ONE, RT_ONE));
    c->fov_degrees = real(s, 5, 175);
    c->perspective = fz_u8(&s->in) % 4 != 0;
    c->ortho_width = real(s, 0.5, 8);
    c->width = c->height = SIDE;
    rt_trace_settings *t = &c->trace;
    uint8_t flags = fz_u8(&s->in);
    t->max_depth = fz_below(&s->in, 5);
    t->shadows = fz_below(&s->in, 4);
    t->reflections = flags & 1;
    t->refractions = flags & 2;
    t->diffuse_reflection = flags & 4;
    t->caustics = flags & 8;
    t->random_single_branching = flags & 16;
    t->samples_per_pixel_index = fz_below(&s->in, 2);
    t->monte_carlo = fz_below(&s->in, 3);
    t->sample_count_type = fz_below(&s->in, 3);
    t->min_samples_index = fz_below(&s->in, 2);
    t->max_samples_index = fz_below(&s->in, 2);
    t->difference_threshold = real(s, 0, 0.5);
    t->std_error_threshold = real(s, 0, 0.5);
    t->focus_distance = real(s, 0, 8);
    t->aperture_size = real(s, 0, 0.5);
    d->textures = st->textures;
    d->materials = st->materials;
    d->meshes = st->meshes;
    d->objects = st->objects;
    d->lights = st->lights;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    source s = {fz_bytes_of(data, size), false};
    s.raw = fz_u8(&s.in) % 4 == 0;
    static storage st;
    memset(&st, 0, sizeof st);
    rt_scene_desc desc;
    describe(&s, &st, &desc);
    rt_scene scene;
    rt_build_error err;
    if (fz_build(&desc, &scene, &err) != RT_OK) return 0;
    uint8_t with_bvh[SIDE * SIDE * 3], without[SIDE * SIDE * 3], tiles[SIDE * SIDE * 3];
    rt_tracer tr = {.scene = &scene, .use_bvh = true};
    rt_render_region(&tr, 0, 0, SIDE, SIDE, with_bvh);
    /* Tiles in another order: the bytes of a pixel depend on nothing else. */
    rt_render_region(&tr, 0, SIDE / 2, SIDE, SIDE, tiles);
    rt_render_region(&tr, 0, 0, SIDE, SIDE / 2, tiles);
    FZ_CHECK(memcmp(with_bvh, tiles, sizeof tiles) == 0, "rendering by tiles changed the image");
    /* Raw transforms put quadrics beyond their intersector's precision (see
     * docs/robustness.md), where BVH culling legitimately differs: no check there. */
    if (s.raw) return 0;
    tr.use_bvh = false;
    rt_render_region(&tr, 0, 0, SIDE, SIDE, without);
    FZ_CHECK(memcmp(with_bvh, without, sizeof without) == 0, "the BVH changed the image");
    tr.use_bvh = true;
    for (uint32_t y = 0; y < SIDE; y++)
        for (uint32_t x = 0; x < SIDE; x++) {
            rt_vec3 c = rt_render_pixel(&tr, x, y);
            /* rt_is_finite: not NaN or infinite in double, not saturated in Q32.32 (where
             * c.x == c.x, the NaN test this replaces, could not fail). */
            FZ_CHECK(rt_is_finite(c.x) && rt_is_finite(c.y) && rt_is_finite(c.z),
                     "pixel (%u, %u) of a bounded scene is %.17g %.17g %.17g", x, y, rt_to_double(c.x),
                     rt_to_double(c.y), rt_to_double(c.z));
        }
    return 0;
}

/* Scene blobs; see blob.h. One function, transfer(), lists every field once and
 * serves the size pass, the writer and the reader alike. */
#include "blob.h"

#define BLOB_VERSION 1u

typedef enum { BLOB_SIZE, BLOB_WRITE, BLOB_READ } blob_mode;

typedef struct {
    blob_mode mode;
    uint8_t *out;      /* BLOB_WRITE */
    const uint8_t *in; /* BLOB_READ */
    size_t capacity, pos;
    rt_arena *arena; /* BLOB_READ */
    bool failed, out_of_memory;
} blob_io;

static void io_bytes(blob_io *io, void *data, size_t n)
{
    if (io->failed) return;
    if (io->mode != BLOB_SIZE && n > io->capacity - io->pos) {
        io->failed = true;
        return;
    }
    uint8_t *p = data;
    if (io->mode == BLOB_WRITE)
        for (size_t i = 0; i < n; i++) io->out[io->pos + i] = p[i];
    else if (io->mode == BLOB_READ)
        for (size_t i = 0; i < n; i++) p[i] = io->in[io->pos + i];
    io->pos += n;
}

static void io_u64(blob_io *io, uint64_t *v)
{
    uint8_t b[8];
    for (int i = 0; i < 8; i++) b[i] = (uint8_t)(*v >> (8 * i));
    io_bytes(io, b, 8);
    if (io->mode == BLOB_READ) {
        uint64_t r = 0;
        for (int i = 0; i < 8; i++) r |= (uint64_t)b[i] << (8 * i);
        *v = r;
    }
}

static void io_u32(blob_io *io, uint32_t *v)
{
    uint64_t w = *v;
    io_u64(io, &w);
    if (io->mode == BLOB_READ) {
        if (w > UINT32_MAX) io->failed = true;
        *v = (uint32_t)w;
    }
}

static void io_bool(blob_io *io, bool *v)
{
    uint32_t w = *v ? 1u : 0u;
    io_u32(io, &w);
    *v = w != 0;
}

static void io_real(blob_io *io, rt_real *v)
{
    uint64_t bits = rt_real_to_bits(*v);
    io_u64(io, &bits);
    if (io->mode == BLOB_READ) *v = rt_real_from_bits(bits);
}

static void io_vec3(blob_io *io, rt_vec3 *v)
{
    io_real(io, &v->x);
    io_real(io, &v->y);
    io_real(io, &v->z);
}

static void io_affine(blob_io *io, rt_affine *a)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) io_real(io, &a->linear.m[i][j]);
    io_vec3(io, &a->translation);
}

/* An array of count elements: the caller's array when writing, a new one when reading.
 * min_bytes is each element's smallest encoded size, to reject lying counts early. */
static void *io_array(blob_io *io, const void *array, uint32_t count, size_t elem_size, size_t min_bytes)
{
    if (io->mode != BLOB_READ) return (void *)array;
    if (io->failed || (size_t)count > (io->capacity - io->pos) / min_bytes) {
        io->failed = true;
        return 0;
    }
    void *p = rt_arena_array(io->arena, count, elem_size);
    if (!p) io->failed = io->out_of_memory = true;
    return p;
}

static void io_channel(blob_io *io, rt_channel *c)
{
    io_vec3(io, &c->color);
    io_u32(io, &c->texture);
}

/* An enumerated setting, stored as its 32-bit value. */
#define io_choice(io, field)                   \
    do {                                       \
        uint32_t value = (uint32_t) * (field); \
        io_u32((io), &value);                  \
        *(field) = value;                      \
    } while (0)

static void io_trace(blob_io *io, rt_trace_settings *t)
{
    io_u32(io, &t->max_depth);
    io_choice(io, &t->shadows);
    io_bool(io, &t->reflections);
    io_bool(io, &t->refractions);
    io_u32(io, &t->samples_per_pixel_index);
    io_choice(io, &t->monte_carlo);
    io_bool(io, &t->diffuse_reflection);
    io_bool(io, &t->caustics);
    io_bool(io, &t->random_single_branching);
    io_real(io, &t->focus_distance);
    io_real(io, &t->aperture_size);
    io_choice(io, &t->sample_count_type);
    io_u32(io, &t->min_samples_index);
    io_u32(io, &t->max_samples_index);
    io_real(io, &t->difference_threshold);
    io_real(io, &t->std_error_threshold);
}

static void io_camera(blob_io *io, rt_camera_desc *c)
{
    io_affine(io, &c->world);
    io_real(io, &c->fov_degrees);
    io_bool(io, &c->perspective);
    io_real(io, &c->ortho_width);
    io_u32(io, &c->width);
    io_u32(io, &c->height);
    io_trace(io, &c->trace);
}

static void io_materials(blob_io *io, rt_scene_desc *d)
{
    io_u32(io, &d->material_count);
    rt_material *m = io_array(io, d->materials, d->material_count, sizeof *m, 8);
    for (uint32_t i = 0; i < d->material_count && !io->failed; i++) {
        io_channel(io, &m[i].diffuse);
        io_channel(io, &m[i].specular);
        io_channel(io, &m[i].emissive);
        io_channel(io, &m[i].transmittance);
        io_real(io, &m[i].shininess);
        io_real(io, &m[i].index_of_refraction);
    }
    d->materials = m;
}

static void io_textures(blob_io *io, rt_scene_desc *d)
{
    io_u32(io, &d->texture_count);
    rt_texture *t = io_array(io, d->textures, d->texture_count, sizeof *t, 8);
    for (uint32_t i = 0; i < d->texture_count && !io->failed; i++) {
        io_u32(io, &t[i].width);
        io_u32(io, &t[i].height);
        io_bool(io, &t[i].bilinear);
        if (io->mode == BLOB_READ && (uint64_t)t[i].width * t[i].height > (uint64_t)1 << 28) io->failed = true;
        uint32_t bytes = t[i].width * t[i].height * 3u;
        uint8_t *rgb = io_array(io, t[i].rgb, bytes, 1, 1);
        if (io->failed) return;
        io_bytes(io, rgb, bytes);
        t[i].rgb = rgb;
    }
    d->textures = t;
}

static void io_mesh(blob_io *io, rt_mesh_desc *m)
{
    io_u32(io, &m->vertex_count);
    io_u32(io, &m->triangle_count);
    bool has_normals = m->normals != 0, has_uvs = m->uvs != 0;
    io_bool(io, &has_normals);
    io_bool(io, &has_uvs);
    if (m->triangle_count > UINT32_MAX / 3) io->failed = true;
    rt_vec3 *p = io_array(io, m->positions, m->vertex_count, sizeof *p, 24);
    for (uint32_t v = 0; v < m->vertex_count && !io->failed; v++) io_vec3(io, &p[v]);
    rt_vec3 *n = has_normals ? io_array(io, m->normals, m->vertex_count, sizeof *n, 24) : 0;
    for (uint32_t v = 0; n && v < m->vertex_count && !io->failed; v++) io_vec3(io, &n[v]);
    rt_vec2 *uv = has_uvs ? io_array(io, m->uvs, m->vertex_count, sizeof *uv, 16) : 0;
    for (uint32_t v = 0; uv && v < m->vertex_count && !io->failed; v++) {
        io_real(io, &uv[v].u);
        io_real(io, &uv[v].v);
    }
    uint32_t *idx = io_array(io, m->indices, m->triangle_count * 3, sizeof *idx, 8);
    for (uint32_t k = 0; k < m->triangle_count * 3 && !io->failed; k++) io_u32(io, &idx[k]);
    m->positions = p;
    m->normals = n;
    m->uvs = uv;
    m->indices = idx;
}

static void io_meshes(blob_io *io, rt_scene_desc *d)
{
    io_u32(io, &d->mesh_count);
    rt_mesh_desc *m = io_array(io, d->meshes, d->mesh_count, sizeof *m, 32);
    for (uint32_t i = 0; i < d->mesh_count && !io->failed; i++) {
        rt_mesh_desc copy = m[i]; /* the writer's meshes are const */
        io_mesh(io, &copy);
        if (io->mode == BLOB_READ) m[i] = copy;
    }
    d->meshes = m;
}

static void io_objects(blob_io *io, rt_scene_desc *d)
{
    io_u32(io, &d->object_count);
    rt_object_desc *o = io_array(io, d->objects, d->object_count, sizeof *o, 8);
    for (uint32_t i = 0; i < d->object_count && !io->failed; i++) {
        uint32_t kind = (uint32_t)o[i].kind;
        io_u32(io, &kind);
        if (kind > RT_SHAPE_MESH) io->failed = true;
        o[i].kind = (rt_shape_kind)kind;
        io_affine(io, &o[i].world);
        io_u32(io, &o[i].material);
        io_u32(io, &o[i].mesh);
        io_u32(io, &o[i].subdivision);
        io_u32(io, &o[i].source);
    }
    d->objects = o;
}

static void io_lights(blob_io *io, rt_scene_desc *d)
{
    io_u32(io, &d->light_count);
    rt_light_desc *l = io_array(io, d->lights, d->light_count, sizeof *l, 8);
    for (uint32_t i = 0; i < d->light_count && !io->failed; i++) {
        uint32_t kind = (uint32_t)l[i].kind;
        io_u32(io, &kind);
        if (kind > RT_LIGHT_AREA) io->failed = true;
        l[i].kind = (rt_light_kind)kind;
        io_affine(io, &l[i].world);
        io_vec3(io, &l[i].color);
        io_vec3(io, &l[i].ambient);
        io_real(io, &l[i].atten_const);
        io_real(io, &l[i].atten_linear);
        io_real(io, &l[i].atten_quad);
    }
    d->lights = l;
}

static void transfer(blob_io *io, rt_scene_desc *d)
{
    uint8_t magic[8] = {'R', 'T', 'K', 'S', 'C', 'E', 'N', 'E'};
    uint8_t seen[8];
    uint32_t version = BLOB_VERSION, real_bytes = (uint32_t)sizeof(rt_real);
    uint32_t real_kind = rt_real_to_bits(RT_ONE) == 0x3ff0000000000000ull ? 1u : 2u; /* double or fixed */
    uint32_t want_version = version, want_kind = real_kind;
    for (int i = 0; i < 8; i++) seen[i] = magic[i];
    io_bytes(io, seen, 8);
    io_u32(io, &version);
    io_u32(io, &real_bytes);
    io_u32(io, &real_kind);
    for (int i = 0; i < 8; i++)
        if (seen[i] != magic[i]) io->failed = true;
    if (version != want_version || real_kind != want_kind || real_bytes != sizeof(rt_real)) io->failed = true;
    io_camera(io, &d->camera);
    io_materials(io, d);
    io_textures(io, d);
    io_meshes(io, d);
    io_objects(io, d);
    io_lights(io, d);
}

size_t rt_blob_size(const rt_scene_desc *desc)
{
    blob_io io = {BLOB_SIZE, 0, 0, 0, 0, 0, false, false};
    rt_scene_desc copy = *desc;
    transfer(&io, &copy);
    return io.pos;
}

size_t rt_blob_write(const rt_scene_desc *desc, uint8_t *out, size_t capacity)
{
    blob_io io = {BLOB_WRITE, out, 0, capacity, 0, 0, false, false};
    rt_scene_desc copy = *desc;
    transfer(&io, &copy);
    return io.failed ? 0 : io.pos;
}

rt_status rt_blob_read(const uint8_t *bytes, size_t size, rt_arena *arena, rt_scene_desc *out)
{
    blob_io io = {BLOB_READ, 0, bytes, size, 0, arena, false, false};
    rt_scene_desc d = {0};
    transfer(&io, &d);
    if (io.out_of_memory) return RT_ERR_NOMEM;
    if (io.failed || io.pos != size) return RT_ERR_INVALID;
    *out = d;
    return RT_OK;
}

/* The CSE457 YAML scene loader (docs/format.md §2-§7). Sections are read in the
 * skeleton's order -- Textures, Meshes, ShaderPrograms, Materials, Root -- whatever
 * their order in the file, and only what the tracer sees reaches the description:
 * materials whose shader is trace compatible, the geometry that uses them, and the
 * textures and meshes those need. Asset files are read last, once the whole scene
 * has been checked, each at most once. */
#include "load/scene_load.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin_mesh.h"
#include "image/image.h"
#include "load/input_file.h"
#include "load/name_index.h"
#include "load/ply.h"
#include "load/yaml_read.h"
#include "mem/mem.h"

#define UNSET UINT32_MAX /* an index not assigned yet; as a material: not traced */
#define MAX_NODE_DEPTH 1000

/* A growable array of fixed-size elements. */
typedef struct {
    void *data;
    uint32_t count, cap;
} list;

/* What rtp_loaded_scene.storage points to: the arrays behind desc. */
typedef struct {
    list materials; /* rt_material */
    list textures;  /* rt_texture */
    list images;    /* rtp_image: the pixels behind textures */
    list meshes;    /* rt_mesh_desc */
    list plys;      /* rtp_ply_mesh: the arrays behind meshes read from files */
    list objects;   /* rt_object_desc */
    list lights;    /* rt_light_desc */
} store;

/* The identity of an asset file: two entries naming one file (by any path) share a read. */
typedef struct {
    dev_t dev;
    ino_t ino;
} file_id;

/* The named entries of the file's sections, found by name through the loader's indices. */
typedef struct {
    const char *name;
    const rtp_yaml_node *key, *node; /* node is NULL for an empty (null) entry */
    uint32_t index;                  /* into desc.textures once a traced material uses it */
    bool bilinear;
    file_id file; /* once read */
} texture_decl;

typedef struct {
    const char *name;
    const rtp_yaml_node *key, *node;
    uint32_t index; /* into desc.meshes once traced geometry uses it */
    file_id file;   /* once read */
} mesh_decl;

typedef struct {
    const char *name;
    bool traced;
} shader_decl;

typedef struct {
    const char *name;
    uint32_t index; /* into desc.materials, or UNSET when not trace compatible */
} material_decl;

typedef struct {
    rtp_yaml y;
    char *root; /* the folder asset paths are relative to */
    store *st;
    list names;                                /* char *, the Name of each enabled node: rtp_loaded_scene.node_names */
    list material_names, texture_names;        /* char *, by desc index */
    list asset_paths;                          /* char *, each asset file read: rtp_loaded_scene.asset_paths */
    list textures, meshes, shaders, materials; /* the *_decl of the sections */
    rtp_name_index texture_names_ix, mesh_names_ix, shader_names_ix, material_names_ix; /* name -> decl */
    rtp_name_index texture_files, mesh_files; /* file_id -> the decl that read it */
    uint32_t cube, square;                    /* desc.meshes index of the built-ins once used */
    bool have_camera;
    rt_camera_desc camera;
} loader;

/* A new zeroed element at the end of l, or NULL (error reported) when out of memory. */
static void *push(loader *L, list *l, size_t size)
{
    if (l->count == l->cap) {
        uint32_t cap = l->cap ? l->cap * 2 : 8;
        void *data = rtp_mem_realloc(l->data, (size_t)cap * size, "the scene description");
        if (!data) {
            rtp_yaml_fail(&L->y, NULL, NULL, "%s", rtp_mem_refusal());
            return NULL;
        }
        l->data = data;
        l->cap = cap;
    }
    void *item = (char *)l->data + (size_t)l->count++ * size;
    memset(item, 0, size);
    return item;
}

/* Appends a copy of name to a list of char *. */
static bool push_name(loader *L, list *l, const char *name)
{
    char **slot = push(L, l, sizeof *slot);
    return slot && ((*slot = rtp_mem_strdup(name, "the scene's names")) ||
                    rtp_yaml_fail(&L->y, NULL, NULL, "%s", rtp_mem_refusal()));
}

/* Records that entry `index` of a section is called name. */
static bool index_name(loader *L, rtp_name_index *ix, const char *name, uint32_t index)
{
    return rtp_name_index_put(ix, name, strlen(name), index) ||
           rtp_yaml_fail(&L->y, NULL, NULL, "%s", rtp_mem_refusal());
}

/* The entry called name in a list of *_decl through its index, or NULL. */
static void *find(const list *l, const rtp_name_index *ix, size_t size, const char *name)
{
    uint32_t i = rtp_name_index_get(ix, name, strlen(name));
    return i == RTP_NAME_NONE ? NULL : (char *)l->data + (size_t)i * size;
}

/* ---- Values ---- */

/* Three numbers of the map under key, named by the letters of axes ("RGB", "XYZ"). */
static bool read_triple(rtp_yaml *y, const rtp_yaml_node *map, const char *key, const char *axes, double def,
                        double out[3])
{
    rtp_yaml_node *m;
    if (!rtp_yaml_map(y, map, key, false, &m)) return false;
    size_t mark = rtp_yaml_push(y, key);
    for (int i = 0; i < 3; i++) {
        char axis[2] = {axes[i], '\0'};
        if (!rtp_yaml_real(y, m, axis, def, &out[i])) return false;
    }
    rtp_yaml_pop(y, mark);
    return true;
}

static rt_vec3 vec3(const double v[3])
{
    return rt_v3(rt_from_double(v[0]), rt_from_double(v[1]), rt_from_double(v[2]));
}

/* The skeleton's 8-bit material colour (format.md §4.5): the float product c * 255,
 * truncated, then byte / 255. */
static rt_real quantise(double c)
{
    float f = (float)(c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c);
    float scaled = f * 255.0f;
    return rt_from_double((unsigned char)scaled / 255.0);
}

/* ---- Resource sections ---- */

typedef bool (*entry_fn)(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry);

/* Calls fn for every "name: {map}" entry of the top-level section. */
static bool for_each_entry(loader *L, const rtp_yaml_node *top, const char *section, entry_fn fn)
{
    rtp_yaml *y = &L->y;
    rtp_yaml_node *map;
    if (!rtp_yaml_map(y, top, section, false, &map)) return false;
    size_t mark = rtp_yaml_push(y, section);
    for (size_t i = 0; i < rtp_yaml_count(map); i++) {
        rtp_yaml_node *entry;
        const rtp_yaml_node *key = rtp_yaml_pair(y, map, i, &entry);
        const char *name = rtp_yaml_text(key);
        if (!name) continue; /* a non-scalar key cannot be referred to */
        size_t entry_mark = rtp_yaml_push(y, name);
        if (!rtp_yaml_want_map(y, entry, NULL) || !fn(L, key, entry)) return false;
        rtp_yaml_pop(y, entry_mark);
    }
    rtp_yaml_pop(y, mark);
    return true;
}

/* Path is type-checked here and read when a traced material uses the texture. */
static bool texture_entry(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry)
{
    const char *path;
    texture_decl *t = push(L, &L->textures, sizeof *t);
    if (!t) return false;
    *t = (texture_decl){.name = key->text, .key = key, .node = entry, .index = UNSET};
    return rtp_yaml_bool(&L->y, entry, "Bilinear", true, &t->bilinear) &&
           rtp_yaml_string(&L->y, entry, "Path", "", &path) &&
           index_name(L, &L->texture_names_ix, key->text, L->textures.count - 1);
}

static bool mesh_entry(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry)
{
    const char *path;
    mesh_decl *m = push(L, &L->meshes, sizeof *m);
    if (!m) return false;
    *m = (mesh_decl){.name = key->text, .key = key, .node = entry, .index = UNSET};
    return rtp_yaml_string(&L->y, entry, "Path", "", &path) &&
           index_name(L, &L->mesh_names_ix, key->text, L->meshes.count - 1);
}

/* Undefined shader programs are not traced, except these two built-ins (format.md §4.3). */
static bool builtin_traced(const char *shader)
{
    return !strcmp(shader, "Blinn-Phong Shader") || !strcmp(shader, "Toon Shader");
}

static bool shader_entry(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry)
{
    shader_decl *s = push(L, &L->shaders, sizeof *s);
    if (!s) return false;
    s->name = key->text;
    return rtp_yaml_bool(&L->y, entry, "Trace Compatible", builtin_traced(key->text), &s->traced) &&
           index_name(L, &L->shader_names_ix, key->text, L->shaders.count - 1);
}

/* A colour channel (format.md §4.5): a quantised solid colour, or a texture replacing it. */
static bool load_channel(loader *L, const rtp_yaml_node *uniforms, const char *key, double def, rt_channel *out)
{
    rtp_yaml *y = &L->y;
    rtp_yaml_node *channel;
    double rgb[3];
    bool use_texture;
    const char *map_name;
    if (!rtp_yaml_map(y, uniforms, key, false, &channel)) return false;
    size_t mark = rtp_yaml_push(y, key);
    if (!read_triple(y, channel, "Color", "RGB", def, rgb) ||
        !rtp_yaml_bool(y, channel, "Use Texture", false, &use_texture) ||
        !rtp_yaml_string(y, channel, "Color Map", "", &map_name))
        return false;
    out->color = rt_v3(quantise(rgb[0]), quantise(rgb[1]), quantise(rgb[2]));
    out->texture = RT_NO_TEXTURE;
    if (use_texture && *map_name) {
        texture_decl *t = find(&L->textures, &L->texture_names_ix, sizeof *t, map_name);
        if (!t)
            return rtp_yaml_fail(y, rtp_yaml_get(y, channel, "Color Map"), "Color Map",
                                 "no texture named '%s' in Textures", map_name);
        if (t->index == UNSET) {
            if (!push(L, &L->st->textures, sizeof(rt_texture)) || !push_name(L, &L->texture_names, map_name))
                return false;
            t->index = L->st->textures.count - 1; /* filled by load_assets */
        }
        out->texture = t->index;
    }
    rtp_yaml_pop(y, mark);
    return true;
}

static bool material_entry(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry)
{
    rtp_yaml *y = &L->y;
    const char *shader, *name = key->text;
    rtp_yaml_node *u;
    double shininess, ior;
    material_decl *d = push(L, &L->materials, sizeof *d);
    if (!d || !rtp_yaml_string(y, entry, "Shader", "", &shader) ||
        !index_name(L, &L->material_names_ix, name, L->materials.count - 1))
        return false;
    const shader_decl *s = find(&L->shaders, &L->shader_names_ix, sizeof *s, shader);
    *d = (material_decl){.name = name, .index = UNSET};
    if (!(s ? s->traced : builtin_traced(shader))) return true;

    rt_material *m = push(L, &L->st->materials, sizeof *m);
    if (!m || !push_name(L, &L->material_names, name) || !rtp_yaml_map(y, entry, "Uniforms", false, &u)) return false;
    d->index = L->st->materials.count - 1;
    size_t mark = rtp_yaml_push(y, "Uniforms");
    if (!load_channel(L, u, "Diffuse", 0.5, &m->diffuse) || !load_channel(L, u, "Specular", 0.5, &m->specular) ||
        !load_channel(L, u, "Emissive", 0.0, &m->emissive) ||
        !load_channel(L, u, "Transmittence", 0.0, &m->transmittance) ||
        !rtp_yaml_real(y, u, "Shininess", 20.0, &shininess) || !rtp_yaml_real(y, u, "IndexOfRefraction", 1.0, &ior))
        return false;
    if (!(ior > 0.0))
        return rtp_yaml_expected(y, rtp_yaml_get(y, u, "IndexOfRefraction"), "IndexOfRefraction", "a number above 0");
    rtp_yaml_pop(y, mark);
    m->shininess = rt_from_double(shininess);
    m->index_of_refraction = rt_from_double(ior);
    return true;
}

/* ---- Components ---- */

/* Camera settings (format.md §5.3); a NULL map gives the skeleton's defaults. */
static bool read_camera(rtp_yaml *y, const rtp_yaml_node *c, const rt_affine *world, rt_camera_desc *cam)
{
    rt_trace_settings *s = &cam->trace;
    rtp_yaml_node *t;
    double fov, ortho, focus, aperture, difference, std_error;
    uint32_t shadows, monte_carlo, count_type;
    memset(cam, 0, sizeof *cam);
    cam->world = *world;
    if (!rtp_yaml_real(y, c, "FOV", 50.0, &fov) ||
        !rtp_yaml_bool(y, c, "Perspective Camera?", true, &cam->perspective) ||
        !rtp_yaml_real(y, c, "Orthographic View Width", 5.0, &ortho) ||
        !rtp_yaml_uint(y, c, "Render Width (px)", 1280, 1, RT_MAX_IMAGE_SIDE, &cam->width) ||
        !rtp_yaml_uint(y, c, "Render Height (px)", 720, 1, RT_MAX_IMAGE_SIDE, &cam->height) ||
        !rtp_yaml_map(y, c, "Trace", false, &t))
        return false;
    size_t mark = rtp_yaml_push(y, "Trace");
    if (!rtp_yaml_uint(y, t, "Maximum Recursion Depth", 5, 0, RT_MAX_RECURSION_DEPTH, &s->max_depth) ||
        !rtp_yaml_index(y, t, "Shadows", RT_SHADOWS_NONE, RT_SHADOWS_LAST, &shadows) ||
        !rtp_yaml_bool(y, t, "Reflections", true, &s->reflections) ||
        !rtp_yaml_bool(y, t, "Refractions", true, &s->refractions) ||
        !rtp_yaml_index(y, t, "Samples Per Pixel", 0, RT_MAX_SPP_INDEX, &s->samples_per_pixel_index) ||
        !rtp_yaml_index(y, t, "Monte Carlo", RT_MONTE_CARLO_OFF, RT_MONTE_CARLO_LAST, &monte_carlo) ||
        !rtp_yaml_bool(y, t, "Diffuse Reflection", true, &s->diffuse_reflection) ||
        !rtp_yaml_bool(y, t, "Caustics", true, &s->caustics) ||
        !rtp_yaml_bool(y, t, "Random Single Branching", true, &s->random_single_branching) ||
        !rtp_yaml_real(y, t, "Focus Distance", 1.0, &focus) || !rtp_yaml_real(y, t, "Aperture Size", 0.0, &aperture) ||
        !rtp_yaml_index(y, t, "Sample Count Type", RT_SAMPLES_CONSTANT, RT_SAMPLES_LAST, &count_type) ||
        !rtp_yaml_index(y, t, "Minimum Samples", 0, RT_MAX_MIN_SAMPLES_INDEX, &s->min_samples_index) ||
        !rtp_yaml_index(y, t, "Maximum Samples", 2, RT_MAX_MAX_SAMPLES_INDEX, &s->max_samples_index) ||
        !rtp_yaml_real(y, t, "Difference Threshold", 0.02, &difference) ||
        !rtp_yaml_real(y, t, "Std. Error Threshold", 0.02, &std_error))
        return false;
    s->shadows = (rt_shadow_mode)shadows;
    s->monte_carlo = (rt_monte_carlo_mode)monte_carlo;
    s->sample_count_type = (rt_sample_count_type)count_type;
    rtp_yaml_pop(y, mark);
    if (!(fov > 0.0 && fov < 180.0))
        return rtp_yaml_expected(y, rtp_yaml_get(y, c, "FOV"), "FOV", "degrees between 0 and 180 (both excluded)");
    cam->fov_degrees = rt_from_double(fov);
    cam->ortho_width = rt_from_double(ortho);
    s->focus_distance = rt_from_double(focus);
    s->aperture_size = rt_from_double(aperture);
    s->difference_threshold = rt_from_double(difference);
    s->std_error_threshold = rt_from_double(std_error);
    return true;
}

/* Every camera is checked; the first enabled one in depth-first order is used. */
static bool load_camera(loader *L, const rtp_yaml_node *c, const rt_affine *world)
{
    rt_camera_desc cam;
    if (!read_camera(&L->y, c, world, &cam)) return false;
    if (!L->have_camera) L->camera = cam;
    L->have_camera = true;
    return true;
}

/* Lights (format.md §5.4). Their colours are used as written, not quantised. */
static bool load_light(loader *L, const rtp_yaml_node *c, rt_light_kind kind, const rt_affine *world)
{
    rtp_yaml *y = &L->y;
    double color[3], ambient[3], multiplier = 1.0, atten[3] = {0.0, 0.0, 0.0};
    if (!read_triple(y, c, "Color", "RGB", 1.0, color) || !read_triple(y, c, "Ambient", "RGB", 0.0, ambient))
        return false;
    bool ok = kind == RT_LIGHT_DIRECTIONAL ? rtp_yaml_real(y, c, "Intensity Multiplier", 1.0, &multiplier)
                                           : rtp_yaml_real(y, c, "Const Atten", 0.0, &atten[0]) &&
                                                 rtp_yaml_real(y, c, "Linear Atten", 0.0, &atten[1]) &&
                                                 rtp_yaml_real(y, c, "Quad Atten", 0.2, &atten[2]);
    if (!ok) return false;
    for (int i = 0; i < 3; i++) {
        color[i] *= multiplier;
        if (!isfinite(color[i]))
            return rtp_yaml_fail(y, rtp_yaml_get(y, c, "Intensity Multiplier"), "Intensity Multiplier",
                                 "Color times Intensity Multiplier overflows");
    }
    /* Refused here too, to name the place in the file. */
    if (kind == RT_LIGHT_DIRECTIONAL && rt_v3_is_zero(rt_scene_light_direction(world)))
        return rtp_yaml_fail(y, c, NULL, "the node's Transform scales its Y axis to 0: the light has no direction");
    rt_light_desc *l = push(L, &L->st->lights, sizeof *l);
    if (!l) return false;
    l->kind = kind;
    l->world = *world;
    l->color = vec3(color);
    l->ambient = vec3(ambient);
    l->atten_const = rt_from_double(atten[0]);
    l->atten_linear = rt_from_double(atten[1]);
    l->atten_quad = rt_from_double(atten[2]);
    return true;
}

/* The desc index of the component's material, or UNSET when the tracer does not see
 * it: not trace compatible, or not defined (the skeleton's fallback is not traced). */
static bool component_material(loader *L, const rtp_yaml_node *c, uint32_t *material)
{
    const char *name;
    if (!rtp_yaml_string(&L->y, c, "Material", "", &name)) return false;
    const material_decl *m = find(&L->materials, &L->material_names_ix, sizeof *m, name);
    *material = m ? m->index : UNSET;
    return true;
}

static rt_object_desc *add_object(loader *L, rt_shape_kind kind, const rt_affine *world, uint32_t material,
                                  uint32_t source)
{
    rt_object_desc *o = push(L, &L->st->objects, sizeof *o);
    if (o) *o = (rt_object_desc){.kind = kind, .world = *world, .material = material, .source = source};
    return o;
}

/* Adds a built-in mesh to desc.meshes on first use; *out is its index. */
static bool builtin_mesh(loader *L, rt_mesh_desc mesh, uint32_t *index, uint32_t *out)
{
    if (*index == UNSET) {
        rt_mesh_desc *m = push(L, &L->st->meshes, sizeof *m);
        if (!m) return false;
        *m = mesh;
        *index = L->st->meshes.count - 1;
    }
    *out = *index;
    return true;
}

static bool load_quadric(loader *L, const rtp_yaml_node *c, rt_shape_kind kind, const rt_affine *world, uint32_t source)
{
    uint32_t material;
    if (!component_material(L, c, &material)) return false;
    return material == UNSET || add_object(L, kind, world, material, source);
}

/* A Plane is the built-in unit square, traced as a mesh (format.md §5.7). */
static bool load_plane(loader *L, const rtp_yaml_node *c, const rt_affine *world, uint32_t source)
{
    uint32_t material;
    rt_object_desc *o;
    if (!component_material(L, c, &material)) return false;
    if (material == UNSET) return true;
    return (o = add_object(L, RT_SHAPE_MESH, world, material, source)) &&
           builtin_mesh(L, rt_builtin_mesh_square(), &L->square, &o->mesh);
}

static bool load_triangle_mesh(loader *L, const rtp_yaml_node *c, const rt_affine *world, uint32_t source)
{
    rtp_yaml *y = &L->y;
    uint32_t material, subdivision;
    const char *name;
    rt_object_desc *o;
    if (!rtp_yaml_uint(y, c, "LoopSubdivision", 0, 0, RT_MAX_SUBDIVISION, &subdivision) ||
        !component_material(L, c, &material))
        return false;
    if (material == UNSET) return true;
    if (!rtp_yaml_string(y, c, "Mesh", NULL, &name) || !(o = add_object(L, RT_SHAPE_MESH, world, material, source)))
        return false;
    o->subdivision = subdivision;
    mesh_decl *m = find(&L->meshes, &L->mesh_names_ix, sizeof *m, name);
    if (m) {
        if (m->index == UNSET) {
            if (!push(L, &L->st->meshes, sizeof(rt_mesh_desc))) return false;
            m->index = L->st->meshes.count - 1; /* filled by load_assets */
        }
        o->mesh = m->index;
        return true;
    }
    if (!strcmp(name, "Cube")) return builtin_mesh(L, rt_builtin_mesh_cube(), &L->cube, &o->mesh);
    return rtp_yaml_fail(y, rtp_yaml_get(y, c, "Mesh"), "Mesh", "no mesh named '%s' in Meshes, and it is not 'Cube'",
                         name);
}

static bool load_component(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *c, const rt_affine *world,
                           uint32_t source)
{
    rtp_yaml *y = &L->y;
    const char *kind = rtp_yaml_text(key);
    if (!kind) return true; /* not a component name */
    if (!rtp_yaml_want_map(y, c, kind)) return false;
    size_t mark = rtp_yaml_push(y, kind);
    bool ok = true; /* Transform is read by load_node; EnvironmentMap and the rest are ignored */
    if (!strcmp(kind, "Camera"))
        ok = load_camera(L, c, world);
    else if (!strcmp(kind, "PointLight"))
        ok = load_light(L, c, RT_LIGHT_POINT, world);
    else if (!strcmp(kind, "DirectionalLight"))
        ok = load_light(L, c, RT_LIGHT_DIRECTIONAL, world);
    else if (!strcmp(kind, "AreaLight"))
        ok = load_light(L, c, RT_LIGHT_AREA, world);
    else if (!strcmp(kind, "Sphere"))
        ok = load_quadric(L, c, RT_SHAPE_SPHERE, world, source);
    else if (!strcmp(kind, "Cylinder"))
        ok = load_quadric(L, c, RT_SHAPE_CYLINDER, world, source);
    else if (!strcmp(kind, "Plane"))
        ok = load_plane(L, c, world, source);
    else if (!strcmp(kind, "TriangleMesh"))
        ok = load_triangle_mesh(L, c, world, source);
    else if (!strcmp(kind, "Cone") || !strcmp(kind, "Ring") || !strcmp(kind, "SurfaceOfRevolution"))
        ok = rtp_yaml_fail(y, key, NULL, "component not supported");
    if (ok) rtp_yaml_pop(y, mark);
    return ok;
}

/* ---- Node tree ---- */

/* parent * T * R * S of the node's Transform component (format.md §5.2). */
static bool node_transform(rtp_yaml *y, const rtp_yaml_node *components, const rt_affine *parent, rt_affine *world)
{
    rtp_yaml_node *t;
    double translation[3], rotation[3], scale[3];
    if (!rtp_yaml_map(y, components, "Transform", false, &t)) return false;
    size_t mark = rtp_yaml_push(y, "Transform");
    if (!read_triple(y, t, "Translation", "XYZ", 0.0, translation) ||
        !read_triple(y, t, "Rotation", "XYZ", 0.0, rotation) || !read_triple(y, t, "Scale", "XYZ", 1.0, scale))
        return false;
    rtp_yaml_pop(y, mark);
    rt_affine local = rt_affine_trs(vec3(translation), vec3(rotation), vec3(scale));
    *world = rt_affine_mul(parent, &local);
    if (!rt_affine_is_finite(world))
        return rtp_yaml_fail(y, t, "Transform", "the node's world transform overflows (a huge Scale or Translation?)");
    return true;
}

/* Adds node and its subtree unless it is disabled (format.md §5). */
static bool load_node(loader *L, const rtp_yaml_node *node, const rt_affine *parent, unsigned depth)
{
    rtp_yaml *y = &L->y;
    const char *name;
    bool enabled;
    rtp_yaml_node *components, *children;
    rt_affine world;
    if (depth > MAX_NODE_DEPTH) return rtp_yaml_fail(y, node, NULL, "nodes nested more than %d deep", MAX_NODE_DEPTH);
    if (!rtp_yaml_want_map(y, node, NULL) || !rtp_yaml_string(y, node, "Name", NULL, &name) ||
        !rtp_yaml_bool(y, node, "Enabled", true, &enabled))
        return false;
    if (!enabled) return true;

    if (!push_name(L, &L->names, name)) return false;
    uint32_t source = L->names.count - 1;
    if (!rtp_yaml_map(y, node, "Components", false, &components) ||
        !rtp_yaml_seq(y, node, "Children", false, &children))
        return false;
    size_t mark = rtp_yaml_push(y, "Components");
    if (!node_transform(y, components, parent, &world)) return false;
    for (size_t i = 0; i < rtp_yaml_count(components); i++) {
        rtp_yaml_node *c;
        const rtp_yaml_node *key = rtp_yaml_pair(y, components, i, &c);
        if (!load_component(L, key, c, &world, source)) return false;
    }
    rtp_yaml_pop(y, mark);
    for (size_t i = 0; i < rtp_yaml_count(children); i++) {
        char segment[48];
        snprintf(segment, sizeof segment, "Children[%zu]", i);
        mark = rtp_yaml_push(y, segment);
        if (!load_node(L, rtp_yaml_item(y, children, i), &world, depth + 1)) return false;
        rtp_yaml_pop(y, mark);
    }
    return true;
}

static bool load_sections(loader *L)
{
    rtp_yaml *y = &L->y;
    const rtp_yaml_node *top = rtp_yaml_root(y);
    rtp_yaml_node *root;
    rt_affine identity = rt_affine_identity();
    if (top->kind != RTP_YAML_MAP) return rtp_yaml_expected(y, top, NULL, "a scene (a YAML map)");
    /* Cubemaps are never sampled by the tracer (format.md §2.4). */
    if (!for_each_entry(L, top, "Textures", texture_entry) || !for_each_entry(L, top, "Meshes", mesh_entry) ||
        !for_each_entry(L, top, "ShaderPrograms", shader_entry) ||
        !for_each_entry(L, top, "Materials", material_entry) || !rtp_yaml_map(y, top, "Root", true, &root))
        return false;
    size_t mark = rtp_yaml_push(y, "Root");
    if (!load_node(L, root, &identity, 0)) return false;
    rtp_yaml_pop(y, mark);
    if (!L->have_camera) { /* the skeleton's default camera (format.md §5.3) */
        rt_affine at = identity;
        at.translation = rt_v3(RT_ZERO, RT_ZERO, rt_from_double(2.5));
        return read_camera(y, NULL, &at, &L->camera);
    }
    return true;
}

/* ---- Asset files ---- */

/* The folder asset paths are relative to (format.md §3): the parent of the nearest
 * ancestor of the scene's folder named "assets", else the scene's folder; for a scene
 * read from standard input, the working folder. */
static bool find_root(loader *L, const char *scene_path, const char *assets_root)
{
    if (assets_root || !strcmp(scene_path, "-")) {
        L->root = strdup(assets_root ? assets_root : ".");
        return L->root || rtp_yaml_fail(&L->y, NULL, NULL, "out of memory");
    }
    char *dir = realpath(scene_path, NULL);
    if (!dir) return rtp_yaml_fail(&L->y, NULL, NULL, "cannot resolve the scene's folder: %s", strerror(errno));
    L->root = dir;
    char *end = strrchr(dir, '/'); /* realpath is absolute: there is a slash */
    end[end == dir] = '\0';        /* keeps "/" for a scene in the file system root */
    while (end > dir) {
        char *start = end;
        while (start[-1] != '/') start--;
        if (end - start == 6 && !memcmp(start, "assets", 6)) {
            start[start - 1 == dir ? 0 : -1] = '\0';
            return true;
        }
        end = start - 1;
    }
    return true;
}

/* Opens the file Path of a Textures or Meshes entry names (relative to the assets
 * root), so that a missing or unusable file is reported against the key that named it. */
static bool open_asset(loader *L, const rtp_yaml_node *key, const rtp_yaml_node *entry, rtp_input *in)
{
    rtp_yaml *y = &L->y;
    const char *path;
    char *resolved, why[RTP_ERR_SIZE];
    /* An empty (null) entry has no place of its own: its key is the place. */
    if (!entry) return rtp_yaml_fail(y, key, "Path", "missing, expected a string");
    if (!rtp_yaml_string(y, entry, "Path", NULL, &path)) return false;
    const char *sep = *L->root && L->root[strlen(L->root) - 1] == '/' ? "" : "/";
    size_t size = strlen(L->root) + strlen(path) + 2;
    if (!(resolved = rtp_mem_alloc(size, "the scene description")))
        return rtp_yaml_fail(y, NULL, NULL, "%s", rtp_mem_refusal());
    if (path[0] == '/')
        snprintf(resolved, size, "%s", path);
    else
        snprintf(resolved, size, "%s%s%s", L->root, sep, path);
    bool ok = rtp_input_open(in, resolved, false, why, sizeof why) ||
              rtp_yaml_fail(y, rtp_yaml_get(y, entry, "Path"), "Path", "cannot read '%s': %s", resolved, why);
    if (!ok) rtp_mem_free(resolved);
    return ok;
}

/* The earlier entry of decls (by index) that read the file in opened, recorded
 * otherwise; RTP_NAME_NONE when this entry is the first to read it. */
static bool first_reader(loader *L, rtp_name_index *files, file_id *id, const rtp_input *in, uint32_t self,
                         uint32_t *first)
{
    *id = (file_id){in->dev, in->ino};
    *first = rtp_name_index_get(files, id, sizeof *id);
    return *first != RTP_NAME_NONE || rtp_name_index_put(files, id, sizeof *id, self) ||
           rtp_yaml_fail(&L->y, NULL, NULL, "%s", rtp_mem_refusal());
}

/* Textures entries naming one file share one read and one image. */
static bool load_texture(loader *L, texture_decl *t)
{
    rt_texture *textures = L->st->textures.data;
    char why[RTP_ERR_SIZE];
    rtp_input in;
    rtp_image img;
    uint32_t first;
    if (!open_asset(L, t->key, t->node, &in)) return false;
    const char *path = in.path;
    bool ok =
        first_reader(L, &L->texture_files, &t->file, &in, (uint32_t)(t - (texture_decl *)L->textures.data), &first);
    if (ok && first != RTP_NAME_NONE) {
        rtp_input_close(&in);
        textures[t->index] = textures[((texture_decl *)L->textures.data)[first].index];
        textures[t->index].bilinear = t->bilinear;
        rtp_mem_free((char *)path);
        return true;
    }
    if (ok && !rtp_image_read_input(&in, &img, why, sizeof why))
        ok = rtp_yaml_fail(&L->y, rtp_yaml_get(&L->y, t->node, "Path"), "Path", "%s", why);
    if (ok && !push_name(L, &L->asset_paths, path)) {
        rtp_image_free(&img);
        ok = false;
    }
    rtp_input_close(&in);
    rtp_mem_free((char *)path);
    if (!ok) return false;
    rtp_image *owned = push(L, &L->st->images, sizeof *owned);
    if (!owned) {
        rtp_image_free(&img);
        return false;
    }
    *owned = img;
    textures[t->index] =
        (rt_texture){.width = img.width, .height = img.height, .rgb = img.rgb, .bilinear = t->bilinear};
    return true;
}

/* Meshes entries naming one file share one read. */
static bool load_mesh(loader *L, mesh_decl *m)
{
    rt_mesh_desc *meshes = L->st->meshes.data;
    char why[RTP_ERR_SIZE];
    rtp_input in;
    rtp_ply_mesh ply;
    uint32_t first;
    if (!open_asset(L, m->key, m->node, &in)) return false;
    const char *path = in.path;
    bool ok = first_reader(L, &L->mesh_files, &m->file, &in, (uint32_t)(m - (mesh_decl *)L->meshes.data), &first);
    if (ok && first != RTP_NAME_NONE) {
        rtp_input_close(&in);
        meshes[m->index] = meshes[((mesh_decl *)L->meshes.data)[first].index];
        rtp_mem_free((char *)path);
        return true;
    }
    if (ok && !rtp_ply_read_input(&in, &ply, why, sizeof why))
        ok = rtp_yaml_fail(&L->y, rtp_yaml_get(&L->y, m->node, "Path"), "Path", "%s", why);
    else if (ok && !push_name(L, &L->asset_paths, path)) {
        rtp_ply_free(&ply);
        ok = false;
    }
    rtp_input_close(&in);
    rtp_mem_free((char *)path);
    if (!ok) return false;
    rtp_ply_mesh *owned = push(L, &L->st->plys, sizeof *owned);
    if (!owned) {
        rtp_ply_free(&ply);
        return false;
    }
    *owned = ply;
    meshes[m->index] = rtp_ply_view(owned);
    return true;
}

/* Reads the textures and meshes that traced materials and geometry use. */
static bool load_assets(loader *L)
{
    rtp_yaml *y = &L->y;
    texture_decl *textures = L->textures.data;
    mesh_decl *meshes = L->meshes.data;
    for (uint32_t i = 0; i < L->textures.count; i++) {
        if (textures[i].index == UNSET) continue;
        rtp_yaml_pop(y, 0);
        rtp_yaml_push(y, "Textures");
        rtp_yaml_push(y, textures[i].name);
        if (!load_texture(L, &textures[i])) return false;
    }
    for (uint32_t i = 0; i < L->meshes.count; i++) {
        if (meshes[i].index == UNSET) continue;
        rtp_yaml_pop(y, 0);
        rtp_yaml_push(y, "Meshes");
        rtp_yaml_push(y, meshes[i].name);
        if (!load_mesh(L, &meshes[i])) return false;
    }
    return true;
}

/* ---- Entry points ---- */

static void free_names(char **names, uint32_t count)
{
    for (uint32_t i = 0; names && i < count; i++) rtp_mem_free(names[i]);
    rtp_mem_free(names);
}

static void hand_over(loader *L, rtp_loaded_scene *out)
{
    store *st = L->st;
    rt_scene_desc *d = &out->desc;
    out->storage = st;
    out->node_names = L->names.data;
    out->node_count = L->names.count;
    out->material_names = L->material_names.data;
    out->texture_names = L->texture_names.data;
    out->asset_paths = L->asset_paths.data;
    out->asset_count = L->asset_paths.count;
    d->materials = st->materials.data;
    d->material_count = st->materials.count;
    d->textures = st->textures.data;
    d->texture_count = st->textures.count;
    d->meshes = st->meshes.data;
    d->mesh_count = st->meshes.count;
    d->objects = st->objects.data;
    d->object_count = st->objects.count;
    d->lights = st->lights.data;
    d->light_count = st->lights.count;
    d->camera = L->camera;
}

bool rtp_scene_load(const char *path, const char *assets_root, rtp_loaded_scene *out, char *err, size_t err_size)
{
    loader L;
    memset(&L, 0, sizeof L);
    memset(out, 0, sizeof *out);
    L.cube = L.square = UNSET;
    if (!rtp_yaml_open(&L.y, path, err, err_size)) return false;
    L.st = calloc(1, sizeof *L.st);
    bool ok = (L.st || rtp_yaml_fail(&L.y, NULL, NULL, "out of memory")) && find_root(&L, path, assets_root) &&
              load_sections(&L) && load_assets(&L);
    if (ok) {
        hand_over(&L, out);
    } else {
        rtp_loaded_scene partial = {.storage = L.st, .node_names = L.names.data, .node_count = L.names.count};
        free_names(L.material_names.data, L.material_names.count);
        free_names(L.texture_names.data, L.texture_names.count);
        free_names(L.asset_paths.data, L.asset_paths.count);
        rtp_scene_unload(&partial);
    }
    rtp_name_index *indices[] = {&L.texture_names_ix,  &L.mesh_names_ix, &L.shader_names_ix,
                                 &L.material_names_ix, &L.texture_files, &L.mesh_files};
    for (size_t i = 0; i < sizeof indices / sizeof indices[0]; i++) rtp_name_index_free(indices[i]);
    rtp_mem_free(L.textures.data);
    rtp_mem_free(L.meshes.data);
    rtp_mem_free(L.shaders.data);
    rtp_mem_free(L.materials.data);
    free(L.root);
    rtp_yaml_close(&L.y);
    return ok;
}

void rtp_scene_unload(rtp_loaded_scene *scene)
{
    free_names(scene->material_names, scene->desc.material_count);
    free_names(scene->texture_names, scene->desc.texture_count);
    store *st = scene->storage;
    if (st) {
        for (uint32_t i = 0; i < st->images.count; i++) rtp_image_free(&((rtp_image *)st->images.data)[i]);
        for (uint32_t i = 0; i < st->plys.count; i++) rtp_ply_free(&((rtp_ply_mesh *)st->plys.data)[i]);
        list *lists[] = {&st->materials, &st->textures, &st->images, &st->meshes, &st->plys, &st->objects, &st->lights};
        for (size_t i = 0; i < sizeof lists / sizeof lists[0]; i++) rtp_mem_free(lists[i]->data);
        free(st);
    }
    free_names(scene->node_names, scene->node_count);
    free_names(scene->asset_paths, scene->asset_count);
    memset(scene, 0, sizeof *scene);
}

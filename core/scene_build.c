/* rt_scene_build: turns a loader's description into the world-space scene the
 * renderer reads. Everything is validated here, at the kernel's boundary. */
#include "bvh.h"
#include "camera.h"
#include "mesh.h"

static rt_status fail(rt_build_error *err, rt_status status, const char *what, uint32_t object)
{
    err->status = status;
    err->what = what;
    err->object = object;
    return status;
}

/* Within RT_TRIANGLE_RANGE of the origin (real_double.h, real_fixed.h say why). */
static bool within_triangle_range(rt_vec3 v)
{
    return rt_abs(v.x) <= RT_TRIANGLE_RANGE && rt_abs(v.y) <= RT_TRIANGLE_RANGE && rt_abs(v.z) <= RT_TRIANGLE_RANGE;
}

rt_vec3 rt_scene_light_direction(const rt_affine *world)
{
    /* A directional light shines from its node's local +Y axis. */
    return rt_v3_normalize(rt_affine_vector(world, rt_v3(RT_ZERO, RT_ONE, RT_ZERO)));
}

static rt_status copy_materials(const rt_scene_desc *d, rt_arena *arena, rt_scene *s, rt_build_error *err)
{
    s->material_count = d->material_count;
    s->materials = RT_NEW_ARRAY(arena, rt_material, d->material_count);
    s->texture_count = d->texture_count;
    s->textures = RT_NEW_ARRAY(arena, rt_texture, d->texture_count);
    if (!s->materials || !s->textures) return fail(err, RT_ERR_NOMEM, "out of memory for materials", UINT32_MAX);
    for (uint32_t i = 0; i < d->texture_count; i++) {
        const rt_texture *t = &d->textures[i];
        if (t->width == 0 || t->height == 0 || !t->rgb || t->width > 65536 || t->height > 65536)
            return fail(err, RT_ERR_INVALID, "a texture has no pixels or is too large", UINT32_MAX);
        size_t bytes = (size_t)t->width * t->height * 3;
        uint8_t *rgb = rt_arena_alloc(arena, bytes);
        if (!rgb) return fail(err, RT_ERR_NOMEM, "out of memory for textures", UINT32_MAX);
        for (size_t k = 0; k < bytes; k++) rgb[k] = t->rgb[k];
        s->textures[i] = *t;
        s->textures[i].rgb = rgb;
    }
    for (uint32_t i = 0; i < d->material_count; i++) {
        const rt_material *m = &d->materials[i];
        const rt_channel *ch[4] = {&m->diffuse, &m->specular, &m->emissive, &m->transmittance};
        for (int c = 0; c < 4; c++) {
            if (ch[c]->texture != RT_NO_TEXTURE && ch[c]->texture >= d->texture_count)
                return fail(err, RT_ERR_INVALID, "a material names a texture that does not exist", UINT32_MAX);
            if (!rt_v3_is_finite(ch[c]->color))
                return fail(err, RT_ERR_INVALID, "a material colour is not finite", UINT32_MAX);
        }
        if (!rt_is_finite(m->shininess) || !rt_is_finite(m->index_of_refraction) || m->index_of_refraction <= RT_ZERO)
            return fail(err, RT_ERR_INVALID, "a shininess or index of refraction is not usable", UINT32_MAX);
        s->materials[i] = *m;
    }
    return RT_OK;
}

/* The object-space mesh of a mesh object: subdivided and given normals as needed. */
static rt_status prepare_mesh(const rt_scene_desc *d, const rt_object_desc *o, uint32_t index, rt_arena *arena,
                              rt_mesh_desc *out, rt_build_error *err)
{
    if (o->mesh >= d->mesh_count) return fail(err, RT_ERR_INVALID, "object names a mesh that does not exist", index);
    if (o->subdivision > RT_MAX_SUBDIVISION) return fail(err, RT_ERR_INVALID, "Loop subdivision level above 5", index);
    *out = d->meshes[o->mesh];
    for (uint32_t t = 0; t < out->triangle_count * 3; t++)
        if (out->indices[t] >= out->vertex_count) return fail(err, RT_ERR_INVALID, "mesh index out of range", index);
    for (uint32_t v = 0; v < out->vertex_count; v++) {
        if (!rt_v3_is_finite(out->positions[v])) return fail(err, RT_ERR_INVALID, "mesh vertex is not finite", index);
        /* Normals are built from products of these: the same range as in world space. */
        if (!within_triangle_range(out->positions[v]))
            return fail(err, RT_ERR_INVALID,
                        "a mesh vertex lies farther than " RT_TRIANGLE_RANGE_TEXT
                        " from the mesh's origin, beyond the range triangles are traced in",
                        index);
    }
    rt_status st = RT_OK;
    if (o->subdivision > 0) st = rt_mesh_subdivide(&d->meshes[o->mesh], o->subdivision, arena, out);
    if (st == RT_OK && !out->normals) {
        rt_vec3 *normals;
        st = rt_mesh_smooth_normals(out, arena, &normals);
        out->normals = normals;
    }
    if (st == RT_ERR_NOMEM) return fail(err, st, "out of memory for mesh processing", index);
    if (st != RT_OK) return fail(err, st, "mesh processing failed", index);
    return RT_OK;
}

static rt_status build_objects(const rt_scene_desc *d, rt_arena *arena, rt_scene *s, rt_build_error *err)
{
    s->object_count = d->object_count;
    s->objects = RT_NEW_ARRAY(arena, rt_object, d->object_count);
    rt_mesh_desc *meshes = RT_NEW_ARRAY(arena, rt_mesh_desc, d->object_count);
    if (!s->objects || !meshes) return fail(err, RT_ERR_NOMEM, "out of memory for objects", UINT32_MAX);
    size_t object_space = rt_arena_mark(arena); /* the meshes prepared below, until copied */
    uint64_t vertices = 0, triangles = 0;
    uint32_t quadrics = 0, with_uvs = 0;
    for (uint32_t i = 0; i < d->object_count; i++) {
        const rt_object_desc *o = &d->objects[i];
        rt_object *obj = &s->objects[i];
        if (o->material >= d->material_count)
            return fail(err, RT_ERR_INVALID, "object names a material that does not exist", i);
        if (!rt_affine_is_finite(&o->world)) return fail(err, RT_ERR_INVALID, "transform is not finite", i);
        obj->kind = o->kind;
        obj->material = o->material;
        obj->source = o->source;
        obj->to_world = o->world;
        rt_affine inv;
        if (!rt_affine_inverse(&o->world, &inv))
            return fail(err, RT_ERR_INVALID,
                        "transform cannot be inverted (a scale of 0, or numbers too large or too small?)", i);
        obj->to_object = inv;
        obj->normal_to_world = rt_mat3_transpose(&inv.linear);
        obj->to_object_diagonal = rt_mat3_is_diagonal(&inv.linear);
        if (o->kind != RT_SHAPE_MESH) {
            quadrics++;
            continue;
        }
        rt_status st = prepare_mesh(d, o, i, arena, &meshes[i], err);
        if (st != RT_OK) return st;
        vertices += meshes[i].vertex_count;
        triangles += meshes[i].triangle_count;
        if (meshes[i].uvs) with_uvs++;
    }
    if (vertices > UINT32_MAX / 2 || triangles + quadrics > UINT32_MAX / 2)
        return fail(err, RT_ERR_INVALID, "scene has too many triangles", UINT32_MAX);
    s->vertex_count = (uint32_t)vertices;
    s->triangle_count = (uint32_t)triangles;
    /* Every vertex and triangle is written below: no zeroing. */
    s->positions = rt_arena_alloc_array(arena, s->vertex_count, sizeof *s->positions);
    s->normals = rt_arena_alloc_array(arena, s->vertex_count, sizeof *s->normals);
    /* A mesh without uvs reads uv (0, 0); when none has them the array is not kept. */
    s->uvs = with_uvs ? RT_NEW_ARRAY(arena, rt_vec2, s->vertex_count) : NULL;
    s->triangles = rt_arena_alloc_array(arena, s->triangle_count, sizeof *s->triangles);
    s->quadric_objects = RT_NEW_ARRAY(arena, uint32_t, quadrics);
    s->mesh_object_count = d->object_count - quadrics;
    s->mesh_objects = RT_NEW_ARRAY(arena, uint32_t, s->mesh_object_count);
    if (!s->positions || !s->normals || (with_uvs && !s->uvs) || !s->triangles || !s->quadric_objects ||
        !s->mesh_objects)
        return fail(err, RT_ERR_NOMEM, "out of memory for meshes", UINT32_MAX);
    uint32_t v0 = 0, t0 = 0, q = 0, mo = 0;
    for (uint32_t i = 0; i < d->object_count; i++) {
        rt_object *obj = &s->objects[i];
        obj->first_triangle = t0;
        obj->triangle_count = 0;
        if (obj->kind != RT_SHAPE_MESH) {
            s->quadric_objects[q++] = i;
            continue;
        }
        s->mesh_objects[mo++] = i;
        const rt_mesh_desc *m = &meshes[i];
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            s->positions[v0 + v] = rt_affine_point(&obj->to_world, m->positions[v]);
            if (m->triangle_count && !within_triangle_range(s->positions[v0 + v]))
                return fail(err, RT_ERR_INVALID,
                            "a mesh vertex lies farther than " RT_TRIANGLE_RANGE_TEXT
                            " from the origin, beyond the range triangles are traced in",
                            i);
            s->normals[v0 + v] = rt_mat3_apply(&obj->normal_to_world, m->normals[v]);
            if (m->uvs) s->uvs[v0 + v] = m->uvs[v];
        }
        for (uint32_t t = 0; t < m->triangle_count; t++)
            for (int k = 0; k < 3; k++) s->triangles[t0 + t].v[k] = v0 + m->indices[3 * t + k];
        obj->triangle_count = m->triangle_count;
        v0 += m->vertex_count;
        t0 += m->triangle_count;
    }
    s->prim_count = s->triangle_count + quadrics;
    /* The object-space meshes are done with: the scene's arrays move down over them, so
     * the BVH's scratch reuses that memory instead of adding to the peak. */
    rt_arena_reset(arena, object_space);
    s->positions = rt_arena_keep(arena, s->positions, s->vertex_count * sizeof *s->positions);
    s->normals = rt_arena_keep(arena, s->normals, s->vertex_count * sizeof *s->normals);
    if (s->uvs) s->uvs = rt_arena_keep(arena, s->uvs, s->vertex_count * sizeof *s->uvs);
    s->triangles = rt_arena_keep(arena, s->triangles, s->triangle_count * sizeof *s->triangles);
    s->quadric_objects = rt_arena_keep(arena, s->quadric_objects, quadrics * sizeof *s->quadric_objects);
    s->mesh_objects = rt_arena_keep(arena, s->mesh_objects, s->mesh_object_count * sizeof *s->mesh_objects);
    return RT_OK;
}

static rt_status build_lights(const rt_scene_desc *d, rt_arena *arena, rt_scene *s, rt_build_error *err)
{
    s->light_count = d->light_count;
    s->lights = RT_NEW_ARRAY(arena, rt_light, d->light_count);
    if (!s->lights) return fail(err, RT_ERR_NOMEM, "out of memory for lights", UINT32_MAX);
    for (uint32_t i = 0; i < d->light_count; i++) {
        const rt_light_desc *ld = &d->lights[i];
        rt_light *l = &s->lights[i];
        if (!rt_affine_is_finite(&ld->world) || !rt_v3_is_finite(ld->color) || !rt_v3_is_finite(ld->ambient) ||
            !rt_is_finite(ld->atten_const) || !rt_is_finite(ld->atten_linear) || !rt_is_finite(ld->atten_quad))
            return fail(err, RT_ERR_INVALID, "a light has a value that is not finite", UINT32_MAX);
        l->kind = ld->kind;
        l->position = ld->world.translation;
        l->direction = rt_scene_light_direction(&ld->world);
        if (ld->kind == RT_LIGHT_DIRECTIONAL && rt_v3_is_zero(l->direction))
            return fail(err, RT_ERR_INVALID, "a directional light has no direction (a scale of 0?)", UINT32_MAX);
        rt_vec3 half = rt_v3(RT_C(-0.5), RT_ZERO, RT_C(-0.5));
        l->corner = rt_affine_point(&ld->world, half);
        l->edge_u = rt_affine_vector(&ld->world, rt_v3(RT_ONE, RT_ZERO, RT_ZERO));
        l->edge_v = rt_affine_vector(&ld->world, rt_v3(RT_ZERO, RT_ZERO, RT_ONE));
        /* Z x X is local +Y, also when the node's Y scale is 0. */
        l->normal = rt_v3_normalize(rt_v3_cross(l->edge_v, l->edge_u));
        l->color = ld->color;
        l->ambient = ld->ambient;
        l->atten_const = ld->atten_const;
        l->atten_linear = ld->atten_linear;
        l->atten_quad = ld->atten_quad;
    }
    return RT_OK;
}

static rt_status build_camera(const rt_camera_desc *c, rt_camera *cam, rt_build_error *err)
{
    if (!rt_affine_is_finite(&c->world)) return fail(err, RT_ERR_INVALID, "camera transform is not finite", UINT32_MAX);
    if (c->width == 0 || c->height == 0) return fail(err, RT_ERR_INVALID, "image size is 0", UINT32_MAX);
    if (!rt_is_finite(c->fov_degrees) || !(c->fov_degrees > RT_ZERO) || !(c->fov_degrees < rt_from_int(180)))
        return fail(err, RT_ERR_INVALID, "camera FOV must be between 0 and 180 degrees", UINT32_MAX);
    cam->eye = c->world.translation;
    cam->forward = rt_v3_normalize(rt_affine_vector(&c->world, rt_v3(RT_ZERO, RT_ZERO, rt_neg(RT_ONE))));
    cam->right = rt_v3_normalize(rt_affine_vector(&c->world, rt_v3(RT_ONE, RT_ZERO, RT_ZERO)));
    cam->up = rt_v3_normalize(rt_affine_vector(&c->world, rt_v3(RT_ZERO, RT_ONE, RT_ZERO)));
    if (rt_v3_is_zero(cam->forward) || rt_v3_is_zero(cam->right) || rt_v3_is_zero(cam->up))
        return fail(err, RT_ERR_INVALID, "camera transform is singular", UINT32_MAX);
    /* The skeleton converts degrees with 3.14159, not pi (format.md §7.2). */
    cam->tan_half_fov = rt_tan(rt_mul(rt_mul(c->fov_degrees, RT_C(0.5)), rt_div(RT_C(3.14159), rt_from_int(180))));
    cam->aspect = rt_div(rt_from_int(c->width), rt_from_int(c->height));
    cam->perspective = c->perspective;
    cam->ortho_width = c->ortho_width;
    cam->width = c->width;
    cam->height = c->height;
    cam->trace = c->trace;
    if (cam->trace.max_depth > RT_MAX_RECURSION_DEPTH)
        return fail(err, RT_ERR_INVALID, "Maximum Recursion Depth is above 64", UINT32_MAX);
    /* Choice indices above their range mean the last choice, as in the skeleton. */
    rt_trace_settings *t = &cam->trace;
    if (t->shadows > RT_SHADOWS_LAST) t->shadows = RT_SHADOWS_LAST;
    if (t->samples_per_pixel_index > RT_MAX_SPP_INDEX) t->samples_per_pixel_index = RT_MAX_SPP_INDEX;
    if (t->monte_carlo > RT_MONTE_CARLO_LAST) t->monte_carlo = RT_MONTE_CARLO_LAST;
    if (t->sample_count_type > RT_SAMPLES_LAST) t->sample_count_type = RT_SAMPLES_LAST;
    if (t->min_samples_index > RT_MAX_MIN_SAMPLES_INDEX) t->min_samples_index = RT_MAX_MIN_SAMPLES_INDEX;
    if (t->max_samples_index > RT_MAX_MAX_SAMPLES_INDEX) t->max_samples_index = RT_MAX_MAX_SAMPLES_INDEX;
    if (!rt_is_finite(cam->trace.focus_distance) || !rt_is_finite(cam->trace.aperture_size) ||
        !rt_is_finite(cam->ortho_width) || !rt_is_finite(cam->trace.difference_threshold) ||
        !rt_is_finite(cam->trace.std_error_threshold))
        return fail(err, RT_ERR_INVALID, "camera focus, aperture, view width or a sampling threshold is not finite",
                    UINT32_MAX);
    rt_camera_prepare(cam);
    return RT_OK;
}

/* With triangles in the scene, every ray must start within RT_TRIANGLE_RANGE, or a
 * triangle could vanish without a word: rays start at the camera (its lens or its
 * orthographic window) and on objects, whose object-space extent is [-0.5, 0.5]^3. */
static rt_status check_triangle_range(const rt_scene *s, rt_build_error *err)
{
    if (s->triangle_count == 0) return RT_OK;
    for (uint32_t i = 0; i < s->object_count; i++) {
        const rt_affine *w = &s->objects[i].to_world;
        if (s->objects[i].kind == RT_SHAPE_MESH) continue; /* its vertices were checked */
        rt_real reach[3];
        for (int k = 0; k < 3; k++) {
            reach[k] = rt_abs(rt_v3_get(w->translation, k));
            for (int j = 0; j < 3; j++) reach[k] = rt_add(reach[k], rt_mul(rt_abs(w->linear.m[k][j]), RT_C(0.5)));
        }
        if (!within_triangle_range(rt_v3(reach[0], reach[1], reach[2])))
            return fail(err, RT_ERR_INVALID,
                        "the object reaches farther than " RT_TRIANGLE_RANGE_TEXT
                        " from the origin, beyond the range triangles are traced in (the scene has triangles)",
                        i);
    }
    const rt_camera *cam = &s->camera;
    rt_real half_w = rt_abs(rt_mul(cam->ortho_width, RT_C(0.5)));
    rt_real spread = cam->perspective ? rt_abs(rt_mul(cam->trace.aperture_size, RT_C(0.5)))
                                      : rt_add(half_w, rt_div(half_w, cam->aspect));
    rt_vec3 eye = cam->eye;
    if (!within_triangle_range(
            rt_v3(rt_add(rt_abs(eye.x), spread), rt_add(rt_abs(eye.y), spread), rt_add(rt_abs(eye.z), spread))))
        return fail(err, RT_ERR_INVALID,
                    "the camera's rays start farther than " RT_TRIANGLE_RANGE_TEXT
                    " from the origin, beyond the range triangles are traced in (the scene has triangles)",
                    UINT32_MAX);
    return RT_OK;
}

rt_status rt_scene_build(const rt_scene_desc *desc, rt_arena *arena, const rt_workers *workers, rt_scene *out,
                         rt_build_error *err)
{
    rt_scene s = {0};
    err->status = RT_OK;
    err->what = "";
    err->object = UINT32_MAX;
    rt_status st = copy_materials(desc, arena, &s, err);
    if (st == RT_OK) st = build_objects(desc, arena, &s, err);
    if (st == RT_OK) st = build_lights(desc, arena, &s, err);
    if (st == RT_OK) st = build_camera(&desc->camera, &s.camera, err);
    if (st == RT_OK) st = check_triangle_range(&s, err);
    if (st == RT_OK && rt_bvh_build(&s, arena, workers) != RT_OK)
        st = fail(err, RT_ERR_NOMEM, "out of memory for the BVH", UINT32_MAX);
    if (st == RT_OK) *out = s;
    return st;
}

/* The open scene as the browser's 3D view draws it: objects, lights and camera as one
 * JSON document on stdout, and the world-space mesh triangles as arrays in memory. */
#include "debug/json_out.h"
#include "debug/pixel_trace.h"
#include "rtk_wasm.h"
#include <stdio.h>

#define EXPORT(name) __attribute__((export_name(#name)))

static void vec(const char *key, rt_vec3 v)
{
    printf("\"%s\": ", key);
    rtp_json_vec3(stdout, v.x, v.y, v.z);
}

/* Row-major 3x4 [linear | translation]. */
static void affine(const rt_affine *a)
{
    fputs("\"to_world\": [", stdout);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++) {
            if (r || c) fputs(", ", stdout);
            rtp_json_number(stdout, c < 3    ? a->linear.m[r][c]
                                    : r == 0 ? a->translation.x
                                    : r == 1 ? a->translation.y
                                             : a->translation.z);
        }
    fputs("]", stdout);
}

static const char *name_of(char **names, uint32_t count, uint32_t i)
{
    return names && i < count && names[i] ? names[i] : "";
}

static void object(const rtp_scene *b, uint32_t i)
{
    const rt_object *o = &b->scene.objects[i];
    static const char *kinds[] = {"sphere", "cylinder", "mesh"};
    printf("{\"index\": %u, \"kind\": \"%s\", \"node\": ", i, kinds[o->kind]);
    rtp_json_string(stdout, name_of(b->loaded.node_names, b->loaded.node_count, o->source));
    fputs(", \"material\": ", stdout);
    rtp_json_string(stdout, name_of(b->loaded.material_names, b->scene.material_count, o->material));
    fputs(", ", stdout);
    vec("diffuse", b->scene.materials[o->material].diffuse.color);
    fputs(", ", stdout);
    vec("emissive", b->scene.materials[o->material].emissive.color);
    fputs(", ", stdout);
    vec("transmittance", b->scene.materials[o->material].transmittance.color);
    fputs(", ", stdout);
    affine(&o->to_world);
    printf(", \"first_triangle\": %u, \"triangle_count\": %u}", o->first_triangle, o->triangle_count);
}

static void light(const rt_light *l, uint32_t i)
{
    printf("{\"index\": %u, \"kind\": \"%s\", ", i, rtp_pixel_trace_light_kind(l->kind));
    vec("position", l->position);
    fputs(", ", stdout);
    vec("direction", l->direction);
    fputs(", ", stdout);
    vec("color", l->color);
    fputs(", ", stdout);
    vec("corner", l->corner);
    fputs(", ", stdout);
    vec("edge_u", l->edge_u);
    fputs(", ", stdout);
    vec("edge_v", l->edge_v);
    fputs("}", stdout);
}

/* {"objects": [...], "lights": [...], "camera": {...}, "triangle_count": N} on stdout. */
EXPORT(rtk_scene_json) void rtk_scene_json(void)
{
    const rtp_scene *b = rtk_wasm_scene();
    const rt_scene *s = &b->scene;
    fputs("{\"objects\": [", stdout);
    for (uint32_t i = 0; i < s->object_count; i++) {
        if (i) fputs(",\n", stdout);
        object(b, i);
    }
    fputs("],\n\"lights\": [", stdout);
    for (uint32_t i = 0; i < s->light_count; i++) {
        if (i) fputs(",\n", stdout);
        light(&s->lights[i], i);
    }
    const rt_camera *c = &s->camera;
    fputs("],\n\"camera\": {", stdout);
    vec("eye", c->eye);
    fputs(", ", stdout);
    vec("forward", c->forward);
    fputs(", ", stdout);
    vec("right", c->right);
    fputs(", ", stdout);
    vec("up", c->up);
    fputs(", \"tan_half_fov\": ", stdout);
    rtp_json_number(stdout, c->tan_half_fov);
    fputs(", \"aspect\": ", stdout);
    rtp_json_number(stdout, c->aspect);
    fputs(", \"ortho_width\": ", stdout);
    rtp_json_number(stdout, c->ortho_width);
    printf(", \"perspective\": %s, \"width\": %u, \"height\": %u},\n", c->perspective ? "true" : "false", c->width,
           c->height);
    printf("\"vertex_count\": %u, \"triangle_count\": %u}\n", s->vertex_count, s->triangle_count);
    fflush(stdout);
}

/* World-space mesh vertices (3 doubles each) and triangles (3 vertex indices each). */
EXPORT(rtk_positions) const rt_vec3 *rtk_positions(void) { return rtk_wasm_scene()->scene.positions; }
EXPORT(rtk_triangles) const rt_triangle *rtk_triangles(void) { return rtk_wasm_scene()->scene.triangles; }

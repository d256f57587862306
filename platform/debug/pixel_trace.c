/* Tracing one pixel with the ray log, and the tree over the log; see pixel_trace.h. */
#include "debug/pixel_trace.h"

#include "mem/mem.h"
#include <string.h>

static uint32_t *index_array(uint32_t count)
{
    uint32_t *a = rtp_mem_alloc((count ? count : 1) * sizeof *a, "the ray log");
    if (a) memset(a, 0xff, (count ? count : 1) * sizeof *a); /* every entry RT_NO_PARENT */
    return a;
}

/* The light record of ray `ray` for light `light`, or RT_NO_PARENT when it was not logged. */
static uint32_t light_record(const rtp_pixel_trace *pt, uint32_t ray, uint32_t light)
{
    for (uint32_t j = pt->first_light[ray]; j != RT_NO_PARENT; j = pt->next_light[j])
        if (pt->log.lights[j].light == light) return j;
    return RT_NO_PARENT;
}

/* Builds the lists back to front, so that prepending keeps log order. */
static void link_tree(rtp_pixel_trace *pt)
{
    const rt_ray_log *log = &pt->log;
    for (uint32_t j = log->light_count; j-- > 0;) {
        uint32_t ray = log->lights[j].ray;
        pt->next_light[j] = pt->first_light[ray];
        pt->first_light[ray] = j;
    }
    pt->first_root = RT_NO_PARENT;
    for (uint32_t i = log->ray_count; i-- > 0;) {
        const rt_ray_record *r = &log->rays[i];
        uint32_t *head = &pt->first_root;
        if (r->parent != RT_NO_PARENT) {
            uint32_t j = r->kind == RT_RAY_SHADOW ? light_record(pt, r->parent, r->light) : RT_NO_PARENT;
            head = j != RT_NO_PARENT ? &pt->first_shadow[j] : &pt->first_child[r->parent];
        }
        pt->next_sibling[i] = *head;
        *head = i;
    }
}

bool rtp_pixel_trace_run(rtp_pixel_trace *pt, const rtp_scene *built, uint32_t x, uint32_t y, uint32_t sample,
                         uint32_t capacity)
{
    const rt_scene *scene = &built->scene;
    memset(pt, 0, sizeof *pt);
    pt->built = built;
    pt->x = x;
    pt->y = y;
    pt->samples = rt_camera_samples(&scene->camera);
    pt->sample = sample;
    pt->log.rays = rtp_mem_calloc(capacity ? capacity : 1, sizeof *pt->log.rays, "the ray log");
    pt->log.lights = rtp_mem_calloc(capacity ? capacity : 1, sizeof *pt->log.lights, "the ray log");
    pt->log.ray_capacity = pt->log.light_capacity = capacity;
    pt->first_child = index_array(capacity);
    pt->first_shadow = index_array(capacity);
    pt->next_sibling = index_array(capacity);
    pt->first_light = index_array(capacity);
    pt->next_light = index_array(capacity);
    if (!pt->log.rays || !pt->log.lights || !pt->first_child || !pt->first_shadow || !pt->next_sibling ||
        !pt->first_light || !pt->next_light) {
        rtp_pixel_trace_free(pt);
        return false;
    }
    rt_tracer logged = {.scene = scene, .use_bvh = true, .log = &pt->log};
    if (sample == RTP_PIXEL_ALL_SAMPLES) {
        pt->color = rt_render_pixel(&logged, x, y);
    } else {
        rt_render_sample(&logged, x, y, sample);
        rt_tracer plain = {.scene = scene, .use_bvh = true};
        pt->color = rt_render_pixel(&plain, x, y);
    }
    pt->rgb[0] = rt_render_color_byte(pt->color.x);
    pt->rgb[1] = rt_render_color_byte(pt->color.y);
    pt->rgb[2] = rt_render_color_byte(pt->color.z);
    link_tree(pt);
    return true;
}

void rtp_pixel_trace_free(rtp_pixel_trace *pt)
{
    rtp_mem_free(pt->log.rays);
    rtp_mem_free(pt->log.lights);
    rtp_mem_free(pt->first_child);
    rtp_mem_free(pt->first_shadow);
    rtp_mem_free(pt->next_sibling);
    rtp_mem_free(pt->first_light);
    rtp_mem_free(pt->next_light);
    memset(pt, 0, sizeof *pt);
}

rtp_hit_names rtp_pixel_trace_names(const rtp_pixel_trace *pt, const rt_ray_record *r)
{
    static const char *const parts[] = {"body", "bottom cap", "top cap"};
    const rt_scene *s = &pt->built->scene;
    const rtp_loaded_scene *l = &pt->built->loaded;
    const rt_object *obj = &s->objects[r->surface.object];
    rtp_hit_names n = {"?", "triangle", NULL, UINT32_MAX, "?"};
    if (obj->source < l->node_count) n.node = l->node_names[obj->source];
    if (obj->material < l->desc.material_count) n.material = l->material_names[obj->material];
    uint32_t prim = r->scene_hit.prim;
    if (prim < s->triangle_count) {
        n.triangle = prim - obj->first_triangle;
    } else if (obj->kind == RT_SHAPE_SPHERE) {
        n.primitive = "sphere";
    } else {
        n.primitive = "cylinder";
        n.part = parts[r->scene_hit.hit.part];
    }
    return n;
}

rtp_hit_material rtp_pixel_trace_material(const rtp_pixel_trace *pt, const rt_ray_record *r)
{
    const rt_scene *s = &pt->built->scene;
    const rt_material *m = &s->materials[r->surface.material];
    rt_vec2 uv = r->surface.uv;
    rtp_hit_material h = {rt_surface_channel(s, &m->diffuse, uv), rt_surface_channel(s, &m->specular, uv),
                          rt_surface_channel(s, &m->transmittance, uv), m->shininess, m->index_of_refraction};
    return h;
}

const char *rtp_pixel_trace_ray_kind(rt_ray_kind kind)
{
    static const char *const names[] = {"camera", "reflection", "refraction", "shadow", "diffuse", "glossy"};
    return names[kind];
}

const char *rtp_pixel_trace_light_kind(rt_light_kind kind)
{
    static const char *const names[] = {"point", "directional", "area"};
    return names[kind];
}

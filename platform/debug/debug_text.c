/* `rtk debug` as text: the ray tree indented by depth, one fact per line. */
#include "debug/debug_output.h"

/* Nine significant digits: enough to tell apart any two floats, short enough to read. */
#define NUM "%.9g"

static void vec(FILE *out, rt_vec3 v)
{
    fprintf(out, "(" NUM ", " NUM ", " NUM ")", rt_to_double(v.x), rt_to_double(v.y), rt_to_double(v.z));
}

static void indent(FILE *out, unsigned level) { fprintf(out, "%*s", (int)(2 * level), ""); }

static void print_hit(FILE *out, const rtp_pixel_trace *pt, const rt_ray_record *r, unsigned level)
{
    rtp_hit_names n = rtp_pixel_trace_names(pt, r);
    indent(out, level);
    fprintf(out, "hit '%s': %s", n.node, n.primitive);
    if (n.part) fprintf(out, " %s", n.part);
    if (n.triangle != UINT32_MAX)
        fprintf(out, " %u of its mesh (b1 " NUM ", b2 " NUM ")", n.triangle, rt_to_double(r->scene_hit.hit.b1),
                rt_to_double(r->scene_hit.hit.b2));
    fprintf(out, ", t " NUM ", material '%s'\n", rt_to_double(r->scene_hit.hit.t), n.material);
    indent(out, level + 1);
    fprintf(out, "point ");
    vec(out, r->surface.point);
    fprintf(out, "  uv (" NUM ", " NUM ")\n", rt_to_double(r->surface.uv.u), rt_to_double(r->surface.uv.v));
    indent(out, level + 1);
    fprintf(out, "normal: geometric ");
    vec(out, r->surface.geometric_normal);
    fprintf(out, "  shading ");
    vec(out, r->surface.normal);
    if (r->kind == RT_RAY_SHADOW) {
        fprintf(out, "\n");
        indent(out, level + 1);
        fprintf(out, "transmittance ");
        vec(out, r->transmittance);
        fprintf(out, "\n");
        return;
    }
    fprintf(out, "  used ");
    vec(out, r->normal_used);
    fprintf(out, r->entering ? " (faces the viewer)\n" : " (flipped to face the viewer)\n");
    rtp_hit_material m = rtp_pixel_trace_material(pt, r);
    indent(out, level + 1);
    fprintf(out, "k_d ");
    vec(out, m.kd);
    fprintf(out, "  k_s ");
    vec(out, m.ks);
    fprintf(out, "  k_t ");
    vec(out, m.kt);
    fprintf(out, "  shininess " NUM "  index " NUM "\n", rt_to_double(m.shininess),
            rt_to_double(m.index_of_refraction));
    indent(out, level + 1);
    fprintf(out, "emissive ");
    vec(out, r->emissive);
    fprintf(out, r->total_internal_reflection ? "  total internal reflection\n" : "\n");
}

static void print_ray(FILE *out, const rtp_pixel_trace *pt, uint32_t id, unsigned level);

static void print_light(FILE *out, const rtp_pixel_trace *pt, uint32_t j, unsigned level)
{
    const rt_light_record *l = &pt->log.lights[j];
    indent(out, level);
    fprintf(out, "light %u (%s): ambient ", l->light,
            rtp_pixel_trace_light_kind(pt->built->scene.lights[l->light].kind));
    vec(out, l->ambient);
    fprintf(out, "  N.L " NUM "  N.H " NUM "\n", rt_to_double(l->n_dot_l), rt_to_double(l->n_dot_h));
    indent(out, level + 1);
    fprintf(out, "diffuse ");
    vec(out, l->diffuse);
    fprintf(out, "  specular ");
    vec(out, l->specular);
    fprintf(out, "\n");
    indent(out, level + 1);
    fprintf(out, "distance attenuation " NUM "  light cosine " NUM "  shadow attenuation ",
            rt_to_double(l->distance_attenuation), rt_to_double(l->light_cosine));
    vec(out, l->shadow_attenuation);
    fprintf(out, "  contribution ");
    vec(out, l->contribution);
    fprintf(out, "\n");
    for (uint32_t s = pt->first_shadow[j]; s != RT_NO_PARENT; s = pt->next_sibling[s]) print_ray(out, pt, s, level + 1);
}

static void print_ray(FILE *out, const rtp_pixel_trace *pt, uint32_t id, unsigned level)
{
    const rt_ray_record *r = &pt->log.rays[id];
    indent(out, level);
    fprintf(out, "%s ray, depth %u", rtp_pixel_trace_ray_kind(r->kind), r->depth);
    if (r->kind == RT_RAY_SHADOW) fprintf(out, ", towards light %u", r->light);
    fprintf(out, "\n");
    indent(out, level + 1);
    fprintf(out, "origin ");
    vec(out, r->ray.origin);
    fprintf(out, "  direction ");
    vec(out, r->ray.direction);
    fprintf(out, "\n");
    if (r->kind == RT_RAY_GLOSSY) {
        indent(out, level + 1);
        fprintf(out, "half vector ");
        vec(out, r->half_vector);
        fprintf(out, r->mirror_fallback ? "  (its reflection fell below the surface: mirror direction)\n" : "\n");
    }
    if (r->hit) {
        print_hit(out, pt, r, level + 1);
    } else if (r->on_light) {
        indent(out, level + 1);
        fprintf(out, "ends on light %u (%s), t " NUM ", point ", r->light,
                rtp_pixel_trace_light_kind(pt->built->scene.lights[r->light].kind), rt_to_double(r->ray.t_max));
        vec(out, rt_v3_madd(r->ray.origin, r->ray.direction, r->ray.t_max));
        fprintf(out, "\n");
    } else {
        indent(out, level + 1);
        fprintf(out, "no hit\n");
    }
    for (uint32_t j = pt->first_light[id]; j != RT_NO_PARENT; j = pt->next_light[j]) print_light(out, pt, j, level + 1);
    for (uint32_t c = pt->first_child[id]; c != RT_NO_PARENT; c = pt->next_sibling[c]) print_ray(out, pt, c, level + 1);
    indent(out, level + 1);
    fprintf(out, r->kind == RT_RAY_SHADOW ? "attenuation " : "returns ");
    vec(out, r->color);
    fprintf(out, "\n");
}

void rtp_debug_print_text(FILE *out, const rtp_pixel_trace *pt)
{
    const rt_camera *cam = &pt->built->scene.camera;
    fprintf(out, "pixel (%u, %u) of %ux%u, %u sample%s per pixel, maximum depth %u\n", pt->x, pt->y, cam->width,
            cam->height, pt->samples, pt->samples == 1 ? "" : "s", cam->trace.max_depth);
    uint32_t sample = pt->sample == RTP_PIXEL_ALL_SAMPLES ? 0 : pt->sample;
    for (uint32_t id = pt->first_root; id != RT_NO_PARENT; id = pt->next_sibling[id]) {
        fprintf(out, "\nsample %u\n", sample++);
        print_ray(out, pt, id, 1);
    }
    if (pt->log.overflow)
        fprintf(out, "\n(the log is full: only the first %u rays and %u light records are shown)\n",
                pt->log.ray_capacity, pt->log.light_capacity);
    fprintf(out, "\npixel (%u, %u): colour ", pt->x, pt->y);
    vec(out, pt->color);
    fprintf(out, "%s-> bytes %u %u %u\n", pt->samples > 1 ? " (average of the samples) " : " ", pt->rgb[0], pt->rgb[1],
            pt->rgb[2]);
}

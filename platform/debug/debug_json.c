/* `rtk debug --json`: the ray tree as one JSON document. Rays nest: a ray's "lights"
 * hold the shadow rays sent to each light, its "children" the reflected, refracted,
 * diffuse and glossy rays. A camera ray that ends on an area light's square (Monte
 * Carlo mode) has "hit": null and names the light in "light_hit". */
#include "debug/debug_output.h"

#include "debug/json_out.h"

static void num(FILE *out, rt_real r) { rtp_json_number(out, rt_to_double(r)); }

static void vec(FILE *out, rt_vec3 v) { rtp_json_vec3(out, rt_to_double(v.x), rt_to_double(v.y), rt_to_double(v.z)); }

/* ", \"name\": " */
static void key(FILE *out, const char *name) { fprintf(out, ", \"%s\": ", name); }

static void newline(FILE *out, unsigned level) { fprintf(out, "\n%*s", (int)(2 * level), ""); }

static void hit(FILE *out, const rtp_pixel_trace *pt, const rt_ray_record *r)
{
    rtp_hit_names n = rtp_pixel_trace_names(pt, r);
    fputs("{\"node\": ", out);
    rtp_json_string(out, n.node);
    fprintf(out, ", \"object\": %u, \"primitive\": ", r->surface.object);
    rtp_json_string(out, n.primitive);
    key(out, "part");
    if (n.part)
        rtp_json_string(out, n.part);
    else
        fputs("null", out);
    key(out, "triangle");
    if (n.triangle == UINT32_MAX) {
        fputs("null", out);
    } else {
        fprintf(out, "%u", n.triangle);
        key(out, "barycentric");
        fputc('[', out);
        num(out, r->scene_hit.hit.b1);
        fputs(", ", out);
        num(out, r->scene_hit.hit.b2);
        fputc(']', out);
    }
    key(out, "t");
    num(out, r->scene_hit.hit.t);
    key(out, "point");
    vec(out, r->surface.point);
    key(out, "uv");
    fputc('[', out);
    num(out, r->surface.uv.u);
    fputs(", ", out);
    num(out, r->surface.uv.v);
    fputc(']', out);
    key(out, "geometric_normal");
    vec(out, r->surface.geometric_normal);
    key(out, "shading_normal");
    vec(out, r->surface.normal);
    key(out, "material");
    rtp_json_string(out, n.material);
    if (r->kind == RT_RAY_SHADOW) {
        key(out, "transmittance");
        vec(out, r->transmittance);
        fputc('}', out);
        return;
    }
    rtp_hit_material m = rtp_pixel_trace_material(pt, r);
    key(out, "normal_used");
    vec(out, r->normal_used);
    fprintf(out, ", \"flipped\": %s", r->entering ? "false" : "true");
    key(out, "kd");
    vec(out, m.kd);
    key(out, "ks");
    vec(out, m.ks);
    key(out, "kt");
    vec(out, m.kt);
    key(out, "shininess");
    num(out, m.shininess);
    key(out, "index_of_refraction");
    num(out, m.index_of_refraction);
    key(out, "emissive");
    vec(out, r->emissive);
    fprintf(out, ", \"total_internal_reflection\": %s}", r->total_internal_reflection ? "true" : "false");
}

/* The area light whose square the ray ends on, where, and the emission it brings back. */
static void light_hit(FILE *out, const rtp_pixel_trace *pt, const rt_ray_record *r)
{
    fprintf(out, "{\"light\": %u, \"kind\": \"%s\"", r->light,
            rtp_pixel_trace_light_kind(pt->built->scene.lights[r->light].kind));
    key(out, "t");
    num(out, r->ray.t_max);
    key(out, "point");
    vec(out, rt_v3_madd(r->ray.origin, r->ray.direction, r->ray.t_max));
    key(out, "emission");
    vec(out, r->color);
    fputc('}', out);
}

static void ray(FILE *out, const rtp_pixel_trace *pt, uint32_t id, unsigned level);

/* The rays of a list, as the elements of a JSON array. */
static void ray_list(FILE *out, const rtp_pixel_trace *pt, uint32_t first, unsigned level)
{
    fputc('[', out);
    for (uint32_t id = first; id != RT_NO_PARENT; id = pt->next_sibling[id]) {
        if (id != first) fputc(',', out);
        newline(out, level);
        ray(out, pt, id, level);
    }
    fputc(']', out);
}

static void light(FILE *out, const rtp_pixel_trace *pt, uint32_t j, unsigned level)
{
    const rt_light_record *l = &pt->log.lights[j];
    rt_light_kind kind = pt->built->scene.lights[l->light].kind;
    fprintf(out, "{\"light\": %u, \"kind\": \"%s\"", l->light, rtp_pixel_trace_light_kind(kind));
    key(out, "ambient");
    vec(out, l->ambient);
    key(out, "n_dot_l");
    num(out, l->n_dot_l);
    key(out, "n_dot_h");
    num(out, l->n_dot_h);
    key(out, "diffuse");
    vec(out, l->diffuse);
    key(out, "specular");
    vec(out, l->specular);
    key(out, "distance_attenuation");
    num(out, l->distance_attenuation);
    key(out, "light_cosine");
    num(out, l->light_cosine);
    key(out, "shadow_attenuation");
    vec(out, l->shadow_attenuation);
    key(out, "contribution");
    vec(out, l->contribution);
    key(out, "shadow_rays");
    ray_list(out, pt, pt->first_shadow[j], level + 1);
    fputc('}', out);
}

static void ray(FILE *out, const rtp_pixel_trace *pt, uint32_t id, unsigned level)
{
    const rt_ray_record *r = &pt->log.rays[id];
    fprintf(out, "{\"kind\": \"%s\", \"depth\": %u", rtp_pixel_trace_ray_kind(r->kind), r->depth);
    if (r->kind == RT_RAY_SHADOW) fprintf(out, ", \"light\": %u", r->light);
    key(out, "origin");
    vec(out, r->ray.origin);
    key(out, "direction");
    vec(out, r->ray.direction);
    if (r->kind == RT_RAY_GLOSSY) {
        key(out, "half_vector");
        vec(out, r->half_vector);
        fprintf(out, ", \"mirror_fallback\": %s", r->mirror_fallback ? "true" : "false");
    }
    key(out, "hit");
    if (r->hit)
        hit(out, pt, r);
    else
        fputs("null", out);
    key(out, "light_hit");
    if (r->on_light)
        light_hit(out, pt, r);
    else
        fputs("null", out);
    key(out, "lights");
    fputc('[', out);
    for (uint32_t j = pt->first_light[id]; j != RT_NO_PARENT; j = pt->next_light[j]) {
        if (j != pt->first_light[id]) fputc(',', out);
        newline(out, level + 1);
        light(out, pt, j, level + 1);
    }
    fputc(']', out);
    key(out, "children");
    ray_list(out, pt, pt->first_child[id], level + 1);
    /* Shadow rays bring back the attenuation so far, other rays their colour. */
    key(out, "color");
    vec(out, r->color);
    fputc('}', out);
}

void rtp_debug_print_json(FILE *out, const rtp_pixel_trace *pt)
{
    const rt_camera *cam = &pt->built->scene.camera;
    fprintf(out, "{\"pixel\": [%u, %u], \"image\": [%u, %u], \"samples_per_pixel\": %u, \"sample\": ", pt->x, pt->y,
            cam->width, cam->height, pt->samples);
    if (pt->sample == RTP_PIXEL_ALL_SAMPLES)
        fputs("null", out);
    else
        fprintf(out, "%u", pt->sample);
    fprintf(out, ", \"max_depth\": %u, \"log_full\": %s,", cam->trace.max_depth, pt->log.overflow ? "true" : "false");
    newline(out, 1);
    fputs("\"samples\": ", out);
    ray_list(out, pt, pt->first_root, 2);
    fputc(',', out);
    newline(out, 1);
    fputs("\"color\": ", out);
    vec(out, pt->color);
    fprintf(out, ", \"bytes\": [%u, %u, %u]\n}\n", pt->rgb[0], pt->rgb[1], pt->rgb[2]);
}

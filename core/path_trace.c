/* Monte Carlo tracing; see path_trace.h. A hit adds its emission and the direct term
 * of every light (format.md §8; an area light at one sampled point of its square, times
 * its cosine there, format.md §11.4), then follows its branches: a cosine-weighted diffuse ray
 * weighted by k_d (the cosine density cancels the cosine of the diffuse integral), a
 * glossy ray about a half vector drawn from the Blinn-Phong lobe (k_s, format.md §11.6) and the
 * refracted ray (k_t). With random single branching one branch is followed, chosen
 * with probability proportional to its weight and divided by that probability, so
 * the expected colour does not change. A camera ray that meets an area light's
 * square before any surface brings back the light's emission (format.md §11.4). */
#include "path_trace.h"
#include "area_light.h"
#include "raylog.h"
#include "shading.h"

typedef struct {
    const rt_tracer *tr;
    const rt_sampler *sampler;
    bool diffuse;       /* Diffuse Reflection is in effect (it needs Reflections) */
    bool caustics;      /* glossy and refraction rays may follow a diffuse bounce */
    bool single_branch; /* Random Single Branching */
} path;

typedef struct {
    rt_ray_kind kind;
    rt_vec3 direction, weight;
    rt_vec3 half_vector;  /* glossy: the sampled half vector (else zero) */
    bool mirror_fallback; /* glossy: the direction about it fell below the surface */
} branch;

static branch make_branch(rt_ray_kind kind, rt_vec3 direction, rt_vec3 weight)
{
    branch b = {kind, direction, weight, rt_v3(RT_ZERO, RT_ZERO, RT_ZERO), false};
    return b;
}

/* Emission plus every light's direct term. An area light acts as a Lambertian point
 * emitter at one point of its square. */
static rt_vec3 direct(const path *pa, const rt_shading_point *p, uint64_t node)
{
    const rt_scene *scene = pa->tr->scene;
    rt_vec3 color = p->ke;
    for (uint32_t i = 0; i < scene->light_count; i++) {
        const rt_light *l = &scene->lights[i];
        bool area = l->kind == RT_LIGHT_AREA;
        rt_vec3 position =
            area ? rt_area_light_point(l, rt_sample_2d(pa->sampler, node, RT_PURPOSE_LIGHT + i)) : l->position;
        color = rt_v3_add(color, rt_shading_light(pa->tr, i, p, position, area));
    }
    return color;
}

/* The reflection branch: the view vector mirrored about a half vector drawn from the
 * Blinn-Phong lobe of exponent Shininess; a direction below the surface falls back to
 * the mirror direction (format.md §11.6). */
static branch glossy(const path *pa, const rt_shading_point *p, uint64_t node)
{
    rt_vec3 h = rt_sample_blinn_half_vector(rt_sample_2d(pa->sampler, node, RT_PURPOSE_GLOSSY), p->n, p->shininess);
    rt_vec3 r = rt_v3_normalize(rt_v3_sub(rt_v3_scale(h, rt_mul(RT_C(2.0), rt_v3_dot(p->v, h))), p->v));
    branch b = make_branch(RT_RAY_GLOSSY, r, p->ks);
    b.half_vector = h;
    b.mirror_fallback = !(rt_v3_dot(r, p->n) > RT_ZERO);
    if (b.mirror_fallback) b.direction = rt_shading_mirror(p);
    return b;
}

/* The rays a hit spawns (at most 3); returns how many. */
static uint32_t branches(const path *pa, const rt_shading_point *p, uint64_t node, bool after_diffuse, branch *out)
{
    const rt_trace_settings *set = &pa->tr->scene->camera.trace;
    uint32_t n = 0;
    if (pa->diffuse && !rt_v3_is_zero(p->kd))
        out[n++] =
            make_branch(RT_RAY_DIFFUSE,
                        rt_sample_cosine_hemisphere(rt_sample_2d(pa->sampler, node, RT_PURPOSE_DIFFUSE), p->n), p->kd);
    /* Without caustics a diffuse bounce is followed by diffuse bounces only. */
    if (after_diffuse && !pa->caustics) return n;
    if (set->reflections && !rt_v3_is_zero(p->ks)) out[n++] = glossy(pa, p, node);
    if (set->refractions && !rt_v3_is_zero(p->kt)) {
        rt_vec3 t;
        rt_ray_record *rec;
        if (rt_shading_refraction(p, &t)) {
            out[n++] = make_branch(RT_RAY_REFRACTION, t, p->kt);
        } else if ((rec = rt_raylog_ray(pa->tr->log, p->ray)) != 0) {
            rec->total_internal_reflection = true;
        }
    }
    return n;
}

static rt_real channel_sum(rt_vec3 c) { return rt_max(rt_add(rt_add(c.x, c.y), c.z), RT_ZERO); }

/* Keeps one branch with probability weight / total weight, its weight divided by
 * that probability; returns 0 when no branch carries weight. */
static uint32_t single_branch(const path *pa, uint64_t node, branch *b, uint32_t n)
{
    rt_real total = RT_ZERO;
    for (uint32_t i = 0; i < n; i++) total = rt_add(total, channel_sum(b[i].weight));
    if (!(total > RT_ZERO)) return 0;
    rt_real target = rt_mul(rt_sample_2d(pa->sampler, node, RT_PURPOSE_BRANCH).u, total);
    rt_real below = RT_ZERO;
    uint32_t k = 0;
    /* The last branch with weight also takes target values that rounding left over. */
    for (uint32_t i = 0; i < n; i++) {
        if (!(channel_sum(b[i].weight) > RT_ZERO)) continue;
        k = i;
        below = rt_add(below, channel_sum(b[i].weight));
        if (target < below) break;
    }
    rt_vec3 weight = rt_v3_scale(b[k].weight, rt_div(total, channel_sum(b[k].weight)));
    b[0] = b[k];
    b[0].weight = weight;
    return 1;
}

/* The colour `ray`, spawned as branch `from` of ray `parent`, brings back. */
static rt_vec3 trace_path(const path *pa, const branch *from, rt_ray ray, uint32_t depth, uint64_t node,
                          uint32_t parent, bool after_diffuse)
{
    const rt_scene *scene = pa->tr->scene;
    uint32_t max_depth = scene->camera.trace.max_depth;
    rt_vec3 color = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    /* As in the Whitted tracer, a ray past the recursion limit is not traced (format.md §9.5). */
    if (depth > max_depth) return color;
    /* Only camera rays see the lights' squares: later rays would count the light that
     * the direct term already does (format.md §11.4). The surface must come first. */
    uint32_t light = 0;
    rt_real light_t;
    bool sees_light = from->kind == RT_RAY_CAMERA && rt_area_light_seen(scene, &ray, &light, &light_t);
    if (sees_light) ray.t_max = light_t;
    rt_shading_point p;
    bool hit = rt_shading_hit(pa->tr, &ray, from->kind, parent, depth, &p);
    rt_ray_record *rec = rt_raylog_ray(pa->tr->log, p.ray);
    if (rec) {
        rec->half_vector = from->half_vector;
        rec->mirror_fallback = from->mirror_fallback;
    }
    if (!hit) {
        if (!sees_light) return color;
        color = rt_v3_scale(scene->lights[light].color, RT_AREA_LIGHT_EMISSION);
        if (rec) {
            rec->on_light = true;
            rec->light = light;
        }
        rt_raylog_color(pa->tr->log, p.ray, color);
        return color;
    }
    color = direct(pa, &p, node);
    branch b[3];
    uint32_t n = depth < max_depth ? branches(pa, &p, node, after_diffuse, b) : 0;
    if (pa->single_branch && n > 1) n = single_branch(pa, node, b, n);
    for (uint32_t i = 0; i < n; i++) {
        rt_vec3 incoming =
            trace_path(pa, &b[i], rt_ray_make(p.point, b[i].direction, RT_REAL_MAX), depth + 1,
                       rt_rng_child(node, b[i].kind), p.ray, after_diffuse || b[i].kind == RT_RAY_DIFFUSE);
        color = rt_v3_add(color, rt_v3_mul(b[i].weight, incoming));
    }
    rt_raylog_color(pa->tr->log, p.ray, color);
    return color;
}

rt_vec3 rt_path_trace(const rt_tracer *tr, const rt_sampler *s, rt_ray ray)
{
    const rt_trace_settings *set = &tr->scene->camera.trace;
    path pa;
    pa.tr = tr;
    pa.sampler = s;
    /* Which keys are in effect follows the skeleton (format.md §11). */
    pa.diffuse = set->monte_carlo != RT_MONTE_CARLO_OFF && set->reflections && set->diffuse_reflection;
    pa.caustics = pa.diffuse && set->shadows != RT_SHADOWS_NONE && set->caustics;
    pa.single_branch = set->monte_carlo != RT_MONTE_CARLO_OFF && set->random_single_branching;
    branch camera = make_branch(RT_RAY_CAMERA, ray.direction, rt_v3(RT_ONE, RT_ONE, RT_ONE));
    return trace_path(&pa, &camera, ray, 0, 0, RT_NO_PARENT, false);
}

/* Monte Carlo tracing; see path_trace.h. A hit adds its emission and the direct term
 * of every light (format §9, an area light at one sampled point of its square), then
 * follows its branches: a cosine-weighted diffuse ray weighted by k_d (the cosine
 * density cancels the cosine of the diffuse integral), the mirror ray (k_s) and the
 * refracted ray (k_t). With random single branching one branch is followed, chosen
 * with probability proportional to its weight and divided by that probability, so
 * the expected colour does not change. */
#include "path_trace.h"
#include "shading.h"

typedef struct {
    const rt_tracer *tr;
    const rt_sampler *sampler;
    bool diffuse;       /* Diffuse Reflection is in effect (it needs Reflections) */
    bool caustics;      /* mirror and refraction may follow a diffuse bounce */
    bool single_branch; /* Random Single Branching */
} path;

typedef struct {
    rt_ray_kind kind;
    rt_vec3 direction, weight;
} branch;

/* Emission plus every light's direct term. An area light acts as a point light at
 * one point of its square and lights only the side its normal faces. */
static rt_vec3 direct(const path *pa, const rt_shading_point *p, uint64_t node)
{
    const rt_scene *scene = pa->tr->scene;
    rt_vec3 color = p->ke;
    for (uint32_t i = 0; i < scene->light_count; i++) {
        const rt_light *l = &scene->lights[i];
        rt_vec3 position = l->position;
        bool emits = true;
        if (l->kind == RT_LIGHT_AREA) {
            rt_vec2 u = rt_sample_2d(pa->sampler, node, RT_PURPOSE_LIGHT + i);
            position = rt_v3_add(l->corner, rt_v3_add(rt_v3_scale(l->edge_u, u.u), rt_v3_scale(l->edge_v, u.v)));
            emits = rt_v3_is_zero(l->normal) || rt_v3_dot(l->normal, rt_v3_sub(p->point, position)) > RT_ZERO;
        }
        color = rt_v3_add(color, rt_shading_light(pa->tr, i, p, position, emits));
    }
    return color;
}

/* The rays a hit spawns (at most 3); returns how many. */
static uint32_t branches(const path *pa, const rt_shading_point *p, uint64_t node, bool after_diffuse, branch *out)
{
    const rt_trace_settings *set = &pa->tr->scene->camera.trace;
    uint32_t n = 0;
    if (pa->diffuse && !rt_v3_is_zero(p->kd)) {
        out[n].kind = RT_RAY_DIFFUSE;
        out[n].weight = p->kd;
        out[n++].direction = rt_sample_cosine_hemisphere(rt_sample_2d(pa->sampler, node, RT_PURPOSE_DIFFUSE), p->n);
    }
    /* Without caustics a diffuse bounce is followed by diffuse bounces only. */
    if (after_diffuse && !pa->caustics) return n;
    if (set->reflections && !rt_v3_is_zero(p->ks)) {
        out[n].kind = RT_RAY_REFLECTION;
        out[n].weight = p->ks;
        out[n++].direction = rt_shading_mirror(p);
    }
    if (set->refractions && !rt_v3_is_zero(p->kt)) {
        rt_ray_record *rec;
        if (rt_shading_refraction(p, &out[n].direction)) {
            out[n].kind = RT_RAY_REFRACTION;
            out[n++].weight = p->kt;
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
    b[0].kind = b[k].kind;
    b[0].direction = b[k].direction;
    b[0].weight = rt_v3_scale(b[k].weight, rt_div(total, channel_sum(b[k].weight)));
    return 1;
}

static rt_vec3 trace_path(const path *pa, rt_ray ray, uint32_t depth, uint64_t node, rt_ray_kind kind, uint32_t parent,
                          bool after_diffuse)
{
    uint32_t max_depth = pa->tr->scene->camera.trace.max_depth;
    rt_vec3 color = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    /* As in the Whitted tracer, a ray past the recursion limit is not traced (format §10.5). */
    if (depth > max_depth) return color;
    rt_shading_point p;
    if (!rt_shading_hit(pa->tr, &ray, kind, parent, depth, &p)) return color;
    color = direct(pa, &p, node);
    branch b[3];
    uint32_t n = depth < max_depth ? branches(pa, &p, node, after_diffuse, b) : 0;
    if (pa->single_branch && n > 1) n = single_branch(pa, node, b, n);
    for (uint32_t i = 0; i < n; i++) {
        rt_vec3 incoming =
            trace_path(pa, rt_ray_make(p.point, b[i].direction, RT_REAL_MAX), depth + 1, rt_rng_child(node, b[i].kind),
                       b[i].kind, p.ray, after_diffuse || b[i].kind == RT_RAY_DIFFUSE);
        color = rt_v3_add(color, rt_v3_mul(b[i].weight, incoming));
    }
    rt_ray_record *rec = rt_raylog_ray(pa->tr->log, p.ray);
    if (rec) rec->color = color;
    return color;
}

rt_vec3 rt_path_trace(const rt_tracer *tr, const rt_sampler *s, rt_ray ray)
{
    const rt_trace_settings *set = &tr->scene->camera.trace;
    path pa;
    pa.tr = tr;
    pa.sampler = s;
    /* Which keys are in effect follows the skeleton (format §12). */
    pa.diffuse = set->monte_carlo != RT_MONTE_CARLO_OFF && set->reflections && set->diffuse_reflection;
    pa.caustics = pa.diffuse && set->shadows != RT_SHADOWS_NONE && set->caustics;
    pa.single_branch = set->monte_carlo != RT_MONTE_CARLO_OFF && set->random_single_branching;
    return trace_path(&pa, ray, 0, 0, RT_RAY_CAMERA, RT_NO_PARENT, false);
}

/* Stratified draws and their warps; see sample.h. */
#include "sample.h"
#include "invariant.h"

rt_vec2 rt_sample_2d(const rt_sampler *s, uint64_t node, uint32_t purpose)
{
    uint64_t key = rt_rng_hash(rt_rng_hash(s->pixel, node), purpose);
    RT_ASSERT(s->strata_log <= 15 && (s->strata_log == 0 || s->sample >> (2 * s->strata_log) == 0));
    uint32_t stratum = rt_rng_permute(s->sample, 2 * s->strata_log, key);
    uint32_t side = 1u << s->strata_log;
    uint64_t jitter = rt_rng_hash(key, s->sample);
    rt_real n = rt_from_int(side);
    rt_vec2 p;
    p.u = rt_div(rt_add(rt_from_int(stratum & (side - 1)), rt_rng_unit(jitter)), n);
    p.v = rt_div(rt_add(rt_from_int(stratum >> s->strata_log), rt_rng_unit(jitter << 32)), n);
    return p;
}

rt_vec2 rt_sample_disc(rt_vec2 u)
{
    rt_real r = rt_sqrt(u.u);
    rt_real phi = rt_mul(rt_mul(RT_C(2.0), RT_PI), u.v);
    rt_vec2 p = {rt_mul(r, rt_cos(phi)), rt_mul(r, rt_sin(phi))};
    return p;
}

/* The unit vector with components (x, y, z) in a tangent frame of unit n (z along n). */
static rt_vec3 about_normal(rt_vec3 n, rt_real x, rt_real y, rt_real z)
{
    /* Any axis far from n gives a tangent frame. */
    rt_vec3 axis = rt_abs(n.x) > RT_C(0.5) ? rt_v3(RT_ZERO, RT_ONE, RT_ZERO) : rt_v3(RT_ONE, RT_ZERO, RT_ZERO);
    rt_vec3 t = rt_v3_normalize(rt_v3_cross(axis, n));
    rt_vec3 b = rt_v3_cross(n, t);
    return rt_v3_normalize(rt_v3_add(rt_v3_add(rt_v3_scale(t, x), rt_v3_scale(b, y)), rt_v3_scale(n, z)));
}

rt_vec3 rt_sample_cosine_hemisphere(rt_vec2 u, rt_vec3 n)
{
    /* Uniform on the disc, projected up onto the hemisphere: density cos/pi (Malley). */
    rt_vec2 d = rt_sample_disc(u);
    rt_real z = rt_sqrt(rt_max(RT_ZERO, rt_sub(rt_sub(RT_ONE, rt_mul(d.u, d.u)), rt_mul(d.v, d.v))));
    return about_normal(n, d.u, d.v, z);
}

rt_vec3 rt_sample_blinn_half_vector(rt_vec2 u, rt_vec3 n, rt_real exponent)
{
    /* The inverse of the lobe's distribution of cos(theta), cos^(exponent+1). */
    rt_real cos_theta = rt_pow(u.u, rt_div(RT_ONE, rt_add(rt_max(exponent, RT_ZERO), RT_ONE)));
    rt_real sin_theta = rt_sqrt(rt_max(RT_ZERO, rt_sub(RT_ONE, rt_mul(cos_theta, cos_theta))));
    rt_real phi = rt_mul(rt_mul(RT_C(2.0), RT_PI), u.v);
    return about_normal(n, rt_mul(sin_theta, rt_cos(phi)), rt_mul(sin_theta, rt_sin(phi)), cos_theta);
}

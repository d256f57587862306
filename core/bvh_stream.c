/* The stream queries of bvh.h: rays grouped into packets by direction octant and largest
 * axis (which decide the axis permutation), each packet walked by the kernel's packet
 * walk (bvh_packet.h); rays the float bounds cannot take, and packets of one ray, go one
 * by one. */
#include "bvh_float.h"

bool rt_bvh_kernel_compiled(rt_kernel k)
{
    return k == RT_KERNEL_PORTABLE ||
           ((k == RT_KERNEL_SSE2 || k == RT_KERNEL_AVX2 || k == RT_KERNEL_AVX512) && FLOAT_WALK);
}

bool rt_bvh_packets(const rt_bvh *bvh) { return FLOAT_WALK && bvh->kernel != RT_KERNEL_PORTABLE; }

#if FLOAT_WALK
/* Rays waiting for their packet: one group per octant (3 bits) and largest axis (kz). */
#define GROUPS 24

typedef struct {
    const rt_ray_setup *rs[RT_PACKET];
    uint32_t index[RT_PACKET], n;
} group;

static void trace_group(const rt_scene *scene, group *g, bool any, rt_scene_hit *out, bool *found)
{
    rt_scene_hit hits[RT_PACKET];
    bool got[RT_PACKET] = {false};
    unsigned taken = 0;
    if (g->n > 1) {
        switch (scene->bvh.kernel) {
        case RT_KERNEL_AVX512: taken = rt_bvh_packet_avx512(scene, g->rs, g->n, any, hits, got); break;
        case RT_KERNEL_AVX2: taken = rt_bvh_packet_avx2(scene, g->rs, g->n, any, hits, got); break;
        default: taken = rt_bvh_packet_sse2(scene, g->rs, g->n, any, hits, got);
        }
    }
    for (uint32_t i = 0; i < g->n; i++) {
        uint32_t r = g->index[i];
        if (!(taken >> i & 1u)) {
            found[r] = any ? rt_scene_any(scene, g->rs[i], true) : rt_scene_nearest(scene, g->rs[i], true, &out[r]);
            continue;
        }
        found[r] = got[i];
        if (got[i] && !any) out[r] = hits[i];
    }
    g->n = 0;
}

static void stream(const rt_scene *scene, const rt_ray_setup *rs, uint32_t n, bool any, rt_scene_hit *out, bool *found)
{
    group groups[GROUPS];
    uint32_t used = 0; /* the groups a ray has gone to: only those are set up and looked at */
    for (uint32_t i = 0; i < n; i++) {
        rt_vec3 d = rs[i].ray.direction;
        uint32_t k = (uint32_t)rs[i].kz * 8 + (d.x < 0) + 2 * (d.y < 0) + 4 * (d.z < 0);
        group *g = &groups[k];
        if (!(used >> k & 1u)) g->n = 0, used |= 1u << k;
        g->rs[g->n] = &rs[i];
        g->index[g->n++] = i;
        if (g->n == RT_PACKET) trace_group(scene, g, any, out, found);
    }
    for (; used; used &= used - 1) {
        group *g = &groups[__builtin_ctz(used)];
        if (g->n > 0) trace_group(scene, g, any, out, found);
    }
}

/* Packets need the float bounds and at least one primitive; otherwise one by one. */
static bool packets(const rt_scene *scene) { return rt_bvh_packets(&scene->bvh) && scene->prim_count > 0; }
#endif

void rt_scene_nearest_stream(const rt_scene *scene, const rt_ray_setup *rs, uint32_t n, rt_scene_hit *out, bool *found)
{
#if FLOAT_WALK
    if (packets(scene)) {
        stream(scene, rs, n, false, out, found);
        return;
    }
#endif
    for (uint32_t i = 0; i < n; i++) found[i] = rt_scene_nearest(scene, &rs[i], true, &out[i]);
}

void rt_scene_any_stream(const rt_scene *scene, const rt_ray_setup *rs, uint32_t n, bool *found)
{
#if FLOAT_WALK
    if (packets(scene)) {
        stream(scene, rs, n, true, NULL, found);
        return;
    }
#endif
    for (uint32_t i = 0; i < n; i++) found[i] = rt_scene_any(scene, &rs[i], true);
}

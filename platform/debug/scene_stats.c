/* Counting a built scene's contents and costing its BVH; see scene_stats.h. */
#include "debug/scene_stats.h"

#include <string.h>

#include "bvh.h"

static double surface_area(const rt_aabb *b)
{
    double x = rt_to_double(rt_sub(b->hi.x, b->lo.x)), y = rt_to_double(rt_sub(b->hi.y, b->lo.y)),
           z = rt_to_double(rt_sub(b->hi.z, b->lo.z));
    return 2 * (x * y + y * z + z * x);
}

/* The root's box: the union of its children's. */
static rt_aabb root_box(const rt_bvh *bvh)
{
    const rt_bvh_node *root = &bvh->nodes[0];
    rt_aabb box = rt_bvh_child_box(bvh, root, 0);
    for (int c = 1; c < RT_BVH_WIDTH && root->count[c] != RT_BVH_NO_CHILD; c++) {
        rt_aabb b = rt_bvh_child_box(bvh, root, c);
        box.lo = rt_v3_min(box.lo, b.lo);
        box.hi = rt_v3_max(box.hi, b.hi);
    }
    return box;
}

double rtp_scene_stats_sah_cost(const rt_bvh *bvh, uint32_t prim_count)
{
    /* Without primitives the root has no children. */
    if (prim_count == 0) return 0;
    rt_aabb box = root_box(bvh);
    double root = surface_area(&box);
    if (!(root > 0)) return prim_count;
    double cost = 1; /* the root's visit */
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const rt_bvh_node *n = &bvh->nodes[i];
        for (int c = 0; c < RT_BVH_WIDTH && n->count[c] != RT_BVH_NO_CHILD; c++) {
            rt_aabb child = rt_bvh_child_box(bvh, n, c);
            cost += (n->count[c] ? n->count[c] : 1) * surface_area(&child) / root;
        }
    }
    return cost;
}

void rtp_scene_stats_compute(const rtp_scene *built, rtp_scene_stats *out)
{
    const rt_scene *s = &built->scene;
    const rt_scene_desc *d = &built->loaded.desc;
    memset(out, 0, sizeof *out);
    out->nodes = built->loaded.node_count;
    for (uint32_t i = 0; i < d->object_count; i++) {
        const rt_object_desc *o = &d->objects[i];
        if (o->kind == RT_SHAPE_SPHERE)
            out->spheres++;
        else if (o->kind == RT_SHAPE_CYLINDER)
            out->cylinders++;
        else
            out->meshes++, out->triangles_loaded += d->meshes[o->mesh].triangle_count;
    }
    out->triangles = s->triangle_count;
    for (uint32_t i = 0; i < s->light_count; i++) out->lights[s->lights[i].kind]++;
    out->bvh_nodes = s->bvh.node_count;
    for (uint32_t i = 0; i < s->bvh.node_count; i++)
        for (int c = 0; c < RT_BVH_WIDTH; c++) {
            uint32_t count = s->bvh.nodes[i].count[c];
            out->bvh_leaves += count > 0 && count != RT_BVH_NO_CHILD;
        }
    out->bvh_depth = s->bvh.depth;
    out->sah_cost = rtp_scene_stats_sah_cost(&s->bvh, s->prim_count);
    out->arena_used = built->arena.used;
    out->arena_high_water = built->arena.high_water;
    out->arena_capacity = built->arena.capacity;
}

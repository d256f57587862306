/* Counting a built scene's contents and costing its BVH; see scene_stats.h. */
#include "scene_stats.h"

#include <string.h>

#include "bvh.h"

static double surface_area(const rt_aabb *b)
{
    double x = rt_to_double(rt_sub(b->hi.x, b->lo.x)), y = rt_to_double(rt_sub(b->hi.y, b->lo.y)),
           z = rt_to_double(rt_sub(b->hi.z, b->lo.z));
    return 2 * (x * y + y * z + z * x);
}

double rt_bvh_sah_cost(const rt_bvh *bvh, uint32_t prim_count)
{
    /* Without primitives the root is an empty leaf whose box is inverted. */
    if (prim_count == 0) return 0;
    rt_aabb root_box = rt_bvh_node_box(bvh, &bvh->nodes[0]);
    double root = surface_area(&root_box);
    if (!(root > 0)) return prim_count;
    double cost = 0;
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const rt_bvh_node *n = &bvh->nodes[i];
        rt_aabb box = rt_bvh_node_box(bvh, n);
        cost += (n->count ? n->count : 1) * surface_area(&box) / root;
    }
    return cost;
}

void rt_scene_stats_compute(const rt_built_scene *built, rt_scene_stats *out)
{
    const rt_scene *s = &built->scene;
    const rt_scene_desc *d = &built->loaded.desc;
    memset(out, 0, sizeof *out);
    out->nodes = built->loaded.node_count;
    for (uint32_t i = 0; i < d->object_count; i++) {
        const rt_object_desc *o = &d->objects[i];
        if (o->kind == RT_SHAPE_SPHERE) out->spheres++;
        else if (o->kind == RT_SHAPE_CYLINDER) out->cylinders++;
        else out->meshes++, out->triangles_loaded += d->meshes[o->mesh].triangle_count;
    }
    out->triangles = s->triangle_count;
    for (uint32_t i = 0; i < s->light_count; i++) out->lights[s->lights[i].kind]++;
    out->bvh_nodes = s->bvh.node_count;
    for (uint32_t i = 0; i < s->bvh.node_count; i++) out->bvh_leaves += s->bvh.nodes[i].count > 0;
    if (s->prim_count == 0) out->bvh_leaves = 1;
    out->bvh_depth = s->bvh.depth;
    out->sah_cost = rt_bvh_sah_cost(&s->bvh, s->prim_count);
    out->arena_used = built->arena.used;
    out->arena_high_water = built->arena.high_water;
    out->arena_capacity = built->arena.capacity;
}

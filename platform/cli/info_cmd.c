/* `rtk info`: what a scene file holds once loaded and built, and what it costs. */
#include "cli/info_cmd.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "debug/json_out.h"
#include "debug/scene_stats.h"
#include "render.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] = "usage: rtk info SCENE.yaml [--json] [options]\n"
                            "\n"
                            "Loads and builds a scene and prints what the tracer sees: nodes, primitives by kind\n"
                            "(triangles after Loop subdivision), lights by kind, trace-compatible materials,\n"
                            "the textures they use (with sizes), camera and trace settings, the BVH's node count,\n"
                            "depth and SAH cost, and the scene memory (arena) used.\n"
                            "\n"
                            "  --json              one JSON document instead of text\n" RTP_CLI_SCENE_OPTIONS_HELP "\n"
                            "Exit codes: 0 ok, 2 bad arguments, 3 bad or missing input file, 5 over the memory cap.\n";

static const char *const shadow_modes[] = {"none", "opaque", "coloured"};
static const char *const monte_carlo_modes[] = {"off", "mode 1", "mode 2"};

typedef struct {
    const char *scene;
    rtp_scene_options build;
    bool json;
} info_args;

static int parse_args(int argc, char **argv, info_args *a)
{
    memset(a, 0, sizeof *a);
    a->build = rtp_scene_default_options();
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        int common = rtp_cli_common_option("info", usage, argc, argv, &i, &a->build);
        if (common < 0) return -common;
        if (common > 0) continue;
        if (!strcmp(arg, "--json")) {
            a->json = true;
        } else {
            int rc = rtp_cli_scene_argument("info", arg, &a->scene);
            if (rc != RTP_EXIT_OK) return rc;
        }
    }
    if (!a->scene) return rtp_cli_usage_error("info", "no scene file given", NULL);
    return RTP_EXIT_OK;
}

static double d(rt_real r) { return rt_to_double(r); }

static const char *plural(uint64_t n) { return n == 1 ? "" : "s"; }

static void print_text(const char *path, const rtp_scene *b, const rtp_scene_stats *st)
{
    const rt_scene *s = &b->scene;
    const rt_camera *cam = &s->camera;
    const rt_trace_settings *t = &cam->trace;
    printf("scene       %s\n", path);
    printf("nodes       %u enabled\n", st->nodes);
    printf("primitives  %u sphere%s, %u cylinder%s, %u mesh%s with %u triangle%s (%llu before subdivision)\n",
           st->spheres, plural(st->spheres), st->cylinders, plural(st->cylinders), st->meshes,
           st->meshes == 1 ? "" : "es", st->triangles, plural(st->triangles), (unsigned long long)st->triangles_loaded);
    printf("lights      %u point, %u directional, %u area\n", st->lights[RT_LIGHT_POINT],
           st->lights[RT_LIGHT_DIRECTIONAL], st->lights[RT_LIGHT_AREA]);
    printf("materials   %u trace compatible\n", s->material_count);
    for (uint32_t i = 0; i < s->material_count; i++) printf("              %s\n", b->loaded.material_names[i]);
    printf("textures    %u used by traced materials\n", s->texture_count);
    for (uint32_t i = 0; i < s->texture_count; i++)
        printf("              %s: %ux%u, %s\n", b->loaded.texture_names[i], s->textures[i].width, s->textures[i].height,
               s->textures[i].bilinear ? "bilinear" : "nearest");
    if (cam->perspective)
        printf("camera      perspective, vertical FOV %.9g degrees", d(b->loaded.desc.camera.fov_degrees));
    else
        printf("camera      orthographic, view width %.9g", d(cam->ortho_width));
    printf(", %ux%u px, eye (%.9g, %.9g, %.9g), looking along (%.9g, %.9g, %.9g)\n", cam->width, cam->height,
           d(cam->eye.x), d(cam->eye.y), d(cam->eye.z), d(cam->forward.x), d(cam->forward.y), d(cam->forward.z));
    printf("trace       maximum depth %u, shadows %s, reflections %s, refractions %s, %u sample%s per pixel, "
           "Monte Carlo %s\n",
           t->max_depth, shadow_modes[t->shadows], t->reflections ? "on" : "off", t->refractions ? "on" : "off",
           rt_camera_samples(cam), plural(rt_camera_samples(cam)), monte_carlo_modes[t->monte_carlo]);
    printf("bvh         %u node%s (%u lea%s), depth %u, SAH cost %.6g (traversal 1, test 1, per ray at the root)\n",
           st->bvh_nodes, plural(st->bvh_nodes), st->bvh_leaves, st->bvh_leaves == 1 ? "f" : "ves", st->bvh_depth,
           st->sah_cost);
    printf("memory      arena %zu bytes used, %zu at most, of %zu reserved\n", st->arena_used, st->arena_high_water,
           st->arena_capacity);
}

static void json_vec(rt_vec3 v)
{
    printf("[");
    rtp_json_number(stdout, d(v.x));
    printf(", ");
    rtp_json_number(stdout, d(v.y));
    printf(", ");
    rtp_json_number(stdout, d(v.z));
    printf("]");
}

static void print_json(const char *path, const rtp_scene *b, const rtp_scene_stats *st)
{
    const rt_scene *s = &b->scene;
    const rt_camera *cam = &s->camera;
    const rt_trace_settings *t = &cam->trace;
    printf("{\"scene\": ");
    rtp_json_string(stdout, path);
    printf(",\n \"nodes\": %u,\n \"primitives\": {\"spheres\": %u, \"cylinders\": %u, \"meshes\": %u, "
           "\"triangles\": %u, \"triangles_before_subdivision\": %llu},\n",
           st->nodes, st->spheres, st->cylinders, st->meshes, st->triangles, (unsigned long long)st->triangles_loaded);
    printf(" \"lights\": {\"point\": %u, \"directional\": %u, \"area\": %u},\n \"materials\": [",
           st->lights[RT_LIGHT_POINT], st->lights[RT_LIGHT_DIRECTIONAL], st->lights[RT_LIGHT_AREA]);
    for (uint32_t i = 0; i < s->material_count; i++) {
        printf(i ? ", " : "");
        rtp_json_string(stdout, b->loaded.material_names[i]);
    }
    printf("],\n \"textures\": [");
    for (uint32_t i = 0; i < s->texture_count; i++) {
        printf(i ? ", {\"name\": " : "{\"name\": ");
        rtp_json_string(stdout, b->loaded.texture_names[i]);
        printf(", \"width\": %u, \"height\": %u, \"bilinear\": %s}", s->textures[i].width, s->textures[i].height,
               s->textures[i].bilinear ? "true" : "false");
    }
    printf("],\n \"camera\": {\"perspective\": %s, \"fov_degrees\": ", cam->perspective ? "true" : "false");
    rtp_json_number(stdout, d(b->loaded.desc.camera.fov_degrees));
    printf(", \"ortho_width\": ");
    rtp_json_number(stdout, d(cam->ortho_width));
    printf(", \"width\": %u, \"height\": %u, \"eye\": ", cam->width, cam->height);
    json_vec(cam->eye);
    printf(", \"forward\": ");
    json_vec(cam->forward);
    printf(", \"up\": ");
    json_vec(cam->up);
    printf("},\n \"trace\": {\"max_depth\": %u, \"shadows\": \"%s\", \"reflections\": %s, \"refractions\": %s, "
           "\"samples_per_pixel\": %u, \"monte_carlo\": %u, \"focus_distance\": ",
           t->max_depth, shadow_modes[t->shadows], t->reflections ? "true" : "false", t->refractions ? "true" : "false",
           rt_camera_samples(cam), t->monte_carlo);
    rtp_json_number(stdout, d(t->focus_distance));
    printf(", \"aperture_size\": ");
    rtp_json_number(stdout, d(t->aperture_size));
    printf("},\n \"bvh\": {\"nodes\": %u, \"leaves\": %u, \"depth\": %u, \"sah_cost\": ", st->bvh_nodes, st->bvh_leaves,
           st->bvh_depth);
    rtp_json_number(stdout, st->sah_cost);
    printf("},\n \"arena\": {\"used\": %zu, \"high_water\": %zu, \"capacity\": %zu}\n}\n", st->arena_used,
           st->arena_high_water, st->arena_capacity);
}

int rtp_cmd_info(int argc, char **argv)
{
    info_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc != RTP_EXIT_OK) return rc;
    rtp_scene built;
    rc = rtp_cli_open_scene("info", a.scene, &a.build, &built);
    if (rc != RTP_EXIT_OK) return rc;
    rtp_scene_stats st;
    rtp_scene_stats_compute(&built, &st);
    if (a.json)
        print_json(a.scene, &built, &st);
    else
        print_text(a.scene, &built, &st);
    rtp_scene_close(&built);
    return RTP_EXIT_OK;
}

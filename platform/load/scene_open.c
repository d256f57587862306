/* Load + build with an arena that grows (up to what the memory cap leaves) until the scene fits. */
#include "load/scene_open.h"

#include "bvh.h"
#include "cli/exit_codes.h"
#include "load/input_file.h"
#include "mem/mem.h"
#include "thread/kernel.h"
#include "thread/pool.h"
#include <stdio.h>
#include <string.h>

static void apply_overrides(rt_scene_desc *d, const rtp_scene_options *opt)
{
    if (opt->width) d->camera.width = opt->width;
    if (opt->height) d->camera.height = opt->height;
    if (opt->depth >= 0) d->camera.trace.max_depth = (uint32_t)opt->depth;
    if (opt->aa >= 0) d->camera.trace.samples_per_pixel_index = (uint32_t)opt->aa;
}

static const char *object_name(const rtp_loaded_scene *l, uint32_t object)
{
    if (object >= l->desc.object_count) return NULL;
    uint32_t node = l->desc.objects[object].source;
    return node < l->node_count ? l->node_names[node] : NULL;
}

int rtp_load_failure_code(void)
{
    if (rtp_input_was_output()) return RTP_EXIT_USAGE;
    if (rtp_mem_refused()) return RTP_EXIT_MEMORY;
    return RTP_EXIT_INPUT;
}

/* What the cap leaves. */
static size_t room(void) { return rtp_mem_cap() - rtp_mem_in_use(); }

static int fail_memory(rtp_scene *out, const char *path, char *err, size_t err_size)
{
    snprintf(err, err_size, "%s: %s", path, rtp_mem_refusal());
    rtp_scene_close(out);
    return RTP_EXIT_MEMORY;
}

int rtp_scene_open(const char *path, const rtp_scene_options *opt, rtp_scene *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    const char *shown = strcmp(path, "-") ? path : "<stdin>";
    if (!rtp_scene_load(path, opt->assets_root, &out->loaded, err, err_size)) return rtp_load_failure_code();
    apply_overrides(&out->loaded.desc, opt);
    const rt_camera_desc *cam = &out->loaded.desc.camera;
    if (opt->with_image && !rtp_image_alloc(&out->image, cam->width, cam->height, "the output image"))
        return fail_memory(out, shown, err, err_size);
    /* The first try leaves half of what the cap leaves to what the command allocates
     * while the scene is held (a part's image and texts); later ones take what they need. */
    size_t size = (size_t)64 << 20;
    if (size > room() / 2) size = room() / 2;
    for (;;) {
        if (size > room()) size = room();
        out->memory = rtp_mem_alloc(size, "the scene arena");
        if (!out->memory) return fail_memory(out, shown, err, err_size);
        rt_arena_init(&out->arena, out->memory, size);
        rt_build_error be;
        rtp_pool *pool = rtp_pool_open(opt->threads);
        rt_status st = rt_scene_build(&out->loaded.desc, &out->arena, rtp_pool_workers(pool), &out->scene, &be);
        rtp_pool_close(pool);
        if (st == RT_OK) {
            rt_bvh_set_kernel(&out->scene.bvh, opt->kernel_forced ? opt->kernel : rtp_kernel_best());
            return RTP_EXIT_OK;
        }
        rtp_mem_free(out->memory);
        out->memory = NULL;
        if (st == RT_ERR_NOMEM && size < room()) {
            size_t grown = out->arena.wanted > size ? out->arena.wanted : size;
            size = grown > room() / 2 ? room() : grown * 2;
            continue;
        }
        const char *name = object_name(&out->loaded, be.object);
        char cap[32], used[32];
        if (st == RT_ERR_NOMEM)
            snprintf(err, err_size, "%s: the scene needs more than --max-memory (%s): %s (%s in use besides)", shown,
                     rtp_mem_describe(rtp_mem_cap(), cap, sizeof cap), be.what,
                     rtp_mem_describe(rtp_mem_in_use(), used, sizeof used));
        else if (name)
            snprintf(err, err_size, "%s: node '%s': %s", shown, name, be.what);
        else
            snprintf(err, err_size, "%s: %s", shown, be.what);
        rtp_scene_close(out);
        return st == RT_ERR_NOMEM ? RTP_EXIT_MEMORY : RTP_EXIT_INPUT;
    }
}

void rtp_scene_close(rtp_scene *b)
{
    rtp_mem_free(b->memory);
    b->memory = NULL;
    rtp_image_free(&b->image);
    rtp_scene_unload(&b->loaded);
}

rtp_scene_options rtp_scene_default_options(void)
{
    rtp_scene_options o = {0};
    /* 4 GiB, or all a 32-bit size_t can count (wasm32), where 4 << 30 would wrap to 0. */
    o.max_memory = (uint64_t)4 << 30 > SIZE_MAX ? SIZE_MAX : (size_t)((uint64_t)4 << 30);
    o.depth = -1;
    o.aa = -1;
    return o;
}

/* Load + build with an arena that grows (up to the memory cap) until the scene fits. */
#include "load/scene_open.h"

#include "bvh.h"
#include "cli/exit_codes.h"
#include "thread/kernel.h"
#include "thread/threads.h"
#include <stdio.h>
#include <stdlib.h>

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

int rtp_scene_open(const char *path, const rtp_scene_options *opt, rtp_scene *out, char *err, size_t err_size)
{
    out->memory = NULL;
    if (!rtp_scene_load(path, opt->assets_root, &out->loaded, err, err_size)) return RTP_EXIT_INPUT;
    apply_overrides(&out->loaded.desc, opt);
    size_t size = (size_t)64 << 20;
    for (;;) {
        if (size > opt->max_memory) size = opt->max_memory;
        out->memory = malloc(size);
        if (!out->memory) {
            snprintf(err, err_size, "%s: cannot allocate %zu MiB for the scene", path, size >> 20);
            rtp_scene_unload(&out->loaded);
            return RTP_EXIT_MEMORY;
        }
        rt_arena_init(&out->arena, out->memory, size);
        rt_build_error be;
        rt_workers workers = rtp_threads_workers(opt->threads);
        rt_status st = rt_scene_build(&out->loaded.desc, &out->arena, &workers, &out->scene, &be);
        if (st == RT_OK) {
            rt_bvh_set_kernel(&out->scene.bvh, opt->kernel_forced ? opt->kernel : rtp_kernel_best());
            return RTP_EXIT_OK;
        }
        free(out->memory);
        out->memory = NULL;
        if (st == RT_ERR_NOMEM && size < opt->max_memory) {
            size_t grown = out->arena.wanted > size ? out->arena.wanted : size;
            size = grown > opt->max_memory / 2 ? opt->max_memory : grown * 2;
            continue;
        }
        const char *name = object_name(&out->loaded, be.object);
        /* In bytes when the cap is not whole MiB, so --max-memory 1K does not read "0 MiB". */
        bool mib = opt->max_memory % ((size_t)1 << 20) == 0;
        if (st == RT_ERR_NOMEM)
            snprintf(err, err_size, "%s: the scene needs more than --max-memory (%zu %s): %s", path,
                     mib ? opt->max_memory >> 20 : opt->max_memory, mib ? "MiB" : "bytes", be.what);
        else if (name)
            snprintf(err, err_size, "%s: node '%s': %s", path, name, be.what);
        else
            snprintf(err, err_size, "%s: %s", path, be.what);
        rtp_scene_unload(&out->loaded);
        return st == RT_ERR_NOMEM ? RTP_EXIT_MEMORY : RTP_EXIT_INPUT;
    }
}

void rtp_scene_close(rtp_scene *b)
{
    free(b->memory);
    b->memory = NULL;
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

/* The hosted half of the public API (include/rtk.h): the scene loader, threads, image
 * files and the debugger's JSON, over the same code the `rtk` command runs. */
#include "blob.h"
#include "cli/exit_codes.h"
#include "debug/debug_output.h"
#include "image/image.h"
#include "load/scene_open.h"
#include "mem/mem.h"
#include "rtk_scene.h"
#include "thread/threads.h"
#include <stdio.h>
#include <stdlib.h>

/* A scene from rtk_open: the public handle and the file's loaded and built scene. */
typedef struct {
    struct rtk_scene handle;
    rtp_scene opened;
} hosted_scene;

static rtk_status status_of_exit(int exit_code)
{
    switch (exit_code) {
    case RTP_EXIT_OK: return RTK_OK;
    case RTP_EXIT_MEMORY: return RTK_ERR_NOMEM;
    case RTP_EXIT_OUTPUT: return RTK_ERR_OUTPUT;
    case RTP_EXIT_INTERRUPTED: return RTK_ERR_INTERRUPTED;
    default: return RTK_ERR_INPUT;
    }
}

rtk_options rtk_default_options(void)
{
    rtp_scene_options d = rtp_scene_default_options();
    return (rtk_options){.assets = d.assets_root,
                         .max_memory = d.max_memory,
                         .width = d.width,
                         .height = d.height,
                         .depth = d.depth,
                         .aa = d.aa,
                         .threads = d.threads};
}

rtk_status rtk_open(const char *path, const rtk_options *options, rtk_scene **out, char *err, size_t err_size)
{
    rtk_options o = options ? *options : rtk_default_options();
    if ((o.depth < -1 || o.depth > RT_MAX_RECURSION_DEPTH) || o.aa < -1 || o.aa > RT_MAX_SPP_INDEX ||
        o.width > RT_MAX_IMAGE_SIDE || o.height > RT_MAX_IMAGE_SIDE) {
        snprintf(err, err_size, "%s: rtk_options out of range (depth -1..64, aa -1..7, width and height 0..16384)",
                 path);
        return RTK_ERR_INVALID;
    }
    hosted_scene *s = malloc(sizeof *s);
    if (!s) {
        snprintf(err, err_size, "%s: out of memory", path);
        return RTK_ERR_NOMEM;
    }
    rtp_scene_options opt = {.assets_root = o.assets,
                             .max_memory = o.max_memory,
                             .width = o.width,
                             .height = o.height,
                             .depth = o.depth,
                             .aa = o.aa,
                             .threads = o.threads};
    /* The loader counts its memory through rtp_mem against one process-wide cap, which the
     * library does not otherwise set: for this open, the cap is what is held now plus
     * opt.max_memory, so other scenes the program holds do not count against it. */
    size_t cap = rtp_mem_cap(), held = rtp_mem_in_use();
    rtp_mem_forget_refusal(); /* an earlier open's refusal is not this one's */
    rtp_mem_set_cap(o.max_memory > SIZE_MAX - held ? SIZE_MAX : held + o.max_memory);
    int rc = rtp_scene_open(path, &opt, &s->opened, err, err_size);
    rtp_mem_set_cap(cap);
    if (rc != RTP_EXIT_OK) {
        free(s);
        return status_of_exit(rc);
    }
    s->handle.scene = &s->opened.scene;
    s->handle.host = s;
    *out = &s->handle;
    return RTK_OK;
}

void rtk_close(rtk_scene *scene)
{
    if (!scene || !scene->host) return;
    hosted_scene *s = scene->host;
    rtp_scene_close(&s->opened);
    free(s);
}

rtk_status rtk_render(const rtk_scene *scene, uint32_t threads, uint8_t *rgb)
{
    rt_tracer tracer = {.scene = scene->scene, .use_bvh = true};
    rtp_threads_options opt = {.threads = threads};
    return rtp_threads_render(&tracer, &opt, rgb) ? RTK_OK : RTK_ERR_NOMEM;
}

rtk_status rtk_pack(const rtk_scene *scene, void **blob, size_t *blob_size)
{
    if (!scene->host) return RTK_ERR_INVALID;
    const rt_scene_desc *desc = &((const hosted_scene *)scene->host)->opened.loaded.desc;
    size_t size = rt_blob_size(desc);
    uint8_t *bytes = malloc(size);
    if (!bytes) return RTK_ERR_NOMEM;
    rt_blob_write(desc, bytes, size);
    *blob = bytes;
    *blob_size = size;
    return RTK_OK;
}

rtk_status rtk_write_image(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height, char *err,
                           size_t err_size)
{
    rtp_image img = {width, height, (uint8_t *)rgb};
    return rtp_image_write(path, &img, err, err_size) ? RTK_OK : RTK_ERR_OUTPUT;
}

char *rtk_debug_pixel_json(const rtk_scene *scene, uint32_t x, uint32_t y, uint32_t sample, char *err, size_t err_size)
{
    const rt_camera *cam = &scene->scene->camera;
    if (!scene->host) {
        snprintf(err, err_size, "rtk_debug_pixel_json: a scene made from a blob has no names to show");
        return NULL;
    }
    if (x >= cam->width || y >= cam->height || (sample != RTK_ALL_SAMPLES && sample >= rt_camera_samples(cam))) {
        snprintf(err, err_size, "rtk_debug_pixel_json: no pixel (%u, %u) sample %u in a %ux%u image of %u samples", x,
                 y, sample, cam->width, cam->height, rt_camera_samples(cam));
        return NULL;
    }
    const rtp_scene *opened = &((const hosted_scene *)scene->host)->opened;
    rtp_pixel_trace pt;
    char *text = NULL;
    size_t size = 0;
    FILE *out = NULL;
    if (rtp_pixel_trace_run(&pt, opened, x, y, sample, RTP_PIXEL_TRACE_CAPACITY)) {
        out = open_memstream(&text, &size);
        if (out) {
            rtp_debug_print_json(out, &pt);
            if (fclose(out) != 0) {
                free(text);
                text = NULL;
            }
        }
        rtp_pixel_trace_free(&pt);
    }
    if (!text) snprintf(err, err_size, "rtk_debug_pixel_json: out of memory");
    return text;
}

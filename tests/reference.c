/* Test helpers for rendering corpus scenes; see reference.h. */
#include "reference.h"

#include "load/scene_open.h"
#include "thread/threads.h"
#include <stdio.h>
#include <stdlib.h>

const char *rt_test_trace_dir(void)
{
    static char path[4096];
    const char *shared = getenv("RTK_SHARED");
    snprintf(path, sizeof path, "%s/cse457/assets/trace", shared ? shared : "../shared");
    return path;
}

bool rt_test_render(const char *scene_path, unsigned threads, bool use_bvh, rtp_image *out, char *err, size_t err_size)
{
    rtp_scene_options opt = {0};
    opt.max_memory = (size_t)4 << 30;
    opt.depth = -1;
    opt.aa = -1;
    rtp_scene built;
    if (rtp_scene_open(scene_path, &opt, &built, err, err_size) != 0) return false;
    out->width = built.scene.camera.width;
    out->height = built.scene.camera.height;
    out->rgb = calloc((size_t)out->width * out->height, 3);
    rt_tracer tracer = {.scene = &built.scene, .use_bvh = use_bvh};
    rtp_threads_options popt = {threads, 0, false, NULL};
    bool ok = out->rgb && rtp_threads_render(&tracer, &popt, out->rgb);
    rtp_scene_close(&built);
    if (!ok) {
        snprintf(err, err_size, "%s: render failed", scene_path);
        rtp_image_free(out);
    }
    return ok;
}

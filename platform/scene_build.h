/* Loads a scene file and builds it into an arena: the step every subcommand shares. */
#ifndef RT_SCENE_BUILD_H
#define RT_SCENE_BUILD_H

#include <stddef.h>
#include "scene_load.h"

typedef struct {
    const char *assets_root; /* NULL: found from the scene file's location */
    size_t max_memory;       /* arena cap in bytes */
    /* Overrides applied to the file's camera when non-zero / non-negative. */
    uint32_t width, height;
    int32_t depth;           /* -1: keep the file's Maximum Recursion Depth */
    int32_t aa;              /* -1: keep the file's Samples Per Pixel index */
    uint32_t threads;        /* for the BVH build; 0: one per online CPU */
    bool kernel_forced;      /* run `kernel` (which must run here, see kernel.h), not the best */
    rt_kernel kernel;
} rt_build_options;

typedef struct {
    rt_loaded_scene loaded;
    rt_scene scene;
    void *memory; /* the arena's memory */
    rt_arena arena;
} rt_built_scene;

/* On failure prints nothing and returns an RT_EXIT_* code with one line in err. */
int rt_scene_open(const char *path, const rt_build_options *opt, rt_built_scene *out, char *err, size_t err_size);
void rt_scene_close(rt_built_scene *b);

#endif

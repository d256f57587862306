/* Loads a scene file and builds it into an arena: the step every subcommand shares. */
#ifndef RTP_SCENE_OPEN_H
#define RTP_SCENE_OPEN_H

#include "load/scene_load.h"
#include <stddef.h>

typedef struct {
    const char *assets_root; /* NULL: found from the scene file's location */
    size_t max_memory;       /* arena cap in bytes */
    /* Overrides applied to the file's camera when non-zero / non-negative. */
    uint32_t width, height;
    int32_t depth;      /* -1: keep the file's Maximum Recursion Depth */
    int32_t aa;         /* -1: keep the file's Samples Per Pixel index */
    uint32_t threads;   /* for the BVH build; 0: one per online CPU */
    bool kernel_forced; /* run `kernel` (which must run here, see kernel.h), not the best */
    rt_kernel kernel;
} rtp_scene_options;

typedef struct {
    rtp_loaded_scene loaded;
    rt_scene scene;
    void *memory; /* the arena's memory */
    rt_arena arena;
} rtp_scene;

/* The options' defaults: the file's values kept, a 4 GiB memory cap. */
rtp_scene_options rtp_scene_default_options(void);

/* On failure prints nothing and returns an RTP_EXIT_* code with one line in err. */
int rtp_scene_open(const char *path, const rtp_scene_options *opt, rtp_scene *out, char *err, size_t err_size);
void rtp_scene_close(rtp_scene *b);

#endif

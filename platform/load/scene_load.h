/* The CSE457 YAML scene loader: one file (plus the meshes and textures it names)
 * in, one rt_scene_desc out. */
#ifndef RTP_SCENE_LOAD_H
#define RTP_SCENE_LOAD_H

#include "scene.h"
#include <stddef.h>

#define RTP_ERR_SIZE 1024

/* Everything a loaded scene owns. desc points into the other fields. */
typedef struct {
    rt_scene_desc desc;
    /* Node names indexed by rt_object_desc.source (for the debugger and `rtk info`). */
    char **node_names;
    uint32_t node_count;
    /* Names of desc.materials[i] and desc.textures[i], as the file's sections call them. */
    char **material_names;
    char **texture_names;
    /* The paths of the asset files read, as opened, in the order read (textures, then
     * meshes): what a distributed part digests besides the scene file. */
    char **asset_paths;
    uint32_t asset_count;
    /* Owned storage behind desc (materials, textures, meshes, objects, lights...). */
    void *storage;
} rtp_loaded_scene;

/* Loads path. assets_root is the folder that contains assets/, or NULL to find it from
 * the scene file's location (format.md §3). On failure returns false with one line in err
 * (no newline) such as "scene.yaml:12:9: Shininess: expected a number, got 'abc'" or
 * "scene.yaml:40:17: Meshes/Knight/Path: cannot open '/x/assets/knight.ply': No such file
 * or directory"; *out is then empty and needs no free. */
bool rtp_scene_load(const char *path, const char *assets_root, rtp_loaded_scene *out, char *err, size_t err_size);
void rtp_scene_unload(rtp_loaded_scene *scene);

#endif

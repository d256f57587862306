/* `rtk pack`: a scene file (and its meshes and textures) as one scene blob (core/blob.h),
 * for renderers without a file system or YAML parser: cross-compiled test drivers and
 * the bare-metal image. */
#include "pack_cmd.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "blob.h"
#include "cli.h"
#include "exit_codes.h"
#include "image.h"

static const char usage[] =
    "usage: rtk pack SCENE.yaml -o OUT.rtscene [options]\n"
    "\n"
    "Writes the scene, with its meshes and textures and the overrides below applied, as\n"
    "one blob that core/blob.h reads. The blob holds this build's scalar type (double or\n"
    "fixed): a build of the other type rejects it.\n"
    "\n"
    "  -o, --output FILE   the blob to write (atomically)\n"
    RT_SCENE_OPTIONS_HELP
    "\n"
    "Exit codes: 0 ok, 2 bad arguments, 3 bad or missing input file, 4 output not\n"
    "writable, 5 over the memory cap.\n";

int rt_cmd_pack(int argc, char **argv)
{
    rt_build_options build = rt_default_build_options();
    const char *scene = NULL, *output = NULL;
    for (int i = 1; i < argc; i++) {
        int common = rt_parse_common_option("pack", usage, argc, argv, &i, &build);
        if (common < 0) return -common;
        if (common > 0) continue;
        const char *arg = argv[i];
        if (!strcmp(arg, "-o") || !strcmp(arg, "--output")) {
            if (i + 1 >= argc) return rt_usage_error("pack", "missing file after", arg);
            output = argv[++i];
        } else {
            int rc = rt_take_scene_argument("pack", arg, &scene);
            if (rc != RT_EXIT_OK) return rc;
        }
    }
    if (!scene || !output) return rt_usage_error("pack", "give a scene file and -o FILE", NULL);
    rt_built_scene built;
    /* Building checks the scene as a render would, so a blob always renders. */
    int rc = rt_open_scene_or_report("pack", scene, &build, &built);
    if (rc != RT_EXIT_OK) return rc;
    char err[RT_ERR_SIZE];
    size_t size = rt_blob_size(&built.loaded.desc);
    uint8_t *bytes = malloc(size);
    if (!bytes || rt_blob_write(&built.loaded.desc, bytes, size) != size) {
        fprintf(stderr, "rtk pack: %s: no memory for a %zu-byte blob\n", scene, size);
        rc = RT_EXIT_MEMORY;
    } else if (!rt_write_file_atomic(output, bytes, size, err, sizeof err)) {
        fprintf(stderr, "rtk pack: %s\n", err);
        rc = RT_EXIT_OUTPUT;
    }
    free(bytes);
    rt_scene_close(&built);
    return rc;
}

/* `rtk pack`: a scene file (and its meshes and textures) as one scene blob (core/blob.h),
 * for renderers without a file system or YAML parser: cross-compiled test drivers and
 * the bare-metal image. */
#include "cli/pack_cmd.h"

#include "blob.h"
#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "image/file_write.h"
#include "image/image.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] = "usage: rtk pack SCENE.yaml -o OUT.rtscene [options]\n"
                            "\n"
                            "Writes the scene, with its meshes and textures and the overrides below applied, as\n"
                            "one blob that core/blob.h reads. The blob holds this build's scalar type (double or\n"
                            "fixed): a build of the other type rejects it.\n"
                            "\n"
                            "  -o, --output FILE   the blob to write (atomically)\n" RTP_CLI_SCENE_OPTIONS_HELP "\n"
                            "Exit codes: 0 ok, 2 bad arguments, 3 bad or missing input file, 4 output not\n"
                            "writable, 5 over the memory cap.\n";

int rtp_cmd_pack(int argc, char **argv)
{
    rtp_scene_options build = rtp_scene_default_options();
    const char *scene = NULL, *output = NULL;
    for (int i = 1; i < argc; i++) {
        int common = rtp_cli_common_option("pack", usage, argc, argv, &i, &build);
        if (common < 0) return -common;
        if (common > 0) continue;
        const char *arg = argv[i];
        if (!strcmp(arg, "-o") || !strcmp(arg, "--output")) {
            if (i + 1 >= argc) return rtp_cli_usage_error("pack", "missing file after", arg);
            output = argv[++i];
        } else {
            int rc = rtp_cli_scene_argument("pack", arg, &scene);
            if (rc != RTP_EXIT_OK) return rc;
        }
    }
    if (!scene || !output) return rtp_cli_usage_error("pack", "give a scene file and -o FILE", NULL);
    rtp_scene built;
    /* Building checks the scene as a render would, so a blob always renders. */
    int rc = rtp_cli_open_scene("pack", scene, &build, &built);
    if (rc != RTP_EXIT_OK) return rc;
    char err[RTP_ERR_SIZE];
    size_t size = rt_blob_size(&built.loaded.desc);
    uint8_t *bytes = malloc(size);
    if (!bytes || rt_blob_write(&built.loaded.desc, bytes, size) != size) {
        fprintf(stderr, "rtk pack: %s: no memory for a %zu-byte blob\n", scene, size);
        rc = RTP_EXIT_MEMORY;
    } else if (!rtp_file_write_atomic(output, bytes, size, err, sizeof err)) {
        fprintf(stderr, "rtk pack: %s\n", err);
        rc = RTP_EXIT_OUTPUT;
    }
    free(bytes);
    rtp_scene_close(&built);
    return rc;
}

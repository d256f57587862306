/* libFuzzer target: the YAML scene loader (platform/load/scene_load.c over libyaml) on
 * arbitrary bytes, with an assets/ folder holding the few small files the seed
 * scenes name. It must refuse with a message or return a description that
 * rt_scene_build reads without a sanitizer report; never crash, never leak. */
#include "check.h"
#include "fixture.h"
#include "image/image.h"
#include "load/scene_load.h"
#include "scratch.h"

static const char tetrahedron_ply[] =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    static uint8_t texels[2 * 2 * 3] = {255, 255, 255, 0, 0, 0, 0, 0, 0, 255, 255, 255};
    rtp_image checkers = {2, 2, texels};
    char err[512];
    const char *textures[] = {"assets/checkers.png", "assets/trace/simple/texture-checkerboard.png"};
    for (int i = 0; i < 2; i++) {
        const char *path = fz_scratch_write(textures[i], "", 0);
        FZ_CHECK(rtp_image_write(path, &checkers, err, sizeof err), "%s", err);
    }
    fz_scratch_write("assets/trace/simple/poly-sphere.ply", tetrahedron_ply, sizeof tetrahedron_ply - 1);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_scratch_write("scene.yaml", data, size);
    rtp_loaded_scene loaded;
    char err[RTP_ERR_SIZE];
    if (!rtp_scene_load(path, fz_scratch_dir(), &loaded, err, sizeof err)) {
        FZ_CHECK(err[0] != 0, "refused without a message");
        return 0;
    }
    rt_scene scene;
    rt_build_error build_err;
    fz_build(&loaded.desc, &scene, &build_err);
    rtp_scene_unload(&loaded);
    return 0;
}

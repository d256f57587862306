/* libFuzzer target: the PLY reader (platform/load/ply.c, ply_body.c) on arbitrary bytes.
 * It must refuse with a message or return a mesh whose arrays match its counts and
 * whose indices are in range (rt_scene_build then reads all of it under ASan). */
#include "check.h"
#include "fixture.h"
#include "load/ply.h"
#include "oracle.h"
#include "scratch.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_scratch_write("input.ply", data, size);
    rtp_ply_mesh mesh;
    char err[512];
    if (!rtp_ply_read(path, &mesh, err, sizeof err)) {
        FZ_CHECK(err[0] != 0, "refused without a message");
        return 0;
    }
    for (uint32_t i = 0; i < 3 * mesh.triangle_count; i++)
        FZ_CHECK(mesh.indices[i] < mesh.vertex_count, "index %u of %u vertices", mesh.indices[i], mesh.vertex_count);
    for (uint32_t v = 0; v < mesh.vertex_count; v++)
        FZ_CHECK(fz_finite3(mesh.positions[v]), "vertex %u is not finite", v);
    rt_mesh_desc view = rtp_ply_view(&mesh);
    rt_scene scene;
    if (mesh.triangle_count > 0 && mesh.triangle_count < 4096 && mesh.vertex_count < 4096)
        fz_scene_one(&scene, RT_SHAPE_MESH, &view, rt_affine_identity());
    rtp_ply_free(&mesh);
    return 0;
}

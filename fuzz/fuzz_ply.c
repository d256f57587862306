/* libFuzzer target: the PLY reader (platform/load/ply.c, ply_body.c) on arbitrary bytes.
 * It must refuse with a message or return a mesh whose arrays match its counts and
 * whose indices are in range (rt_scene_build then reads all of it under ASan). And a
 * differential property: the mesh it returns, written as ASCII, binary little endian
 * and binary big endian PLY (fuzz/ply_write.c), reads back as the same mesh, bit for bit. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fixture.h"
#include "load/ply.h"
#include "oracle.h"
#include "ply_write.h"
#include "scratch.h"

/* Same bits, or NaN in both (the text form keeps a NaN but not its payload). */
static bool same_reals(const rt_real *a, const rt_real *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0 && !(a[i] != a[i] && b[i] != b[i])) return false;
    return true;
}

static void check_round_trip(const rtp_ply_mesh *mesh, fz_ply_format format)
{
    static const char *names[] = {"ASCII", "binary little endian", "binary big endian"};
    size_t size;
    char *bytes = fz_ply_write(mesh, format, &size);
    FZ_CHECK(bytes != NULL, "out of memory writing the mesh");
    const char *path = fz_scratch_write("again.ply", bytes, size);
    free(bytes);
    rtp_ply_mesh again;
    char err[512];
    FZ_CHECK(rtp_ply_read(path, &again, err, sizeof err), "the mesh written as %s is refused: %s", names[format], err);
    FZ_CHECK(again.vertex_count == mesh->vertex_count && again.triangle_count == mesh->triangle_count,
             "%s: %u vertices, %u triangles read back as %u, %u", names[format], mesh->vertex_count,
             mesh->triangle_count, again.vertex_count, again.triangle_count);
    FZ_CHECK(!mesh->normals == !again.normals && !mesh->uvs == !again.uvs, "%s: normals or uvs lost", names[format]);
    size_t v = mesh->vertex_count;
    FZ_CHECK(same_reals(&mesh->positions[0].x, &again.positions[0].x, 3 * v), "%s: positions differ", names[format]);
    FZ_CHECK(!mesh->normals || same_reals(&mesh->normals[0].x, &again.normals[0].x, 3 * v), "%s: normals differ",
             names[format]);
    FZ_CHECK(!mesh->uvs || same_reals(&mesh->uvs[0].u, &again.uvs[0].u, 2 * v), "%s: uvs differ", names[format]);
    FZ_CHECK(memcmp(mesh->indices, again.indices, 3 * sizeof *mesh->indices * mesh->triangle_count) == 0,
             "%s: indices differ", names[format]);
    rtp_ply_free(&again);
}

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
    if (mesh.vertex_count < 4096 && mesh.triangle_count < 4096)
        for (int f = FZ_PLY_ASCII; f <= FZ_PLY_BIG; f++) check_round_trip(&mesh, (fz_ply_format)f);
    rt_mesh_desc view = rtp_ply_view(&mesh);
    rt_scene scene;
    if (mesh.triangle_count > 0 && mesh.triangle_count < 4096 && mesh.vertex_count < 4096)
        fz_scene_one(&scene, RT_SHAPE_MESH, &view, rt_affine_identity());
    rtp_ply_free(&mesh);
    return 0;
}

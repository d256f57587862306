/* Loading is linear in the file's size, whatever the machine's speed: the CPU time of a
 * scene of 4N named materials, textures and meshes, each used once, is compared with
 * that of N (a linear loader: about 4 times; one that searches names linearly: 16), and
 * the flow-nesting bound of the YAML reader is checked at its edge. */
#include "load/scene_load.h"
#include "load/yaml_tree.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static char dir[64];

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "linear"), "cannot create a scratch folder"); }

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(linear_load, .init = setup, .fini = teardown);

static const uint8_t png_2x2[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00,
    0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd, 0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x12, 0x49,
    0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60, 0x60, 0x60, 0x00, 0x42, 0x06, 0x28, 0x0d, 0x00, 0x00, 0x18, 0x00, 0x01,
    0x3b, 0xc5, 0x9d, 0x33, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

static void put_assets(void)
{
    char path[128];
    snprintf(path, sizeof path, "%s/t.png", dir);
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    fwrite(png_2x2, 1, sizeof png_2x2, f);
    fclose(f);
    snprintf(path, sizeof path, "%s/m.ply", dir);
    f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
          f);
    fclose(f);
}

/* n textures, materials and meshes, and n objects each naming one of each. */
static void put_scene(const char *path, int n)
{
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs("Textures:\n", f);
    for (int i = 0; i < n; i++) fprintf(f, "    T%d: {Path: t.png}\n", i);
    fputs("Meshes:\n", f);
    for (int i = 0; i < n; i++) fprintf(f, "    M%d: {Path: m.ply}\n", i);
    fputs("Materials:\n", f);
    for (int i = 0; i < n; i++)
        fprintf(f, "    X%d: {Shader: Blinn-Phong Shader, Uniforms: {Diffuse: {Use Texture: true, Color Map: T%d}}}\n",
                i, n - 1 - i);
    fputs("Root:\n    Name: Root\n    Children:\n", f);
    for (int i = 0; i < n; i++)
        fprintf(f, "        - {Name: N%d, Components: {TriangleMesh: {Mesh: M%d, Material: X%d}}}\n", i, i, n - 1 - i);
    fclose(f);
}

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* The least CPU time of three loads of a scene of n of each. */
static double load_seconds(int n)
{
    char path[128], err[RTP_ERR_SIZE];
    snprintf(path, sizeof path, "%s/scene%d.yaml", dir, n);
    put_scene(path, n);
    double best = 1e30;
    for (int run = 0; run < 3; run++) {
        rtp_loaded_scene scene;
        double start = cpu_seconds();
        cr_assert(rtp_scene_load(path, dir, &scene, err, sizeof err), "%s", err);
        double took = cpu_seconds() - start;
        cr_assert_eq(scene.desc.object_count, (uint32_t)n);
        cr_assert_eq(scene.desc.texture_count, (uint32_t)n);
        rtp_scene_unload(&scene);
        best = took < best ? took : best;
    }
    return best;
}

Test(linear_load, names_are_looked_up_in_constant_time, .timeout = 120)
{
    put_assets();
    double small = load_seconds(5000), large = load_seconds(20000);
    cr_log_info("5000 of each: %.3f s, 20000: %.3f s, ratio %.2f", small, large, large / small);
    cr_expect_lt(large / small, 8.0, "4 times the names took %.1f times as long (linear: 4, quadratic: 16)",
                 large / small);
}

/* The sum of the flow depths over the events may reach 16 per byte plus 16M. */
Test(linear_load, flow_nesting_is_bounded_by_the_work_it_costs)
{
    char err[512];
    rtp_yaml_tree tree;
    /* 2000 levels: about 4 million of work in a 4 KB file: accepted. */
    size_t depth = 2000, size = 2 * depth + 2;
    uint8_t *text = malloc(1 << 22);
    memset(text, '[', depth);
    text[depth] = 'a';
    memset(text + depth + 1, ']', depth);
    cr_expect(rtp_yaml_tree_parse(text, size - 1, "deep.yaml", &tree, err, sizeof err), "%s", err);
    rtp_yaml_tree_free(&tree);
    /* 4000 levels around a million scalars (2 MB): 4e9 of work, refused before. */
    size = 0;
    memset(text, '[', 4000);
    size += 4000;
    for (int i = 0; i < 1000000; i++, size += 2) memcpy(text + size, "a,", 2);
    text[size++] = 'a';
    memset(text + size, ']', 4000);
    size += 4000;
    cr_expect_not(rtp_yaml_tree_parse(text, size, "wide.yaml", &tree, err, sizeof err));
    cr_expect(strstr(err, "nested too deeply for the file's size"), "%s", err);
    free(text);
}

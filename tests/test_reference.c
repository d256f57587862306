/* Renders every corpus scene that has a solution image and compares: the fidelity
 * floor of the issue (>= 40 dB and >= 99% of channels within 2 levels). The rows
 * printed here are the PSNR table quoted in the README. */
#include "image/image_compare.h"
#include "reference.h"
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    char scene[64];    /* path under the trace folder, without .yaml */
    char solution[64]; /* file under solution/ */
} reference_case;

static reference_case cases[] = {
    {"simple/box", "box_3.png"},
    {"simple/box_cyl_opaque_shadow", "box_cyl_opaque_shadow_3.png"},
    {"simple/box_cyl_reflect", "box_cyl_reflect_3.png"},
    {"simple/box_cyl_trans_shadow", "box_cyl_trans_shadow_3.png"},
    {"simple/box_dist_atten", "box_dist_atten_3.png"},
    {"simple/cube_transparent", "cube_transparent_3.png"},
    {"simple/cyl_ambient", "cyl_ambient_3.png"},
    {"simple/cyl_diff_spec", "cyl_diff_spec_3.png"},
    {"simple/cyl_diffuse", "cyl_diffuse_3.png"},
    {"simple/cyl_emissive", "cyl_emissive_3.png"},
    {"simple/cylinder_refract", "cylinder_refract_3.png"},
    {"simple/poly_sphere", "poly_sphere_3.png"},
    {"simple/sphere_refract", "sphere_refract_3.png"},
    {"simple/texture_reflection", "texture_reflection_3.png"},
};

ParameterizedTestParameters(reference, matches_solution)
{
    return cr_make_param_array(reference_case, cases, sizeof cases / sizeof cases[0]);
}

ParameterizedTest(reference_case *c, reference, matches_solution)
{
    char scene[4096], solution[4096], err[1024];
    snprintf(scene, sizeof scene, "%s/%s.yaml", rt_test_trace_dir(), c->scene);
    snprintf(solution, sizeof solution, "%s/solution/%s", rt_test_trace_dir(), c->solution);
    rtp_image ours, theirs;
    cr_assert(rt_test_render(scene, 1, true, &ours, err, sizeof err), "%s", err);
    cr_assert(rtp_image_read(solution, &theirs, err, sizeof err), "%s", err);
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&ours, &theirs, &m), "%s: size %ux%u vs solution %ux%u", c->scene, ours.width,
              ours.height, theirs.width, theirs.height);
    fprintf(stderr, "reference: %-30s PSNR %7.2f dB  within 1: %8.4f%%  within 2: %8.4f%%  max diff %3u\n", c->scene,
            m.psnr, m.within1_pct, m.within2_pct, m.max_diff);
    cr_expect(m.psnr >= 40.0, "%s: PSNR %.2f dB < 40 dB", c->scene, m.psnr);
    cr_expect(m.within2_pct >= 99.0, "%s: only %.3f%% of channels within 2 levels", c->scene, m.within2_pct);
    rtp_image_free(&ours);
    rtp_image_free(&theirs);
}

/* The two solution scenes whose assets the corpus lacks fail with a clear message. */
Test(reference, missing_assets_are_named)
{
    const char *scenes[2] = {"trimeshes/dragon", "trimeshes/revolution_texture"};
    const char *files[2] = {"assets/dragon.ply", "assets/marble.png"};
    for (int i = 0; i < 2; i++) {
        char scene[4096], err[1024] = "";
        snprintf(scene, sizeof scene, "%s/%s.yaml", rt_test_trace_dir(), scenes[i]);
        rtp_image img;
        cr_assert_not(rt_test_render(scene, 1, true, &img, err, sizeof err), "%s rendered", scenes[i]);
        cr_expect(strstr(err, files[i]) != NULL, "message for %s does not name %s: %s", scenes[i], files[i], err);
    }
}

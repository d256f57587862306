/* Renders every corpus scene that has a solution image and holds it to floors set
 * just under what this build measures (README, "Fidelity to the sample solution"):
 * PSNR at most about 1 dB under the measured value, every channel within 1 level of
 * the solution except on the pixels listed for the scene (counted, by position), and a
 * bound on the largest difference. A regression of a few tenths of a dB fails, so a
 * re-bless cannot hide one. The rows printed here are the README's table. The Monte
 * Carlo scene cornell_ray is judged by statistics instead: PSNR at full resolution and
 * after 4x4 box averaging (format.md §11.4, docs/montecarlo.md). */
#include "image/image_compare.h"
#include "reference.h"
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Floors for cornell_ray, a little under what both builds measure (docs/montecarlo.md). */
#define CORNELL_FULL_FLOOR 32.0
#define CORNELL_AVERAGED_FLOOR 44.0

#define MAX_EXCEPTIONS 4

typedef struct {
    uint16_t x, y;
} pixel_at;

/* Floors of one build. psnr INFINITY: the render must equal the solution. */
typedef struct {
    double psnr;                  /* dB */
    unsigned max_diff;            /* levels */
    pixel_at off[MAX_EXCEPTIONS]; /* the only pixels allowed more than 1 level off */
    unsigned off_count;
} floors;

/* Whitted scenes, judged by the within-1-level rules; each build its own floors, from
 * its own measurement (targets/fixed_vs_double.sh says how the builds differ). Monte
 * Carlo scenes are judged by statistics instead, in a table of their own. */
typedef struct {
    char scene[64];    /* path under the trace folder, without .yaml */
    char solution[64]; /* file under solution/ */
    floors dbl, fixed;
} reference_case;

#define SAME \
    (floors) { INFINITY, 0, {{0, 0}}, 0 }
#define ONE_LEVEL(db) \
    (floors) { (db), 1, {{0, 0}}, 0 }

/* The silhouette pixels of the shadow through the transparent box, and of the glass. */
#define TRANS_SHADOW \
    (floors) { 82.1, 11, {{254, 201}, {257, 201}}, 2 }
#define REFRACT \
    (floors) { 58.9, 204, {{331, 416}}, 1 }

/* Measured on this tree (both builds; identical where the two columns agree), floors
 * about 1 dB under it. The off pixels sit on silhouettes where the solution's single
 * precision hits and rtk's double (or Q32.32) misses, or the reverse. */
static reference_case cases[] = {
    {"simple/box", "box_3.png", ONE_LEVEL(100.0), ONE_LEVEL(100.0)},                                     /* 101.07 */
    {"simple/box_cyl_opaque_shadow", "box_cyl_opaque_shadow_3.png", ONE_LEVEL(100.0), ONE_LEVEL(100.0)}, /* 101.07 */
    {"simple/box_cyl_reflect", "box_cyl_reflect_3.png", ONE_LEVEL(106.0), ONE_LEVEL(106.0)},             /* 107.09 */
    /* 83.14, two pixels 11 levels off */
    {"simple/box_cyl_trans_shadow", "box_cyl_trans_shadow_3.png", TRANS_SHADOW, TRANS_SHADOW},
    {"simple/box_dist_atten", "box_dist_atten_3.png", SAME, SAME},
    {"simple/cube_transparent", "cube_transparent_3.png", SAME, SAME},
    {"simple/cyl_ambient", "cyl_ambient_3.png", SAME, SAME},
    {"simple/cyl_diff_spec", "cyl_diff_spec_3.png", ONE_LEVEL(101.3), ONE_LEVEL(101.3)}, /* 102.32 */
    {"simple/cyl_diffuse", "cyl_diffuse_3.png", ONE_LEVEL(106.0), SAME},                 /* 107.09; fixed identical */
    {"simple/cyl_emissive", "cyl_emissive_3.png", SAME, SAME},
    {"simple/cylinder_refract", "cylinder_refract_3.png", REFRACT, REFRACT},         /* 59.93, one pixel 204 off */
    {"simple/poly_sphere", "poly_sphere_3.png", ONE_LEVEL(106.0), ONE_LEVEL(106.0)}, /* 107.09 */
    {"simple/sphere_refract", "sphere_refract_3.png", REFRACT, REFRACT},             /* 59.93, one pixel 204 off */
    /* 81.30; fixed 81.32 */
    {"simple/texture_reflection", "texture_reflection_3.png", ONE_LEVEL(80.3), ONE_LEVEL(80.3)},
};

ParameterizedTestParameters(reference, matches_solution)
{
    return cr_make_param_array(reference_case, cases, sizeof cases / sizeof cases[0]);
}

static bool listed(const floors *f, uint32_t x, uint32_t y)
{
    for (unsigned i = 0; i < f->off_count; i++)
        if (f->off[i].x == x && f->off[i].y == y) return true;
    return false;
}

/* Fails on every pixel more than 1 level off that f does not list; returns how many
 * pixels are more than 1 level off in all. */
static unsigned check_pixels(const char *scene, const floors *f, const rtp_image *ours, const rtp_image *theirs)
{
    unsigned off = 0;
    for (uint32_t y = 0; y < ours->height; y++)
        for (uint32_t x = 0; x < ours->width; x++) {
            const uint8_t *a = ours->rgb + 3 * ((size_t)y * ours->width + x), *b = theirs->rgb + (a - ours->rgb);
            unsigned most = 0;
            for (int c = 0; c < 3; c++) {
                unsigned d = (unsigned)abs((int)a[c] - (int)b[c]);
                most = d > most ? d : most;
            }
            if (most <= 1) continue;
            off++;
            fprintf(stderr, "reference: %s: pixel (%u, %u) is %u levels off: %u %u %u, solution %u %u %u\n", scene, x,
                    y, most, a[0], a[1], a[2], b[0], b[1], b[2]);
            cr_expect(listed(f, x, y), "%s: pixel (%u, %u) is %u levels off and not a listed exception", scene, x, y,
                      most);
        }
    return off;
}

ParameterizedTest(reference_case *c, reference, matches_solution)
{
#ifdef RT_REAL_FIXED
    const floors *f = &c->fixed;
#else
    const floors *f = &c->dbl;
#endif
    char scene[4096], solution[4096], err[1024];
    snprintf(scene, sizeof scene, "%s/%s.yaml", rt_test_trace_dir(), c->scene);
    snprintf(solution, sizeof solution, "%s/solution/%s", rt_test_trace_dir(), c->solution);
    rtp_image ours, theirs;
    cr_assert(rt_test_render(scene, 1, true, &ours, err, sizeof err), "%s", err);
    cr_assert(rtp_image_read(solution, &theirs, err, sizeof err), "%s", err);
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&ours, &theirs, &m), "%s: size %ux%u vs solution %ux%u", c->scene, ours.width,
              ours.height, theirs.width, theirs.height);
    unsigned off = check_pixels(c->scene, f, &ours, &theirs);
    fprintf(stderr,
            "reference: %-30s PSNR %7.2f dB (floor %.2f)  within 1: %8.4f%%  pixels > 1 level off: %u (%u listed)  "
            "max diff %3u (bound %u)\n",
            c->scene, m.psnr, f->psnr, m.within1_pct, off, f->off_count, m.max_diff, f->max_diff);
    cr_expect(m.psnr >= f->psnr, "%s: PSNR %.2f dB under its floor %.2f dB", c->scene, m.psnr, f->psnr);
    cr_expect(m.max_diff <= f->max_diff, "%s: a channel is %u levels off, bound %u", c->scene, m.max_diff, f->max_diff);
    rtp_image_free(&ours);
    rtp_image_free(&theirs);
}

/* PSNR of the 4x4 box averages of a and b (sizes multiples of 4), as tools/fidelity
 * computes it: the mean of each 4x4 block per channel, unrounded. */
static double box4_psnr(const rtp_image *a, const rtp_image *b)
{
    uint32_t w = a->width / 4, h = a->height / 4;
    double sq = 0;
    for (uint32_t by = 0; by < h; by++)
        for (uint32_t bx = 0; bx < w; bx++)
            for (int ch = 0; ch < 3; ch++) {
                double d = 0;
                for (uint32_t y = 4 * by; y < 4 * by + 4; y++)
                    for (uint32_t x = 4 * bx; x < 4 * bx + 4; x++) {
                        size_t i = ((size_t)y * a->width + x) * 3 + ch;
                        d += (double)a->rgb[i] - b->rgb[i];
                    }
                sq += (d / 16) * (d / 16);
            }
    return sq == 0 ? INFINITY : 10 * log10(255.0 * 255.0 * 3.0 * w * h / sq);
}

/* cornell_ray at its own settings (512x512, 64 samples, Monte Carlo 2) against the
 * solution's cornell_ray_5.png. A build renders the same bytes on every machine, so the
 * figures are exact: 32.23 dB at full resolution and 44.21 dB after 4x4 averaging, in
 * both builds (the fixed build's image differs in 3 pixels by one level). Without the light's cosine the
 * image scores 11.35 / 11.42 dB; with camera rays blind to the lights 22.73 / 23.53 dB. */
/* Under ASan the 512x512, 64-sample render takes minutes; there the path tracer's memory
 * is checked by test_montecarlo.c's small renders instead. */
#ifdef __SANITIZE_ADDRESS__
#define SLOW_UNDER_ASAN true
#else
#define SLOW_UNDER_ASAN false
#endif

Test(reference, monte_carlo_cornell_matches_solution_statistically, .timeout = 900, .disabled = SLOW_UNDER_ASAN)
{
    char scene[4096], solution[4096], err[1024];
    snprintf(scene, sizeof scene, "%s/more/cornell_ray.yaml", rt_test_trace_dir());
    snprintf(solution, sizeof solution, "%s/solution/cornell_ray_5.png", rt_test_trace_dir());
    rtp_image ours, theirs;
    cr_assert(rt_test_render(scene, 2, true, &ours, err, sizeof err), "%s", err);
    cr_assert(rtp_image_read(solution, &theirs, err, sizeof err), "%s", err);
    rtp_image_metrics m;
    cr_assert(rtp_image_compare(&ours, &theirs, &m), "size %ux%u vs solution %ux%u", ours.width, ours.height,
              theirs.width, theirs.height);
    double averaged = box4_psnr(&ours, &theirs);
    fprintf(stderr, "reference: %-30s PSNR %7.2f dB  4x4-averaged %7.2f dB (Monte Carlo)\n", "more/cornell_ray", m.psnr,
            averaged);
    cr_expect(m.psnr >= CORNELL_FULL_FLOOR, "PSNR %.2f dB < %.1f dB", m.psnr, CORNELL_FULL_FLOOR);
    cr_expect(averaged >= CORNELL_AVERAGED_FLOOR, "4x4-averaged PSNR %.2f dB < %.1f dB", averaged,
              CORNELL_AVERAGED_FLOOR);
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

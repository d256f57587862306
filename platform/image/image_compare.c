/* PSNR and difference statistics of two images, and their heat map; see image_compare.h. */
#include "image/image_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bool rtp_image_compare(const rtp_image *a, const rtp_image *b, rtp_image_metrics *m)
{
    if (a->width != b->width || a->height != b->height || a->width == 0 || a->height == 0) return false;
    uint64_t pixels = (uint64_t)a->width * a->height, channels = pixels * 3;
    uint64_t sum = 0, sum_sq = 0, within[4] = {0}, over2 = 0, worst_at = 0;
    unsigned worst = 0;
    for (uint64_t p = 0; p < pixels; p++) {
        unsigned most = 0;
        for (int c = 0; c < 3; c++) {
            int s = (int)a->rgb[3 * p + c] - (int)b->rgb[3 * p + c];
            unsigned d = (unsigned)(s < 0 ? -s : s);
            sum += d;
            sum_sq += (uint64_t)d * d;
            within[0] += d == 0;
            within[1] += d <= 1;
            within[2] += d <= 2;
            within[3] += d <= 8;
            most = d > most ? d : most;
        }
        over2 += most > 2;
        if (most > worst) { /* strict: the first pixel in row-major order wins ties */
            worst = most;
            worst_at = p;
        }
    }
    *m = (rtp_image_metrics){
        .width = a->width,
        .height = a->height,
        .psnr = sum_sq == 0 ? INFINITY : 10.0 * log10(255.0 * 255.0 * (double)channels / (double)sum_sq),
        .mean_diff = (double)sum / (double)channels,
        .max_diff = worst,
        .within0_pct = 100.0 * (double)within[0] / (double)channels,
        .within1_pct = 100.0 * (double)within[1] / (double)channels,
        .within2_pct = 100.0 * (double)within[2] / (double)channels,
        .within8_pct = 100.0 * (double)within[3] / (double)channels,
        .pixels_over2 = over2,
        .worst_x = (uint32_t)(worst_at % a->width),
        .worst_y = (uint32_t)(worst_at / a->width),
    };
    memcpy(m->worst_a, a->rgb + 3 * worst_at, 3);
    memcpy(m->worst_b, b->rgb + 3 * worst_at, 3);
    return true;
}

/* Heat-map ramp, by a pixel's largest channel difference d:
 *   d = 0 black; d = 1 blue (0,0,255); d = 4 green (0,255,0); d = 16 yellow (255,255,0);
 *   d >= 64 red (255,0,0); linear in d between stops.
 * Stops grow by 4x, so the ramp is roughly logarithmic: a single level already shows
 * as clear blue, and hue tells 1-level noise from real errors at a glance. */
static void heat(unsigned d, uint8_t rgb[3])
{
    static const unsigned at[4] = {1, 4, 16, 64};
    static const uint8_t colour[4][3] = {{0, 0, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
    if (d == 0) {
        memset(rgb, 0, 3);
        return;
    }
    if (d >= at[3]) {
        memcpy(rgb, colour[3], 3);
        return;
    }
    int i = 0;
    while (d >= at[i + 1]) i++;
    unsigned t = (d - at[i]) * 255 / (at[i + 1] - at[i]); /* 0..255 along the segment */
    for (int c = 0; c < 3; c++) rgb[c] = (uint8_t)((colour[i][c] * (255 - t) + colour[i + 1][c] * t) / 255);
}

bool rtp_image_diff_map(const rtp_image *a, const rtp_image *b, rtp_image *out)
{
    size_t pixels = (size_t)a->width * a->height;
    *out = (rtp_image){.width = a->width, .height = a->height, .rgb = malloc(pixels * 3)};
    if (!out->rgb) return false;
    for (size_t p = 0; p < pixels; p++) {
        unsigned most = 0;
        for (int c = 0; c < 3; c++) {
            int s = (int)a->rgb[3 * p + c] - (int)b->rgb[3 * p + c];
            unsigned d = (unsigned)(s < 0 ? -s : s);
            most = d > most ? d : most;
        }
        heat(most, out->rgb + 3 * p);
    }
    return true;
}

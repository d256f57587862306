/* Image comparison: the metrics behind `rtk compare` and the renderer's reference tests. */
#ifndef RTP_IMAGE_COMPARE_H
#define RTP_IMAGE_COMPARE_H

#include "image/image.h"

typedef struct {
    uint32_t width, height;
    /* 10 log10(255^2 N / sum of squared differences) over all N = 3 w h RGB channels,
     * as tools/fidelity computes it; INFINITY when the images are identical. */
    double psnr;
    double mean_diff;  /* mean |a - b| over all channels, in 8-bit levels */
    unsigned max_diff; /* largest |a - b| over all channels */
    /* Percentage of channels with |a - b| <= 0, 1, 2 and 8 levels. */
    double within0_pct, within1_pct, within2_pct, within8_pct;
    uint64_t pixels_over2;          /* pixels whose largest channel difference exceeds 2 */
    uint32_t worst_x, worst_y;      /* first pixel, row-major from the top left, at max_diff */
    uint8_t worst_a[3], worst_b[3]; /* that pixel's colour in a and in b */
} rtp_image_metrics;

/* Fills *m; false (and *m untouched) when the sizes differ or are zero. */
bool rtp_image_compare(const rtp_image *a, const rtp_image *b, rtp_image_metrics *m);

/* Heat map of each pixel's largest channel difference (black = identical; ramp in image_compare.c)
 * for two images of the same size; out->rgb is malloc'd. False when out of memory. */
bool rtp_image_diff_map(const rtp_image *a, const rtp_image *b, rtp_image *out);

#endif

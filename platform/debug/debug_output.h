/* The outputs of `rtk debug`: a traced pixel's ray tree as text, as JSON, and drawn as SVG. */
#ifndef RTP_DEBUG_OUTPUT_H
#define RTP_DEBUG_OUTPUT_H

#include "debug/pixel_trace.h"
#include "image/image.h"
#include <stdio.h>

void rtp_debug_print_text(FILE *out, const rtp_pixel_trace *pt);
/* One JSON document; non-finite numbers are null. */
void rtp_debug_print_json(FILE *out, const rtp_pixel_trace *pt);
/* Writes an SVG (atomically) with `render` (the scene's image) and the pixel marked, and the
 * ray tree projected on two planes over the objects' outlines. False with one line in err. */
bool rtp_debug_write_svg(const char *path, const rtp_pixel_trace *pt, const rtp_image *render, char *err,
                         size_t err_size);

#endif

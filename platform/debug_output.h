/* The outputs of `rtk debug`: a traced pixel's ray tree as text, as JSON, and drawn as SVG. */
#ifndef RT_DEBUG_OUTPUT_H
#define RT_DEBUG_OUTPUT_H

#include <stdio.h>
#include "image.h"
#include "pixel_trace.h"

void rt_debug_print_text(FILE *out, const rt_pixel_trace *pt);
/* One JSON document; non-finite numbers are null. */
void rt_debug_print_json(FILE *out, const rt_pixel_trace *pt);
/* Writes an SVG (atomically) with `render` (the scene's image) and the pixel marked, and the
 * ray tree projected on two planes over the objects' outlines. False with one line in err. */
bool rt_debug_write_svg(const char *path, const rt_pixel_trace *pt, const rt_image *render, char *err,
                        size_t err_size);

#endif

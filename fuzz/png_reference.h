/* An independent PNG decoder for fuzz_png's differential check: libpng (Debian's
 * libpng-dev), set up to give what rtp_image_read promises: 8-bit RGB, palettes and low
 * bit depths expanded, 16-bit samples cut to their high byte, alpha and tRNS dropped,
 * no gamma applied, interlacing undone. */
#ifndef FZ_PNG_REFERENCE_H
#define FZ_PNG_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

/* Decodes size bytes of PNG; the RGB bytes are malloc'd (freed by the caller). NULL when
 * libpng refuses the file or it has more than max_pixels pixels. */
uint8_t *fz_png_reference_decode(const uint8_t *data, size_t size, size_t max_pixels, uint32_t *width,
                                 uint32_t *height);

#endif

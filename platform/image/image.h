/* Image files: PNG (libspng) and binary PPM, read to and written from 8-bit RGB. */
#ifndef RTP_IMAGE_H
#define RTP_IMAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t width, height;
    uint8_t *rgb; /* width * height * 3, row 0 = top; malloc'd, released by rtp_image_free */
} rtp_image;

/* Reads a PNG (any bit depth / colour type, converted to 8-bit RGB, alpha dropped)
 * or a P6 PPM (maxval 255), chosen by the file's magic bytes, not its name.
 * On failure: false, and one line in err naming the file and what was wrong. */
bool rtp_image_read(const char *path, rtp_image *out, char *err, size_t err_size);
/* Writes PNG when path ends in .png, else P6 PPM; atomically (temp file + rename):
 * on failure nothing is left at path. */
bool rtp_image_write(const char *path, const rtp_image *img, char *err, size_t err_size);
void rtp_image_free(rtp_image *img);

/* The PNG file of img in memory (for embedding): malloc'd bytes, released with free;
 * NULL with one line in err on failure. */
void *rtp_image_encode_png(const rtp_image *img, size_t *size, char *err, size_t err_size);

#endif

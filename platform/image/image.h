/* Image files: PNG (libspng) and binary PPM, read to and written from 8-bit RGB. */
#ifndef RTP_IMAGE_H
#define RTP_IMAGE_H

#include "load/input_file.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t width, height;
    uint8_t *rgb; /* width * height * 3, row 0 = top; rtp_mem's, released by rtp_image_free */
} rtp_image;

/* A black image of the given size, counted against --max-memory as what ("the output
 * image"); false (rtp_mem_refusal() says why) when it does not fit. */
bool rtp_image_alloc(rtp_image *img, uint32_t width, uint32_t height, const char *what);

/* Reads a PNG (any bit depth / colour type, converted to 8-bit RGB, alpha dropped)
 * or a P6 PPM (maxval 255), chosen by the file's magic bytes, not its name.
 * On failure: false, and one line in err naming the file and what was wrong. */
bool rtp_image_read(const char *path, rtp_image *out, char *err, size_t err_size);
/* The same for a file already opened with rtp_input_open, which this reads and closes. */
bool rtp_image_read_input(rtp_input *in, rtp_image *out, char *err, size_t err_size);
/* Writes PNG when path ends in .png, else P6 PPM (also for "-", standard output), by
 * rtp_file_write's rules: on failure nothing is left at path. */
bool rtp_image_write(const char *path, const rtp_image *img, char *err, size_t err_size);
void rtp_image_free(rtp_image *img);

/* A libspng context (SPNG_CTX_ENCODER or 0) whose allocations count against --max-memory,
 * for other PNG code (rtk's parts); NULL when even that does not fit. */
struct spng_ctx *rtp_png_ctx_new(int flags);

/* The PNG file of img in memory (for embedding): rtp_mem bytes, released with rtp_mem_free;
 * NULL with one line in err on failure. */
void *rtp_image_encode_png(const rtp_image *img, size_t *size, char *err, size_t err_size);

#endif

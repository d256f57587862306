/* A part on disk: a PNG of the part's rectangle (8-bit RGB, viewable as it is) whose tEXt
 * chunks, one per field of part.h, come before the image data, so the facts can be
 * read without the pixels. */
#ifndef RTP_PART_FILE_H
#define RTP_PART_FILE_H

#include "part/part.h"

/* Sets p's RTP_PART_PIXELS to the digest of rgb (the region's pixels, row by row) and
 * writes the part atomically. Every other field must be set. False with one line in err
 * (naming path) when the file cannot be written. */
bool rtp_part_write(const char *path, rtp_part *p, const uint8_t *rgb, char *err, size_t err_size);

/* Reads a part, checks it is whole (a PNG intact to its end, every field present and
 * well formed, an image the region's size whose pixels match their digest) and, when
 * rgb is not NULL, hands over its pixels (malloc'd). False with the problem in err
 * (without the path: "truncated (the PNG ends early)"); *p is then empty. */
bool rtp_part_read(const char *path, rtp_part *p, uint8_t **rgb, char *err, size_t err_size);

#endif

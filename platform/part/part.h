/* A part of a distributed render: a rectangle of the frame's pixels and what `rtk stitch`
 * needs to trust it, stored as a PNG of the rectangle with text chunks
 * (part_file.h; the format is in docs/distributed.md). */
#ifndef RTP_PART_H
#define RTP_PART_H

#include "render.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The facts a part carries, each one PNG text chunk. Fields before RTP_PART_REGION name
 * the render (equal in every part of one frame); the others differ from part to part. */
typedef enum {
    RTP_PART_BUILD,    /* "double" or "fixed" */
    RTP_PART_VERSION,  /* rtk --version's line */
    RTP_PART_SCENE,    /* SHA-256 (hex) of the scene file's bytes */
    RTP_PART_ASSETS,   /* SHA-256 of each mesh and texture file read, in load order; "none" */
    RTP_PART_SETTINGS, /* the camera settings that change pixels, after overrides */
    RTP_PART_FRAME,    /* "WIDTHxHEIGHT" of the whole frame */
    RTP_PART_REGION,   /* "X0,Y0,X1,Y1", as --region takes it */
    RTP_PART_INDEX,    /* "I/N" for --part I/N, "region" for --region */
    RTP_PART_PIXELS,   /* SHA-256 of the region's RGB bytes, row by row */
    RTP_PART_FIELDS
} rtp_part_field;

/* Names of the fields (PNG text keywords, "rtk frame") and of what a difference in one
 * means ("frame size"). */
extern const char *const rtp_part_keys[RTP_PART_FIELDS];
extern const char *const rtp_part_field_names[RTP_PART_FIELDS];

typedef struct {
    char *text[RTP_PART_FIELDS]; /* rtp_mem's, released by rtp_part_free */
    /* The numeric fields, parsed from or formatted into text. */
    uint32_t width, height; /* the frame */
    rt_rect region;
    uint32_t index, count; /* part index of count; count 0 for a --region part */
} rtp_part;

void rtp_part_free(rtp_part *p);
/* Sets field f to a copy of value; false when it does not fit (rtp_mem_refusal()). */
bool rtp_part_set(rtp_part *p, rtp_part_field f, const char *value);
/* Formats the FRAME, REGION and INDEX fields from the numbers; false when out of memory. */
bool rtp_part_format_place(rtp_part *p);
/* Parses the FRAME, REGION and INDEX fields (all set) into the numbers; false with the
 * problem in err (e.g. "its region 0,0,9,9 lies outside its 8x8 frame") when one is
 * malformed. */
bool rtp_part_parse_place(rtp_part *p, char *err, size_t err_size);

/* "X0,Y0,X1,Y1" into a non-empty rectangle (X0 < X1, Y0 < Y1); false otherwise. */
bool rtp_part_parse_rect(const char *s, rt_rect *out);
/* "I/N" with I < N, 1 <= N <= max_count; false otherwise. */
bool rtp_part_parse_index(const char *s, uint32_t max_count, uint32_t *index, uint32_t *count);

/* Writes the problem, printf-style, into err; returns false. */
bool rtp_part_fail(char *err, size_t err_size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Lowercase hex of a 32-byte digest into hex (65 bytes with the terminator). */
void rtp_part_hex(const uint8_t digest[32], char hex[65]);

/* The file name part I of N has in a parts folder: "DIR/part-I-of-N.png" (malloc'd, or NULL). */
char *rtp_part_file_name(const char *dir, uint32_t index, uint32_t count);

#endif

/* A stdio stream into memory counted by rtp_mem (open_memstream's buffer is not): for
 * the SVG `rtk debug` composes with fprintf before writing it as one file. */
#ifndef RTP_MEM_STREAM_H
#define RTP_MEM_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct {
    char *data; /* rtp_mem's; what was written, not NUL-terminated */
    size_t size, capacity;
} rtp_mem_buffer;

/* A write-only stream appending to *buf (which must start zeroed). A write that does not
 * fit under the cap fails, so ferror or fclose reports it; rtp_mem_refusal() says why. */
FILE *rtp_mem_stream_open(rtp_mem_buffer *buf);
void rtp_mem_buffer_free(rtp_mem_buffer *buf);

#endif

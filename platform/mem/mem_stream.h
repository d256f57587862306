/* A stdio stream into memory counted by rtp_mem (open_memstream's buffer is not): for
 * the texts rtk composes with fprintf before writing each as one file (`rtk debug`'s SVG,
 * `rtk verify`'s JUnit report and manifest). */
#ifndef RTP_MEM_STREAM_H
#define RTP_MEM_STREAM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct {
    char *data; /* rtp_mem's; what was written, not NUL-terminated */
    size_t size, capacity;
    const char *what; /* the text in a refusal, e.g. "the SVG" */
} rtp_mem_buffer;

/* A write-only stream appending to *buf (zeroed, but for `what`). A write that does not
 * fit under the cap fails, so ferror or fclose reports it; rtp_mem_refusal() says why. */
FILE *rtp_mem_stream_open(rtp_mem_buffer *buf);
void rtp_mem_buffer_free(rtp_mem_buffer *buf);

#endif

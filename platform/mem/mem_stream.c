/* rtp_mem_stream_open (mem_stream.h) on glibc's fopencookie. */
#define _GNU_SOURCE
#include "mem/mem_stream.h"

#include "mem/mem.h"
#include <string.h>

static ssize_t append(void *cookie, const char *bytes, size_t size)
{
    rtp_mem_buffer *buf = cookie;
    if (size > buf->capacity - buf->size) {
        size_t capacity = buf->capacity ? buf->capacity : 4096;
        while (capacity - buf->size < size) capacity *= 2;
        char *grown = rtp_mem_realloc(buf->data, capacity, buf->what);
        if (!grown) return 0; /* 0 of size bytes written: the stream's error */
        buf->data = grown;
        buf->capacity = capacity;
    }
    memcpy(buf->data + buf->size, bytes, size);
    buf->size += size;
    return (ssize_t)size;
}

FILE *rtp_mem_stream_open(rtp_mem_buffer *buf)
{
    cookie_io_functions_t io = {.write = append};
    return fopencookie(buf, "w", io);
}

void rtp_mem_buffer_free(rtp_mem_buffer *buf)
{
    rtp_mem_free(buf->data);
    memset(buf, 0, sizeof *buf);
}

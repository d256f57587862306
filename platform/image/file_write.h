/* Whole files written atomically: a reader sees the old file or the new one, never part. */
#ifndef RTP_FILE_WRITE_H
#define RTP_FILE_WRITE_H

#include <stdbool.h>
#include <stddef.h>

/* Writes size bytes to path via a temporary file in the same folder and rename(2). */
bool rtp_file_write_atomic(const char *path, const void *data, size_t size, char *err, size_t err_size);

#endif

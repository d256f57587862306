/* Output files, written by one rule set (docs/robustness.md, "Inputs and outputs"):
 * - "-" is standard output, written through;
 * - a new file, or an existing regular file, is written atomically: a temporary file
 *   ".rtk-<pid>-<n>.tmp" in the same folder (short, so any legal name works), fsync,
 *   rename(2). Readers see the old file or the complete new one; a replaced file keeps
 *   its permission bits (and its owner, where rtk may set it); a file the user may not
 *   write (mode 0444 for a non-root user) is not replaced;
 * - a symbolic link is followed: its target is written by these rules; a link to
 *   nothing is refused;
 * - a character device or a FIFO is written through, never replaced (so /dev/null
 *   works, /dev/full fails); a FIFO without a reader is refused instead of waited for;
 * - directories, block devices and sockets are refused.
 * An output that is also an input of the command is refused before, by the reader
 * (load/input_file.h). */
#ifndef RTP_FILE_WRITE_H
#define RTP_FILE_WRITE_H

#include <stdbool.h>
#include <stddef.h>

/* Writes size bytes to path by the rules above. On failure nothing was put at path
 * (a stream may have got part of the bytes) and err holds one line naming path. */
bool rtp_file_write(const char *path, const void *data, size_t size, char *err, size_t err_size);

#endif

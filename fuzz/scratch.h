/* The parsers take paths, so the parser targets write each input to a file in a
 * scratch folder of their own (under $TMPDIR, else /dev/shm or /tmp), removed when
 * the process exits. */
#ifndef FZ_SCRATCH_H
#define FZ_SCRATCH_H

#include <stddef.h>
#include <stdint.h>

/* The folder, created on first use. */
const char *fz_scratch_dir(void);
/* Writes size bytes to <scratch>/<name> (creating subfolders) and returns its path,
 * valid until the next call. */
const char *fz_scratch_write(const char *name, const void *data, size_t size);

#endif

/* Input files -- the scene, its meshes and textures, the images `rtk compare` reads --
 * each opened once and read whole into memory counted against --max-memory. The rules
 * (docs/robustness.md, "Inputs and outputs"):
 * - a path must name a regular file: directories, FIFOs, devices and sockets are refused
 *   from stat(2) before any open, and the open is non-blocking, so a FIFO or a device
 *   never makes rtk wait (nor sees an open it could react to);
 * - "-" is standard input, whatever it is, where the caller allows it (the scene);
 * - a file that is also one of the command's outputs (same device and inode, however it
 *   is named) is refused, so rtk never overwrites its own input: the command exits 2. */
#ifndef RTP_INPUT_FILE_H
#define RTP_INPUT_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

typedef struct {
    const char *path; /* as given; "-" for standard input */
    int fd;
    dev_t dev; /* the file's identity, to read each file once */
    ino_t ino;
    off_t size;         /* regular files: the length fstat reported */
    bool regular;       /* false only for standard input that is not a regular file */
    bool open_failed;   /* the failure was the system's (err holds strerror): callers word it */
    bool special;       /* the failure: a FIFO, a device or a socket */
    bool is_output_too; /* the failure: the file is also an output of the command */
} rtp_input;

/* Opens path for reading ("-": standard input when allow_stdin). On failure returns
 * false with the problem, without the path, in err: the system's reason when the file
 * could not be opened (in->open_failed), else e.g. "is a FIFO, not a regular file". */
bool rtp_input_open(rtp_input *in, const char *path, bool allow_stdin, char *err, size_t err_size);
/* Reads the whole file into *data (rtp_mem, released with rtp_mem_free) and closes it. Files longer than max_size bytes (0: no limit)
 * are refused as "file too large for <kind> ..." before anything is read, and so are
 * files that do not fit under --max-memory. On failure the problem is in err. */
bool rtp_input_read(rtp_input *in, size_t max_size, const char *kind, uint8_t **data, size_t *size, char *err,
                    size_t err_size);
void rtp_input_close(rtp_input *in);

/* Registers an output the command will write: an input that is the same file is refused.
 * Call it for every output before reading any input. */
void rtp_input_forbid(const char *output);
/* True once an input was refused for being an output too (exit 2). */
bool rtp_input_was_output(void);

#endif

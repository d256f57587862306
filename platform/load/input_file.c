/* Opening and reading input files under rtk's rules (see input_file.h). */
#include "load/input_file.h"

#include "mem/mem.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* render -o, compare --diff, debug --svg, pack -o: one each; room to spare. */
#define MAX_OUTPUTS 4
/* Standard input is read in pieces of at least this, doubling. */
#define STDIN_CHUNK ((size_t)64 << 10)

static struct {
    dev_t dev;
    ino_t ino;
    char name[256];
} outputs[MAX_OUTPUTS];
static int output_count;
static bool output_hit;

void rtp_input_forbid(const char *output)
{
    struct stat st;
    if (output_count == MAX_OUTPUTS || !strcmp(output, "-") || stat(output, &st) != 0 || !S_ISREG(st.st_mode)) return;
    outputs[output_count].dev = st.st_dev;
    outputs[output_count].ino = st.st_ino;
    snprintf(outputs[output_count].name, sizeof outputs[output_count].name, "%s", output);
    output_count++;
}

bool rtp_input_was_output(void) { return output_hit; }

static const char *kind_of(mode_t mode)
{
    if (S_ISDIR(mode)) return "is a directory";
    if (S_ISFIFO(mode)) return "is a FIFO, not a regular file";
    if (S_ISCHR(mode)) return "is a character device, not a regular file";
    if (S_ISBLK(mode)) return "is a block device, not a regular file";
    if (S_ISSOCK(mode)) return "is a socket, not a regular file";
    return "is not a regular file";
}

static bool refuse_kind(rtp_input *in, mode_t mode, char *err, size_t err_size)
{
    in->special = !S_ISDIR(mode);
    snprintf(err, err_size, "%s", kind_of(mode));
    return false;
}

static bool system_failure(rtp_input *in, int e, char *err, size_t err_size)
{
    in->open_failed = true;
    snprintf(err, err_size, "%s", strerror(e));
    return false;
}

/* Refuses a file that is also an output; identity from fstat of the open descriptor. */
static bool check_identity(rtp_input *in, const struct stat *st, char *err, size_t err_size)
{
    in->dev = st->st_dev;
    in->ino = st->st_ino;
    in->size = st->st_size;
    for (int i = 0; i < output_count; i++) {
        if (S_ISREG(st->st_mode) && outputs[i].dev == st->st_dev && outputs[i].ino == st->st_ino) {
            in->is_output_too = output_hit = true;
            snprintf(err, err_size, "is also the output '%s': rtk does not overwrite its inputs", outputs[i].name);
            return false;
        }
    }
    return true;
}

bool rtp_input_open(rtp_input *in, const char *path, bool allow_stdin, char *err, size_t err_size)
{
    *in = (rtp_input){.path = path, .fd = -1};
    struct stat st;
    if (allow_stdin && !strcmp(path, "-")) {
        if (fstat(STDIN_FILENO, &st) != 0) return system_failure(in, errno, err, err_size);
        if (S_ISDIR(st.st_mode)) return refuse_kind(in, st.st_mode, err, err_size);
        in->regular = S_ISREG(st.st_mode);
        if (!check_identity(in, &st, err, err_size)) return false;
        in->fd = STDIN_FILENO;
        return true;
    }
    /* stat first: a FIFO or device is refused without being opened. */
    if (stat(path, &st) != 0) return system_failure(in, errno, err, err_size);
    if (!S_ISREG(st.st_mode)) return refuse_kind(in, st.st_mode, err, err_size);
    /* Non-blocking in case the path was swapped for a FIFO since the stat. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return system_failure(in, errno, err, err_size);
    in->fd = fd;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        rtp_input_close(in);
        return system_failure(in, e, err, err_size);
    }
    bool ok = S_ISREG(st.st_mode) || refuse_kind(in, st.st_mode, err, err_size);
    if (ok) ok = check_identity(in, &st, err, err_size);
    if (!ok) rtp_input_close(in);
    in->regular = true;
    return ok;
}

void rtp_input_close(rtp_input *in)
{
    if (in->fd > STDIN_FILENO) close(in->fd);
    in->fd = -1;
}

/* Reads up to want bytes at buf; returns how many (fewer at the end of the file), or -1. */
static ssize_t read_fully(int fd, uint8_t *buf, size_t want)
{
    size_t got = 0;
    while (got < want) {
        ssize_t n = read(fd, buf + got, want - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return -1;
        if (n == 0) break;
        got += (size_t)n;
    }
    return (ssize_t)got;
}

/* Standard input that is not a regular file: its length is unknown until the end. */
static bool read_stream(rtp_input *in, const char *kind, uint8_t **data, size_t *size, char *err, size_t err_size)
{
    char what[64];
    snprintf(what, sizeof what, "%s from standard input", kind);
    size_t cap = STDIN_CHUNK, got = 0;
    uint8_t *buf = rtp_mem_alloc(cap, what);
    for (;;) {
        if (!buf) return snprintf(err, err_size, "%s", rtp_mem_refusal()), false;
        ssize_t n = read_fully(in->fd, buf + got, cap - got);
        if (n < 0) {
            int e = errno;
            rtp_mem_free(buf);
            return snprintf(err, err_size, "cannot read: %s", strerror(e)), false;
        }
        got += (size_t)n;
        if (got < cap) break;
        uint8_t *grown = rtp_mem_realloc(buf, 2 * cap, what);
        if (!grown) rtp_mem_free(buf);
        buf = grown;
        cap *= 2;
    }
    *data = buf;
    *size = got;
    return true;
}

bool rtp_input_read(rtp_input *in, size_t max_size, const char *kind, uint8_t **data, size_t *size, char *err,
                    size_t err_size)
{
    bool ok;
    if (!in->regular) {
        ok = read_stream(in, kind, data, size, err, err_size);
    } else {
        size_t length = (size_t)in->size;
        char limit[32];
        uint8_t *buf = NULL;
        ssize_t got = 0;
        if (max_size && length > max_size)
            snprintf(err, err_size, "file too large for %s (over %s)", kind,
                     rtp_mem_describe(max_size, limit, sizeof limit));
        else if (!(buf = rtp_mem_alloc(length ? length : 1, "the file")))
            snprintf(err, err_size, "%s", rtp_mem_refusal());
        else if ((got = read_fully(in->fd, buf, length)) < 0)
            snprintf(err, err_size, "cannot read: %s", strerror(errno));
        ok = buf && got >= 0;
        if (ok) { /* a file that shrank while reading ends early: the parsers say truncated */
            *data = buf;
            *size = (size_t)got;
        } else {
            rtp_mem_free(buf);
        }
    }
    rtp_input_close(in);
    return ok;
}

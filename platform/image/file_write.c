/* rtp_file_write (file_write.h): atomic replacement of regular files, streams written
 * through, everything else refused. */
#include "image/file_write.h"

#include "cli/signals.h"
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Names ".rtk-<pid>-<n>.tmp" are tried until one is free. Not mkstemp: its files are
 * 0600, while open(0666) applies the umask the user expects for a new file. */
#define RTP_TEMP_ATTEMPTS 100

static bool fail(char *err, size_t err_size, const char *path, const char *what)
{
    if (err_size > 0) snprintf(err, err_size, "%s: %s", path, what);
    return false;
}

static bool fail_errno(char *err, size_t err_size, const char *path, int e)
{
    char what[128];
    if (e == ENOENT)
        snprintf(what, sizeof what, "directory does not exist");
    else if (e == EISDIR)
        snprintf(what, sizeof what, "is a directory");
    else
        snprintf(what, sizeof what, "cannot write: %s", strerror(e));
    return fail(err, err_size, path, what);
}

/* Returns 0 or the errno of the failed write. A descriptor left non-blocking by
 * whoever shares it is waited on rather than failed. */
static int write_all(int fd, const unsigned char *data, size_t size)
{
    while (size > 0) {
        ssize_t n = write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            struct pollfd p = {.fd = fd, .events = POLLOUT};
            poll(&p, 1, -1);
            continue;
        }
        if (n < 0) return errno;
        if (n == 0) return EIO;
        data += n;
        size -= (size_t)n;
    }
    return 0;
}

/* Makes the rename itself survive a crash; best effort, the file is already complete. */
static void sync_folder(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
}

/* A character device, a FIFO or standard output: written in place, since it cannot be
 * replaced; what reached it before a failure stays there. */
static bool write_stream(const char *path, int fd, const void *data, size_t size, char *err, size_t err_size)
{
    rtp_signals_streaming(path);
    int e = write_all(fd, data, size);
    rtp_signals_streaming(NULL);
    return e == 0 || fail_errno(err, err_size, strcmp(path, "-") ? path : "standard output", e);
}

static bool write_device(const char *path, char *err, size_t err_size, const void *data, size_t size)
{
    /* Non-blocking open: a FIFO nobody reads is an error now, not a wait forever. */
    int fd = open(path, O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0 && errno == ENXIO) return fail(err, err_size, path, "is a FIFO that no process is reading");
    if (fd < 0) return fail_errno(err, err_size, path, errno);
    struct stat st;
    bool ok = fstat(fd, &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)); /* not swapped meanwhile */
    if (!ok)
        fail(err, err_size, path, "changed while rtk opened it");
    else if (fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0)
        ok = fail_errno(err, err_size, path, errno);
    else
        ok = write_stream(path, fd, data, size, err, err_size);
    if (close(fd) != 0 && ok) ok = fail_errno(err, err_size, path, errno);
    return ok;
}

/* Creates a temporary file in dir (ending in '/', or empty for the working folder),
 * tracked for the signal handler before a signal can be taken. Returns its descriptor. */
static int create_temp(const char *dir, char *tmp, size_t tmp_size)
{
    int fd = -1;
    rtp_signals_hold();
    for (int attempt = 0; attempt < RTP_TEMP_ATTEMPTS && fd < 0; attempt++) {
        snprintf(tmp, tmp_size, "%s.rtk-%ld-%d.tmp", dir, (long)getpid(), attempt);
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST) break;
    }
    int e = errno;
    if (fd >= 0) rtp_signals_track(tmp);
    rtp_signals_release();
    errno = e;
    return fd;
}

/* A new file (old == NULL) or a regular file replaced: temporary file, then rename. */
static bool write_atomic(const char *path, const struct stat *old, const void *data, size_t size, char *err,
                         size_t err_size)
{
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    if (path[dir_len] == '\0') return fail(err, err_size, path, *path ? "is a directory" : "empty file name");
    char dir[PATH_MAX], tmp[PATH_MAX + 48];
    if (dir_len >= sizeof dir) return fail_errno(err, err_size, path, ENAMETOOLONG);
    memcpy(dir, path, dir_len);
    dir[dir_len] = '\0';
    int fd = create_temp(dir, tmp, sizeof tmp);
    if (fd < 0) return fail_errno(err, err_size, path, errno);
    int e = 0;
    if (old) { /* the replacement keeps the file's owner (when rtk may set it) and permission bits */
        if (geteuid() == 0) (void)!fchown(fd, old->st_uid, old->st_gid);
        if (fchmod(fd, old->st_mode & 07777) != 0) e = errno;
    }
    if (e == 0) e = write_all(fd, data, size);
    if (e == 0 && fsync(fd) != 0) e = errno;
    if (close(fd) != 0 && e == 0) e = errno;
    rtp_signals_hold(); /* from here on the output goes in place whatever arrives */
    if (e == 0 && rename(tmp, path) != 0) e = errno;
    if (e != 0) unlink(tmp);
    rtp_signals_track(NULL);
    if (e != 0) return fail_errno(err, err_size, path, e);
    sync_folder(dir_len ? dir : ".");
    return true;
}

bool rtp_file_write(const char *path, const void *data, size_t size, char *err, size_t err_size)
{
    if (!strcmp(path, "-")) return write_stream("-", STDOUT_FILENO, data, size, err, err_size);
    struct stat st;
    if (stat(path, &st) != 0) { /* stat follows links, also /proc's (/dev/stdout on a pipe) */
        int e = errno;
        if (e == ENOENT && lstat(path, &st) == 0 && S_ISLNK(st.st_mode))
            return fail(err, err_size, path, "is a symbolic link to a file that does not exist");
        return e == ENOENT ? write_atomic(path, NULL, data, size, err, err_size) : fail_errno(err, err_size, path, e);
    }
    if (S_ISDIR(st.st_mode)) return fail(err, err_size, path, "is a directory");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return write_device(path, err, err_size, data, size);
    if (!S_ISREG(st.st_mode))
        return fail(err, err_size, path, "is neither a regular file, a character device nor a FIFO: not written");
    if (faccessat(AT_FDCWD, path, W_OK, AT_EACCESS) != 0) return fail_errno(err, err_size, path, errno);
    /* A link's target is replaced, in the target's folder; the link stays. */
    struct stat link;
    char *target = NULL;
    if (lstat(path, &link) == 0 && S_ISLNK(link.st_mode) && !(target = realpath(path, NULL)))
        return fail_errno(err, err_size, path, errno);
    bool ok = write_atomic(target ? target : path, &st, data, size, err, err_size);
    free(target);
    return ok;
}

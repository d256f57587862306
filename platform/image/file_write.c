/* rtp_file_write_atomic (file_write.h): temporary file in the target's folder,
 * fsync, rename(2), so readers see the old file or the complete new one, never a part. */
#include "image/file_write.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Tries ".<name>.<pid>.<n>.tmp" until one is free. Not mkstemp: its files are 0600,
 * while open(0666) applies the umask the user expects for the final file. */
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

/* Returns 0 or the errno of the failed write. */
static int write_all(int fd, const unsigned char *data, size_t size)
{
    while (size > 0) {
        ssize_t n = write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        data += n;
        size -= (size_t)n;
    }
    return 0;
}

/* Makes the rename itself survive a crash; best effort, the file is already complete. */
static void sync_folder(const char *path, size_t dir_len)
{
    char *dir = strndup(path, dir_len > 0 ? dir_len : 1);
    if (!dir) return;
    if (dir_len == 0) dir[0] = '.';
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
    free(dir);
}

bool rtp_file_write_atomic(const char *path, const void *data, size_t size, char *err, size_t err_size)
{
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    const char *name = path + dir_len;
    if (*name == '\0') return fail(err, err_size, path, *path ? "is a directory" : "empty file name");

    size_t tmp_size = strlen(path) + 48;
    char *tmp = malloc(tmp_size);
    if (!tmp) return fail(err, err_size, path, "out of memory");
    memcpy(tmp, path, dir_len);
    int fd = -1;
    for (int attempt = 0; attempt < RTP_TEMP_ATTEMPTS && fd < 0; attempt++) {
        snprintf(tmp + dir_len, tmp_size - dir_len, ".%s.%ld.%d.tmp", name, (long)getpid(), attempt);
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) {
        int e = errno;
        free(tmp);
        return fail_errno(err, err_size, path, e);
    }

    int e = write_all(fd, data, size);
    if (e == 0 && fsync(fd) != 0) e = errno;
    if (close(fd) != 0 && e == 0) e = errno;
    if (e == 0 && rename(tmp, path) != 0) e = errno;
    if (e != 0) {
        unlink(tmp);
        free(tmp);
        return fail_errno(err, err_size, path, e);
    }
    sync_folder(path, dir_len);
    free(tmp);
    return true;
}

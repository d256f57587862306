/* realpath(3) for wasi-libc, which lacks it (platform/load/scene_load.c uses it to find the
 * scene's folder). WASI file systems here have no symbolic links, so the path is made
 * absolute against the working directory and "." and ".." are removed lexically; like
 * realpath, it fails (ENOENT) when the path does not exist. */
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

char *realpath(const char *restrict path, char *restrict resolved)
{
    struct stat st;
    if (!path) {
        errno = EINVAL;
        return NULL;
    }
    if (stat(path, &st) != 0) return NULL;
    char joined[PATH_MAX], out[PATH_MAX];
    size_t n = 0;
    if (path[0] == '/') {
        joined[0] = '\0';
    } else if (!getcwd(joined, sizeof joined)) {
        return NULL;
    }
    if (strlen(joined) + strlen(path) + 2 > sizeof joined) {
        errno = ENAMETOOLONG;
        return NULL;
    }
    strcat(joined, "/");
    strcat(joined, path);
    /* Copy component by component; ".." drops the last one kept. */
    for (const char *p = joined; *p;) {
        while (*p == '/') p++;
        const char *end = p;
        while (*end && *end != '/') end++;
        size_t len = (size_t)(end - p);
        bool dot = len == 1 && p[0] == '.', dot_dot = len == 2 && p[0] == '.' && p[1] == '.';
        if (dot_dot) {
            while (n > 0 && out[n - 1] != '/') n--;
            if (n > 0) n--;
        } else if (len > 0 && !dot) {
            out[n++] = '/';
            memcpy(out + n, p, len);
            n += len;
        }
        p = end;
    }
    if (n == 0) out[n++] = '/';
    out[n] = '\0';
    char *dst = resolved ? resolved : malloc(n + 1);
    if (!dst) return NULL;
    memcpy(dst, out, n + 1);
    return dst;
}

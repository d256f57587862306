/* File owners and permission bits for wasi-libc, which declares these calls but has no
 * implementation: WASI files carry neither, so a replaced output has nothing of the
 * kind to keep (platform/image/file_write.c). */
#include <sys/stat.h>
#include <unistd.h>

uid_t geteuid(void) { return 1; } /* never root: no owner to restore */

int fchown(int fd, uid_t owner, gid_t group)
{
    (void)fd;
    (void)owner;
    (void)group;
    return 0;
}

int fchmod(int fd, mode_t mode)
{
    (void)fd;
    (void)mode;
    return 0;
}

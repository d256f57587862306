/* Scratch folders for tests (tmpdir.h). */
#include "tmpdir.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool tmpdir_make(char *path, size_t size, const char *what)
{
    int n = snprintf(path, size, "/tmp/rtk-%s-XXXXXX", what);
    return n > 0 && (size_t)n < size && mkdtemp(path) != NULL;
}

static void remove_entries(const char *path)
{
    DIR *d = opendir(path);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        char child[4096];
        snprintf(child, sizeof child, "%s/%s", path, e->d_name);
        struct stat st;
        if (lstat(child, &st) == 0 && S_ISDIR(st.st_mode))
            tmpdir_remove(child);
        else
            unlink(child);
    }
    closedir(d);
}

void tmpdir_remove(const char *path)
{
    /* readdir may skip entries while the folder changes, so empty it until rmdir succeeds. */
    for (int pass = 0; pass < 8 && rmdir(path) != 0 && errno == ENOTEMPTY; pass++) remove_entries(path);
}

int tmpdir_count(const char *path)
{
    DIR *d = opendir(path);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(d);
    return n;
}

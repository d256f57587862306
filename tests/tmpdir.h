/* Scratch folders under /tmp for tests that read and write files. */
#ifndef RT_TEST_TMPDIR_H
#define RT_TEST_TMPDIR_H

#include <stdbool.h>
#include <stddef.h>

/* Creates a fresh /tmp/rtk-<what>-XXXXXX and puts its path in path[size]; false on failure. */
bool tmpdir_make(char *path, size_t size, const char *what);
/* Removes the folder and everything below it. */
void tmpdir_remove(const char *path);
/* Number of entries in the folder, without . and ..; -1 when it cannot be opened. */
int tmpdir_count(const char *path);

#endif

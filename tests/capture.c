/* Standard output caught in a file (capture.h). dup2 rather than Criterion's pipe
 * redirection: a ray tree can be larger than a pipe's buffer. */
#include "capture.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char *read_all(FILE *f)
{
    if (fseek(f, 0, SEEK_END) != 0) return NULL;
    long size = ftell(f);
    char *text = size >= 0 ? malloc((size_t)size + 1) : NULL;
    if (!text) return NULL;
    rewind(f);
    size_t got = fread(text, 1, (size_t)size, f);
    text[got] = '\0';
    return text;
}

int capture_stdout(int (*cmd)(int, char **), int argc, char **argv, char **out)
{
    *out = NULL;
    FILE *f = tmpfile();
    if (!f) return -1;
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    dup2(fileno(f), STDOUT_FILENO);
    int rc = cmd(argc, argv);
    fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    *out = read_all(f);
    fclose(f);
    return rc;
}

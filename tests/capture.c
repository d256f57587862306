/* Standard output or error caught in a file (capture.h). dup2 rather than Criterion's pipe
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

/* Calls cmd with the descriptor fd (of stream) sent to a temporary file. */
static int capture(int fd, FILE *stream, int (*cmd)(int, char **), int argc, char **argv, char **out)
{
    *out = NULL;
    FILE *f = tmpfile();
    if (!f) return -1;
    fflush(stream);
    int saved = dup(fd);
    dup2(fileno(f), fd);
    int rc = cmd(argc, argv);
    fflush(stream);
    dup2(saved, fd);
    close(saved);
    *out = read_all(f);
    fclose(f);
    return rc;
}

int capture_stdout(int (*cmd)(int, char **), int argc, char **argv, char **out)
{
    return capture(STDOUT_FILENO, stdout, cmd, argc, argv, out);
}

int capture_stderr(int (*cmd)(int, char **), int argc, char **argv, char **out)
{
    return capture(STDERR_FILENO, stderr, cmd, argc, argv, out);
}

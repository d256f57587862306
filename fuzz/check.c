/* Reporting of broken invariants; see check.h. */
#include "check.h"
#include "invariant.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void fz_fail(const char *file, int line, const char *cond, const char *fmt, ...)
{
    fprintf(stderr, "%s:%d: invariant broken: %s\n  ", file, line, cond);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    abort();
}

/* The core is built with RT_ASSERTS here: a broken invariant is a finding. */
void rt_invariant_failed(const char *file, int line, const char *condition)
{
    fz_fail(file, line, condition, "core invariant");
}

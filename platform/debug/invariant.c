/* What a hosted program linking a core built with RT_ASSERTS does when an invariant breaks
 * (core/invariant.h): say where on stderr and abort, so tests and sanitizers report it. */
#include "invariant.h"
#include <stdio.h>
#include <stdlib.h>

void rt_invariant_failed(const char *file, int line, const char *condition)
{
    fprintf(stderr, "%s:%d: invariant broken: %s\n", file, line, condition);
    abort();
}

/* Argument-parsing helpers; see cli.h. */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include "exit_codes.h"

bool rt_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    if (!s || *s < '0' || *s > '9') return false;
    errno = 0;
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return false;
    *out = (uint32_t)v;
    return true;
}

bool rt_parse_bytes(const char *s, size_t *out)
{
    if (!s || *s < '0' || *s > '9') return false;
    errno = 0;
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    unsigned shift = 0;
    if (*end == 'K' || *end == 'k') shift = 10, end++;
    else if (*end == 'M' || *end == 'm') shift = 20, end++;
    else if (*end == 'G' || *end == 'g') shift = 30, end++;
    if (errno || *end || v == 0 || v > (SIZE_MAX >> shift)) return false;
    *out = (size_t)v << shift;
    return true;
}

int rt_usage_error(const char *cmd, const char *msg, const char *arg)
{
    if (arg) fprintf(stderr, "rtk %s: %s '%s' (see rtk %s --help)\n", cmd, msg, arg, cmd);
    else fprintf(stderr, "rtk %s: %s (see rtk %s --help)\n", cmd, msg, cmd);
    return RT_EXIT_USAGE;
}

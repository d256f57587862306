/* Small helpers shared by the rtk subcommands' argument parsing. */
#ifndef RT_CLI_H
#define RT_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Parses a whole decimal integer in [lo, hi]; false on anything else. */
bool rt_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out);
/* Parses a byte count with an optional K/M/G suffix (powers of 1024). */
bool rt_parse_bytes(const char *s, size_t *out);
/* Prints "rtk <cmd>: <msg>" and a hint to stderr; returns RT_EXIT_USAGE. */
int rt_usage_error(const char *cmd, const char *msg, const char *arg);

#endif

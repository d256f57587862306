/* A strict JSON (RFC 8259) syntax check, for the subcommands' --json output. */
#ifndef RT_TEST_JSON_CHECK_H
#define RT_TEST_JSON_CHECK_H

#include <stdbool.h>

/* True when text is exactly one JSON value, with optional whitespace around it. */
bool json_is_valid(const char *text);

#endif

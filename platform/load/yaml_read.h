/* Typed reading of a YAML tree (yaml_tree.h) for the scene loader. Every reader takes a map
 * and a key, fills a default when the key is absent (or null), and reports anything
 * else that is not the expected kind as one line
 *   "<file>:<line>:<col>: <key path>: expected <what>, got <what was there>"
 * where the key path is y->path (the map being read, maintained with push/pop) plus
 * the key. A NULL map reads as an empty one, so absent sections give defaults. */
#ifndef RTP_YAML_READ_H
#define RTP_YAML_READ_H

#include "load/yaml_tree.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RTP_YAML_PATH_SIZE 512

typedef struct {
    rtp_yaml_tree tree;
    const char *file; /* as it appears in messages */
    char path[RTP_YAML_PATH_SIZE];
    size_t path_len;
    char *err;
    size_t err_size;
} rtp_yaml;

/* Reads file once ("-": standard input, named "<stdin>" in messages) and parses its
 * first document under yaml_tree.h's rules. On failure returns false with one line in
 * err; rtp_mem_refused() and rtp_input_was_output() tell a failure that is not the
 * file's fault. */
bool rtp_yaml_open(rtp_yaml *y, const char *file, char *err, size_t err_size);
void rtp_yaml_close(rtp_yaml *y);
rtp_yaml_node *rtp_yaml_root(rtp_yaml *y);

/* Appends "/segment" to the key path; rtp_yaml_pop(y, mark) restores it. */
size_t rtp_yaml_push(rtp_yaml *y, const char *segment);
void rtp_yaml_pop(rtp_yaml *y, size_t mark);

/* Writes "<file>:<line>:<col>: <path>[/key]: <message>" (the place is at's start) to
 * the error buffer; returns false so callers can `return rtp_yaml_fail(...)`. */
bool rtp_yaml_fail(rtp_yaml *y, const rtp_yaml_node *at, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* rtp_yaml_fail with "expected <what>, got <a description of at>". */
bool rtp_yaml_expected(rtp_yaml *y, const rtp_yaml_node *at, const char *key, const char *what);

/* The text of a scalar node, NULL for maps and sequences. */
const char *rtp_yaml_text(const rtp_yaml_node *n);
/* Number of pairs of a map or items of a sequence; 0 for NULL and scalars. */
size_t rtp_yaml_count(const rtp_yaml_node *n);
/* The i-th pair of a map: returns its key node and sets *value (NULL when null). */
rtp_yaml_node *rtp_yaml_pair(rtp_yaml *y, const rtp_yaml_node *map, size_t i, rtp_yaml_node **value);
rtp_yaml_node *rtp_yaml_item(rtp_yaml *y, const rtp_yaml_node *seq, size_t i);
/* The value of key in map; NULL when map is NULL, the key is absent or its value null. */
rtp_yaml_node *rtp_yaml_get(rtp_yaml *y, const rtp_yaml_node *map, const char *key);

/* True when n is a map or NULL; otherwise reports "<key>: expected a map". */
bool rtp_yaml_want_map(rtp_yaml *y, const rtp_yaml_node *n, const char *key);
/* Map and sequence values; *out = NULL when absent and not required. */
bool rtp_yaml_map(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool required, rtp_yaml_node **out);
bool rtp_yaml_seq(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool required, rtp_yaml_node **out);
/* A string; def NULL makes the key required. */
bool rtp_yaml_string(rtp_yaml *y, const rtp_yaml_node *map, const char *key, const char *def, const char **out);
/* true/false (also True/TRUE/False/FALSE). */
bool rtp_yaml_bool(rtp_yaml *y, const rtp_yaml_node *map, const char *key, bool def, bool *out);
/* A finite number in strtod syntax, whatever the YAML typing. An animated value (a map
 * with FrameValues) reads as its first frame value. */
bool rtp_yaml_real(rtp_yaml *y, const rtp_yaml_node *map, const char *key, double def, double *out);
/* A number with an integral value in [lo, hi]. */
bool rtp_yaml_uint(rtp_yaml *y, const rtp_yaml_node *map, const char *key, uint32_t def, uint32_t lo, uint32_t hi,
                   uint32_t *out);
/* A choice index: an integral value >= 0, clamped to last. */
bool rtp_yaml_index(rtp_yaml *y, const rtp_yaml_node *map, const char *key, uint32_t def, uint32_t last, uint32_t *out);

#endif

/* Typed reading of a libyaml document for the scene loader. Every reader takes a map
 * and a key, fills a default when the key is absent (or null), and reports anything
 * else that is not the expected kind as one line
 *   "<file>:<line>:<col>: <key path>: expected <what>, got <what was there>"
 * where the key path is y->path (the map being read, maintained with push/pop) plus
 * the key. A NULL map reads as an empty one, so absent sections give defaults. */
#ifndef RTP_YAML_READ_H
#define RTP_YAML_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <yaml.h>

#define RTP_YAML_PATH_SIZE 512
/* Maps and lists nested deeper are refused; well above the two levels (a map and a
 * Children list) each of scene_load's at most 1000 nested nodes takes. */
#define RTP_YAML_MAX_DEPTH 4096

typedef struct {
    yaml_document_t doc;
    const char *file; /* as it appears in messages */
    char path[RTP_YAML_PATH_SIZE];
    size_t path_len;
    char *err;
    size_t err_size;
} rtp_yaml;

/* Parses the first document of file. Documents nested deeper than RTP_YAML_MAX_DEPTH,
 * and documents in which a node is reached twice (aliases), are refused, so the
 * document is a tree and walking it is linear. */
bool rtp_yaml_open(rtp_yaml *y, const char *file, char *err, size_t err_size);
void rtp_yaml_close(rtp_yaml *y);
yaml_node_t *rtp_yaml_root(rtp_yaml *y);

/* Appends "/segment" to the key path; rtp_yaml_pop(y, mark) restores it. */
size_t rtp_yaml_push(rtp_yaml *y, const char *segment);
void rtp_yaml_pop(rtp_yaml *y, size_t mark);

/* Writes "<file>:<line>:<col>: <path>[/key]: <message>" (the place is at's start) to
 * the error buffer; returns false so callers can `return rtp_yaml_fail(...)`. */
bool rtp_yaml_fail(rtp_yaml *y, const yaml_node_t *at, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* rtp_yaml_fail with "expected <what>, got <a description of at>". */
bool rtp_yaml_expected(rtp_yaml *y, const yaml_node_t *at, const char *key, const char *what);

/* The text of a scalar node, NULL for maps and sequences. */
const char *rtp_yaml_text(const yaml_node_t *n);
/* Number of pairs of a map or items of a sequence; 0 for NULL and scalars. */
size_t rtp_yaml_count(const yaml_node_t *n);
/* The i-th pair of a map: returns its key node and sets *value (NULL when null). */
yaml_node_t *rtp_yaml_pair(rtp_yaml *y, const yaml_node_t *map, size_t i, yaml_node_t **value);
yaml_node_t *rtp_yaml_item(rtp_yaml *y, const yaml_node_t *seq, size_t i);
/* The value of key in map; NULL when map is NULL, the key is absent or its value null. */
yaml_node_t *rtp_yaml_get(rtp_yaml *y, const yaml_node_t *map, const char *key);

/* True when n is a map or NULL; otherwise reports "<key>: expected a map". */
bool rtp_yaml_want_map(rtp_yaml *y, const yaml_node_t *n, const char *key);
/* Map and sequence values; *out = NULL when absent and not required. */
bool rtp_yaml_map(rtp_yaml *y, const yaml_node_t *map, const char *key, bool required, yaml_node_t **out);
bool rtp_yaml_seq(rtp_yaml *y, const yaml_node_t *map, const char *key, bool required, yaml_node_t **out);
/* A string; def NULL makes the key required. */
bool rtp_yaml_string(rtp_yaml *y, const yaml_node_t *map, const char *key, const char *def, const char **out);
/* true/false (also True/TRUE/False/FALSE). */
bool rtp_yaml_bool(rtp_yaml *y, const yaml_node_t *map, const char *key, bool def, bool *out);
/* A finite number in strtod syntax, whatever the YAML typing. An animated value (a map
 * with FrameValues) reads as its first frame value. */
bool rtp_yaml_real(rtp_yaml *y, const yaml_node_t *map, const char *key, double def, double *out);
/* A number with an integral value in [lo, hi]. */
bool rtp_yaml_uint(rtp_yaml *y, const yaml_node_t *map, const char *key, uint32_t def, uint32_t lo, uint32_t hi,
                   uint32_t *out);
/* A choice index: an integral value >= 0, clamped to last. */
bool rtp_yaml_index(rtp_yaml *y, const yaml_node_t *map, const char *key, uint32_t def, uint32_t last, uint32_t *out);

#endif

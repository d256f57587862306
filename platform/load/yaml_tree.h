/* A YAML document as a compact tree, built in one pass over libyaml's events (libyaml's
 * own document loader takes no allocator and about 80 bytes per node; this one counts
 * every byte against --max-memory; libyaml's own buffers, at most about 1.6 times the
 * longest scalar plus 2 MB as measured, are counted as twice the input's size while it
 * parses). The tree is the first document of the stream; it
 * is refused with one line, "<file>:<line>:<col>: ...", when it
 * - nests maps and lists deeper than RTP_YAML_MAX_DEPTH;
 * - nests flow collections ([ ] { }) so deep for its size that libyaml would take more
 *   than linear time: its scanner spends, on every token, time in proportion to the flow
 *   depth (upstream yaml/libyaml#286). The sum of the flow depths of the events may be
 *   at most RTP_YAML_FLOW_WORK_PER_BYTE times the file's size plus RTP_YAML_FLOW_WORK_FREE,
 *   so parsing stays linear in the file size while small deep files still load;
 * - uses an alias (the tree would not be a tree);
 * - repeats a key in a map: both places are named. */
#ifndef RTP_YAML_TREE_H
#define RTP_YAML_TREE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Maps and lists nested deeper are refused: well above the two levels (a map and a
 * Children list) each of scene_load's at most 1000 nested nodes takes. */
#define RTP_YAML_MAX_DEPTH 4096
/* The corpus nests flow collections at most 2 deep (a sum of about 2 per event); a scene
 * of 1000 nested nodes in flow style (JSON) sums to about 8 million. */
#define RTP_YAML_FLOW_WORK_PER_BYTE 16
#define RTP_YAML_FLOW_WORK_FREE (16u << 20)

typedef enum { RTP_YAML_SCALAR, RTP_YAML_MAP, RTP_YAML_SEQ } rtp_yaml_kind;

typedef struct rtp_yaml_node {
    const char *text;      /* a scalar's value (NUL-terminated); NULL for maps and lists */
    uint32_t line, column; /* of the node's start, 1-based */
    uint32_t count;        /* map: pairs; list: items */
    uint32_t first;        /* the first child in rtp_yaml_tree.children: maps key, value, ... */
    uint8_t kind;          /* rtp_yaml_kind */
    bool is_null;          /* a plain "", "~" or "null" (any case), or tagged !!null */
} rtp_yaml_node;

typedef struct {
    rtp_yaml_node *nodes; /* nodes[0] is the root */
    uint32_t node_count;
    uint32_t *children;
    char *text; /* every scalar's value, one after the other */
} rtp_yaml_tree;

/* Parses the first document of data[0..size) (file names the input in messages). An
 * empty stream gives a tree of no nodes. On failure returns false with one line in err. */
bool rtp_yaml_tree_parse(const uint8_t *data, size_t size, const char *file, rtp_yaml_tree *out, char *err,
                         size_t err_size);
void rtp_yaml_tree_free(rtp_yaml_tree *t);

#endif

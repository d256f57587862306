/* Small helpers shared by the rtk subcommands' argument parsing. */
#ifndef RTP_CLI_H
#define RTP_CLI_H

#include "load/scene_open.h"
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Parses a whole decimal integer in [lo, hi]; false on anything else. */
bool rtp_cli_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out);
/* Parses a byte count with an optional K/M/G suffix (powers of 1024). */
bool rtp_cli_parse_bytes(const char *s, size_t *out);
/* Prints "rtk <cmd>: <msg>" and a hint to stderr; returns RTP_EXIT_USAGE. */
int rtp_cli_usage_error(const char *cmd, const char *msg, const char *arg);

/* Parses the scene option at argv[*i] (see rtp_cli_scene_option) without printing: 1 when
 * consumed (*i advanced past its value), 0 when argv[*i] is not one, -1 with *problem set
 * (a phrase to put before the option's name) when its value is wrong. */
int rtp_cli_parse_scene_option(int argc, char **argv, int *i, rtp_scene_options *opt, const char **problem);

/* The scene options every scene-reading subcommand shares (--width --height --depth
 * --aa --spp --assets --max-memory --kernel), at argv[*i]. Returns 1 when it consumed the option (and
 * its value; *i is advanced past it), 0 when argv[*i] is not one of them, or
 * RTP_EXIT_USAGE's negation after printing a usage error. */
int rtp_cli_scene_option(const char *cmd, int argc, char **argv, int *i, rtp_scene_options *opt);

/* rtp_cli_scene_option, and --help / -h, which prints usage and exits with 0: what every
 * scene command looks for first at argv[*i]. Same returns as rtp_cli_scene_option. */
int rtp_cli_common_option(const char *cmd, const char *usage, int argc, char **argv, int *i, rtp_scene_options *opt);
/* An argument no option took: the scene file the first time, else a usage error (an
 * unknown option or a second file). Returns RTP_EXIT_OK or RTP_EXIT_USAGE. */
int rtp_cli_scene_argument(const char *cmd, const char *arg, const char **scene);
/* rtp_scene_open under the cap opt->max_memory, reporting a failure as
 * "rtk <cmd>: <what went wrong>" on stderr. */
int rtp_cli_open_scene(const char *cmd, const char *path, const rtp_scene_options *opt, rtp_scene *out);
/* The scene's name in messages: the path, or "<stdin>" for "-". */
const char *rtp_cli_scene_name(const char *path);
/* Flushes standard output; a failed write there (a full disk, a closed pipe) is reported
 * as one line and gives RTP_EXIT_OUTPUT, else RTP_EXIT_OK. */
int rtp_cli_flush_stdout(const char *cmd);

#define RTP_CLI_SCENE_OPTIONS_HELP                                                                    \
    "  --width N           override the camera's Render Width (px), 1..16384\n"                       \
    "  --height N          override the camera's Render Height (px), 1..16384\n"                      \
    "  --depth N           override Maximum Recursion Depth, 0..64\n"                                 \
    "  --aa N              override Samples Per Pixel: 4^N samples per pixel, N 0..7\n"               \
    "  --spp N             the same as N samples per pixel, N a power of 4 (1, 4, ..., 16384)\n"      \
    "  --assets DIR        the folder that contains assets/ (default: found from the scene's path;\n" \
    "                      for the scene '-', read from standard input: the working folder)\n"        \
    "  --max-memory SIZE   cap on all the memory rtk allocates, e.g. 512M or 4G (default 4G)\n"       \
    "  --kernel NAME       BVH code: portable, sse2, avx2 or avx512 (default: the fastest this\n"     \
    "                      CPU runs); the image does not depend on it\n"

#endif

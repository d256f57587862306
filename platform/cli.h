/* Small helpers shared by the rtk subcommands' argument parsing. */
#ifndef RT_CLI_H
#define RT_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scene_build.h"

/* Parses a whole decimal integer in [lo, hi]; false on anything else. */
bool rt_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out);
/* Parses a byte count with an optional K/M/G suffix (powers of 1024). */
bool rt_parse_bytes(const char *s, size_t *out);
/* Prints "rtk <cmd>: <msg>" and a hint to stderr; returns RT_EXIT_USAGE. */
int rt_usage_error(const char *cmd, const char *msg, const char *arg);

/* Defaults for the options below: file values kept, 4 GiB memory cap. */
rt_build_options rt_default_build_options(void);

/* The scene options every scene-reading subcommand shares (--width --height --depth
 * --aa --spp --assets --max-memory --kernel), at argv[*i]. Returns 1 when it consumed the option (and
 * its value; *i is advanced past it), 0 when argv[*i] is not one of them, or
 * RT_EXIT_USAGE's negation after printing a usage error. */
int rt_parse_scene_option(const char *cmd, int argc, char **argv, int *i, rt_build_options *opt);

/* rt_parse_scene_option, and --help / -h, which prints usage and exits with 0: what every
 * scene command looks for first at argv[*i]. Same returns as rt_parse_scene_option. */
int rt_parse_common_option(const char *cmd, const char *usage, int argc, char **argv, int *i, rt_build_options *opt);
/* An argument no option took: the scene file the first time, else a usage error (an
 * unknown option or a second file). Returns RT_EXIT_OK or RT_EXIT_USAGE. */
int rt_take_scene_argument(const char *cmd, const char *arg, const char **scene);
/* rt_scene_open, reporting a failure as "rtk <cmd>: <what went wrong>" on stderr. */
int rt_open_scene_or_report(const char *cmd, const char *path, const rt_build_options *opt, rt_built_scene *out);

#define RT_SCENE_OPTIONS_HELP \
    "  --width N           override the camera's Render Width (px), 1..16384\n" \
    "  --height N          override the camera's Render Height (px), 1..16384\n" \
    "  --depth N           override Maximum Recursion Depth, 0..64\n" \
    "  --aa N              override Samples Per Pixel: 4^N samples per pixel, N 0..7\n" \
    "  --spp N             the same as N samples per pixel, N a power of 4 (1, 4, ..., 16384)\n" \
    "  --assets DIR        the folder that contains assets/ (default: found from the scene's path)\n" \
    "  --max-memory SIZE   cap on scene memory, e.g. 512M or 4G (default 4G)\n" \
    "  --kernel NAME       BVH code: portable, sse2 or avx2 (default: the fastest this CPU\n" \
    "                      runs); the image does not depend on it\n"

#endif

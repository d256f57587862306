/* Argument-parsing helpers; see cli.h. */
#include "cli/cli.h"

#include "cli/exit_codes.h"
#include "cli/message.h"
#include "cli/signals.h"
#include "mem/mem.h"
#include "thread/kernel.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool rtp_cli_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    if (!s || *s < '0' || *s > '9') return false;
    errno = 0;
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return false;
    *out = (uint32_t)v;
    return true;
}

bool rtp_cli_parse_bytes(const char *s, size_t *out)
{
    if (!s || *s < '0' || *s > '9') return false;
    errno = 0;
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    unsigned shift = 0;
    if (*end == 'K' || *end == 'k')
        shift = 10, end++;
    else if (*end == 'M' || *end == 'm')
        shift = 20, end++;
    else if (*end == 'G' || *end == 'g')
        shift = 30, end++;
    if (errno || *end || v == 0 || v > (SIZE_MAX >> shift)) return false;
    *out = (size_t)v << shift;
    return true;
}

int rtp_cli_usage_error(const char *cmd, const char *msg, const char *arg)
{
    if (arg)
        rtp_message(cmd, "%s '%s' (see rtk %s --help)", msg, arg, cmd);
    else
        rtp_message(cmd, "%s (see rtk %s --help)", msg, cmd);
    return RTP_EXIT_USAGE;
}

int rtp_cli_parse_scene_option(int argc, char **argv, int *i, rtp_scene_options *opt, const char **problem)
{
    const char *arg = argv[*i];
    const char *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    uint32_t n;
    if (!strcmp(arg, "--width") || !strcmp(arg, "--height")) {
        if (!rtp_cli_parse_u32(val, 1, RT_MAX_IMAGE_SIDE, &n)) return *problem = "expected 1..16384 after", -1;
        *(arg[2] == 'w' ? &opt->width : &opt->height) = n;
    } else if (!strcmp(arg, "--depth")) {
        if (!rtp_cli_parse_u32(val, 0, RT_MAX_RECURSION_DEPTH, &n)) return *problem = "expected 0..64 after", -1;
        opt->depth = (int32_t)n;
    } else if (!strcmp(arg, "--aa")) {
        if (!rtp_cli_parse_u32(val, 0, RT_MAX_SPP_INDEX, &n)) return *problem = "expected 0..7 after", -1;
        opt->aa = (int32_t)n;
    } else if (!strcmp(arg, "--spp")) {
        /* The format counts samples as 4^index: a power of 4, 1..16384. */
        if (!rtp_cli_parse_u32(val, 1, 1u << (2 * RT_MAX_SPP_INDEX), &n) || (n & (n - 1)) || !(n & 0x55555555u))
            return *problem = "expected a power of 4 (1, 4, 16, ..., 16384) after", -1;
        opt->aa = __builtin_ctz(n) / 2;
    } else if (!strcmp(arg, "--assets")) {
        if (!val) return *problem = "missing folder after", -1;
        opt->assets_root = val;
    } else if (!strcmp(arg, "--max-memory")) {
        if (!rtp_cli_parse_bytes(val, &opt->max_memory)) return *problem = "expected a size such as 512M after", -1;
    } else if (!strcmp(arg, "--kernel")) {
        if (!rtp_kernel_parse(val, &opt->kernel)) return *problem = "expected portable, sse2, avx2 or avx512 after", -1;
        if (!rtp_kernel_runs(opt->kernel)) return *problem = "this CPU or build cannot run the kernel given by", -1;
        opt->kernel_forced = true;
    } else {
        return 0;
    }
    (*i)++;
    return 1;
}

int rtp_cli_scene_option(const char *cmd, int argc, char **argv, int *i, rtp_scene_options *opt)
{
    const char *problem;
    int rc = rtp_cli_parse_scene_option(argc, argv, i, opt, &problem);
    return rc < 0 ? -rtp_cli_usage_error(cmd, problem, argv[*i]) : rc;
}

int rtp_cli_common_option(const char *cmd, const char *usage, int argc, char **argv, int *i, rtp_scene_options *opt)
{
    const char *arg = argv[*i];
    if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
        fputs(usage, stdout);
        exit(rtp_cli_flush_stdout(cmd));
    }
    return rtp_cli_scene_option(cmd, argc, argv, i, opt);
}

int rtp_cli_scene_argument(const char *cmd, const char *arg, const char **scene)
{
    if (arg[0] == '-' && arg[1]) return rtp_cli_usage_error(cmd, "unknown option", arg);
    if (*scene) return rtp_cli_usage_error(cmd, "unexpected argument", arg);
    *scene = arg;
    return RTP_EXIT_OK;
}

const char *rtp_cli_scene_name(const char *path) { return strcmp(path, "-") ? path : "<stdin>"; }

int rtp_cli_open_scene(const char *cmd, const char *path, const rtp_scene_options *opt, rtp_scene *out)
{
    char err[RTP_ERR_SIZE];
    rtp_mem_set_cap(opt->max_memory);
    int rc = rtp_scene_open(path, opt, out, err, sizeof err);
    if (rc != RTP_EXIT_OK) rtp_message(cmd, "%s", err);
    return rc;
}

int rtp_cli_flush_stdout(const char *cmd)
{
    int e = fflush(stdout) == 0 ? 0 : errno;
    if (e == 0 && ferror(stdout)) e = EIO;
    if (e == 0) return RTP_EXIT_OK;
    rtp_message(cmd, "cannot write to standard output: %s", strerror(e));
    return RTP_EXIT_OUTPUT;
}

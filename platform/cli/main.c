/* rtk: the command line. Dispatches to one subcommand per file. */
#include "cli/compare_cmd.h"
#include "cli/debug_cmd.h"
#include "cli/exit_codes.h"
#include "cli/info_cmd.h"
#include "cli/pack_cmd.h"
#include "cli/render_cmd.h"
#include "cli/stitch_cmd.h"
#include "cli/verify_cmd.h"
#include "cli/version.h"
#include <stdio.h>
#include <string.h>

static const char usage[] =
    "usage: rtk COMMAND [ARGS]\n"
    "\n"
    "rtk is a ray tracer for the CSE457 scene format whose renders are bitwise\n"
    "reproducible.\n"
    "\n"
    "commands:\n"
    "  render SCENE.yaml -o OUT.png   render a scene (rtk render --help)\n"
    "  compare A B                    compare two images (rtk compare --help)\n"
    "  debug SCENE.yaml --pixel X,Y   every ray behind one pixel (rtk debug --help)\n"
    "  info SCENE.yaml                what a scene holds and costs (rtk info --help)\n"
    "  pack SCENE.yaml -o OUT         the scene as one blob for bare-metal and cross builds\n"
    "  stitch PART... -o OUT.png      the parts of a distributed render as one frame\n"
    "                                 (rtk stitch --help)\n"
    "  verify MANIFEST                render hashes checked, as sha256sum -c (rtk verify --help)\n"
    "  --version                      version, build (double/fixed), compiler and commit\n"
    "\n"
    "Exit codes: 0 ok, 1 a compare threshold or a verify hash not met, 2 bad arguments,\n"
    "3 bad or missing input file, 4 output not writable, 5 over the memory cap,\n"
    "6 interrupted.\n";

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs("rtk: no command given (see rtk --help)\n", stderr);
        return RTP_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        fputs(usage, stdout);
        return RTP_EXIT_OK;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        puts(rtp_version_line());
        return RTP_EXIT_OK;
    }
    if (!strcmp(cmd, "render")) return rtp_cmd_render(argc - 1, argv + 1);
    if (!strcmp(cmd, "compare")) return rtp_cmd_compare(argc - 1, argv + 1);
    if (!strcmp(cmd, "debug")) return rtp_cmd_debug(argc - 1, argv + 1);
    if (!strcmp(cmd, "info")) return rtp_cmd_info(argc - 1, argv + 1);
    if (!strcmp(cmd, "pack")) return rtp_cmd_pack(argc - 1, argv + 1);
    if (!strcmp(cmd, "stitch")) return rtp_cmd_stitch(argc - 1, argv + 1);
    if (!strcmp(cmd, "verify")) return rtp_cmd_verify(argc - 1, argv + 1);
    fprintf(stderr, "rtk: unknown command '%s' (see rtk --help)\n", cmd);
    return RTP_EXIT_USAGE;
}

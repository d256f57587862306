/* `rtk compare`. */
#ifndef RTP_COMPARE_CMD_H
#define RTP_COMPARE_CMD_H

/* `rtk compare A B [--diff OUT] [--min-psnr DB] [--max-diff N] [--json]`; argv[0] is "compare".
 * Returns an RTP_EXIT_* code. */
int rtp_cmd_compare(int argc, char **argv);

#endif

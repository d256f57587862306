/* The `rtk stitch` subcommand. */
#ifndef RTP_STITCH_CMD_H
#define RTP_STITCH_CMD_H

int rtp_cmd_stitch(int argc, char **argv);

#endif

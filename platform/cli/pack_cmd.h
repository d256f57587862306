/* The `rtk pack` subcommand. */
#ifndef RTP_PACK_CMD_H
#define RTP_PACK_CMD_H

int rtp_cmd_pack(int argc, char **argv);

#endif

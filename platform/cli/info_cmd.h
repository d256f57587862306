/* The `rtk info` subcommand. */
#ifndef RTP_INFO_CMD_H
#define RTP_INFO_CMD_H

/* `rtk info SCENE.yaml [--json]`; argv[0] is "info". Returns an RTP_EXIT_* code. */
int rtp_cmd_info(int argc, char **argv);

#endif

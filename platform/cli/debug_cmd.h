/* The `rtk debug` subcommand. */
#ifndef RTP_DEBUG_CMD_H
#define RTP_DEBUG_CMD_H

/* `rtk debug SCENE.yaml --pixel X,Y [...]`; argv[0] is "debug". Returns an RTP_EXIT_* code. */
int rtp_cmd_debug(int argc, char **argv);

#endif

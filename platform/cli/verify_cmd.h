/* `rtk verify`. */
#ifndef RTP_VERIFY_CMD_H
#define RTP_VERIFY_CMD_H

/* `rtk verify MANIFEST [--junit FILE]` and `rtk verify --write MANIFEST SCENE...`; argv[0] is
 * "verify". Returns an RTP_EXIT_* code. */
int rtp_cmd_verify(int argc, char **argv);

#endif

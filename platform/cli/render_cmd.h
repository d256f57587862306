/* The `rtk render` subcommand. */
#ifndef RTP_RENDER_CMD_H
#define RTP_RENDER_CMD_H

int rtp_cmd_render(int argc, char **argv);

#endif

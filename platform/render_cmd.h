/* The `rtk render` subcommand. */
#ifndef RT_RENDER_CMD_H
#define RT_RENDER_CMD_H

int rt_cmd_render(int argc, char **argv);

#endif

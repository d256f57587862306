/* The `rtk pack` subcommand. */
#ifndef RT_PACK_CMD_H
#define RT_PACK_CMD_H

int rt_cmd_pack(int argc, char **argv);

#endif

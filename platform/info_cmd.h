/* The `rtk info` subcommand. */
#ifndef RT_INFO_CMD_H
#define RT_INFO_CMD_H

/* `rtk info SCENE.yaml [--json]`; argv[0] is "info". Returns an RT_EXIT_* code. */
int rt_cmd_info(int argc, char **argv);

#endif

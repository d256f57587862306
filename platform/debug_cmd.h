/* The `rtk debug` subcommand. */
#ifndef RT_DEBUG_CMD_H
#define RT_DEBUG_CMD_H

/* `rtk debug SCENE.yaml --pixel X,Y [...]`; argv[0] is "debug". Returns an RT_EXIT_* code. */
int rt_cmd_debug(int argc, char **argv);

#endif

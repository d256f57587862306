/* What the bare-metal driver needs from the board: text out, a clock, and exit. */
#ifndef RT_BOARD_H
#define RT_BOARD_H

#include <stddef.h>
#include <stdint.h>

void rt_board_print(const char *text);
uint32_t rt_board_centiseconds(void);
void rt_board_exit(int status);

#endif

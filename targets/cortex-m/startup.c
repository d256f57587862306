/* Reset, fault handlers and semihosting for a Cortex-M3 with no operating system. */
#include "board.h"

extern uint32_t _data_load, _data_start, _data_end, _bss_start, _bss_end, _stack_top;
int main(void);

/* Arm semihosting: a breakpoint the debugger (here qemu) services. */
static uint32_t semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void rt_board_print(const char *text) { semihost(0x04, text); /* SYS_WRITE0 */ }

uint32_t rt_board_centiseconds(void) { return semihost(0x10, 0); /* SYS_CLOCK */ }

void rt_board_exit(int status)
{
    /* SYS_EXIT with ADP_Stopped_ApplicationExit (0) or RunTimeErrorUnknown (failure). */
    semihost(0x18, (const void *)(uintptr_t)(status == 0 ? 0x20026u : 0x20023u));
    for (;;) {
    }
}

static void fault(void)
{
    rt_board_print("rtk: fault\n");
    rt_board_exit(1);
}

void rt_reset(void)
{
    for (uint32_t *src = &_data_load, *dst = &_data_start; dst < &_data_end;) *dst++ = *src++;
    for (uint32_t *p = &_bss_start; p < &_bss_end;) *p++ = 0;
    rt_board_exit(main());
}

/* Initial stack pointer, then the handlers: reset, NMI, hard fault, and the other faults. */
__attribute__((section(".vectors"), used)) static const void *const vectors[] = {
    &_stack_top, (void *)rt_reset, (void *)fault, (void *)fault, (void *)fault, (void *)fault, (void *)fault,
};

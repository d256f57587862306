/* platform/cli/signals.h for WebAssembly: WASI delivers no signals to a module (the page
 * cancels a render between tiles itself, web/app), so there is nothing to install,
 * track or undo, and a render is never stopped from here. */
#include "cli/exit_codes.h"
#include "cli/signals.h"

static volatile int never_stopped;

void rtp_signals_install(const char *cmd, const char *subject)
{
    (void)cmd;
    (void)subject;
}

volatile int *rtp_signals_defer(void) { return &never_stopped; }
void rtp_signals_immediate(void) {}
int rtp_signals_stopped(void) { return RTP_EXIT_INTERRUPTED; }
void rtp_signals_track(const char *temp_path) { (void)temp_path; }
void rtp_signals_streaming(const char *name) { (void)name; }
void rtp_signals_hold(void) {}
void rtp_signals_release(void) {}

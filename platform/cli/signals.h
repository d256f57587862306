/* SIGINT, SIGTERM and SIGHUP end every command in every phase with exit 6 and one line,
 * "rtk <cmd>: <subject>: interrupted; nothing written", and leave no output behind; a
 * signal the parent set to be ignored stays ignored. Two ways to stop:
 * - immediate (the default): the handler removes the temporary output file being
 *   written, if any, writes the line and calls _exit(6). Loading, building and encoding
 *   hold nothing else that must be undone: outputs reach their place only by rename.
 * - deferred (around the render): the handler only raises the flag the render checks
 *   between tiles, and the command stops, frees what it holds and returns 6.
 * Once an output is in place (rtp_signals_hold) the command finishes whatever arrives.
 * SIGPIPE is ignored: a closed standard output is a write error (exit 4), not a kill. */
#ifndef RTP_SIGNALS_H
#define RTP_SIGNALS_H

/* Installs the handlers; subject (a file name, or NULL) goes into the line. */
void rtp_signals_install(const char *cmd, const char *subject);
/* Switches to deferred stopping; returns the flag that becomes non-zero on a signal. */
volatile int *rtp_signals_defer(void);
/* Back to immediate stopping; a signal caught while deferred stops the process now. */
void rtp_signals_immediate(void);
/* Prints the interrupted line (after a deferred stop) and returns 6. */
int rtp_signals_stopped(void);

/* The temporary file a signal must remove (NULL: none). */
void rtp_signals_track(const char *temp_path);
/* While an output streams to a device, FIFO or standard output, which cannot be taken
 * back, the line says "interrupted; <name> is incomplete" instead (NULL: back). */
void rtp_signals_streaming(const char *name);
/* Blocks the signals until exit: the output is about to be put in place, and a signal
 * that arrives from now on no longer stops the command. Also blocks them around
 * creating a temporary file, so it is tracked before a handler could miss it. Both do
 * nothing before rtp_signals_install: in the library, the caller's signals are its own. */
void rtp_signals_hold(void);
void rtp_signals_release(void);

#endif

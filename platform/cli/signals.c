/* Stopping on SIGINT, SIGTERM and SIGHUP (see signals.h). The handler uses only
 * async-signal-safe calls and a lock-free atomic: unlink, write, pause, _exit. */
#include "cli/signals.h"

#include "cli/exit_codes.h"
#include "cli/message.h"
#include <limits.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static const int stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

static volatile int stop_flag;
static volatile sig_atomic_t deferred, tracked, streaming;
static char message[2048], stream_message[2048 + PATH_MAX], temp_path[PATH_MAX];
static size_t message_len, stream_message_len;

static atomic_flag stopping = ATOMIC_FLAG_INIT;

/* One caller ends the process. A process-directed signal can reach each thread (timeout
 * sends it to the command and again to its process group), and the main thread can stop
 * after a deferred signal while a handler runs: the others wait for the _exit. */
static void stop_now(void)
{
    if (atomic_flag_test_and_set(&stopping))
        for (;;) pause();
    if (tracked) unlink(temp_path);
    if (streaming)
        (void)!write(STDERR_FILENO, stream_message, stream_message_len);
    else
        (void)!write(STDERR_FILENO, message, message_len);
    _exit(RTP_EXIT_INTERRUPTED);
}

static void on_signal(int sig)
{
    (void)sig;
    stop_flag = 1;
    if (!deferred) stop_now();
}

/* "rtk <cmd>: [<subject>: ]<what>\n", escaped as every message is. */
static size_t compose(char *out, size_t size, const char *cmd, const char *subject, const char *what)
{
    char raw[1024], escaped[sizeof message - 64];
    snprintf(raw, sizeof raw, "%s%s%s", subject ? subject : "", subject ? ": " : "", what);
    rtp_message_escape(raw, escaped, sizeof escaped);
    snprintf(out, size, "rtk %s: %s\n", cmd, escaped);
    return strlen(out);
}

static char command[32], subject_copy[1024];
static bool has_subject, installed;

void rtp_signals_install(const char *cmd, const char *subject)
{
    snprintf(command, sizeof command, "%s", cmd);
    installed = true;
    has_subject = subject != NULL;
    snprintf(subject_copy, sizeof subject_copy, "%s", subject ? subject : "");
    message_len =
        compose(message, sizeof message, command, has_subject ? subject_copy : NULL, "interrupted; nothing written");
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof stop_signals / sizeof stop_signals[0]; i++) sigaddset(&sa.sa_mask, stop_signals[i]);
    sa.sa_flags = SA_RESTART;
    for (size_t i = 0; i < sizeof stop_signals / sizeof stop_signals[0]; i++) {
        struct sigaction old;
        if (sigaction(stop_signals[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        sigaction(stop_signals[i], &sa, NULL);
    }
    signal(SIGPIPE, SIG_IGN);
}

volatile int *rtp_signals_defer(void)
{
    deferred = 1;
    return &stop_flag;
}

void rtp_signals_immediate(void)
{
    deferred = 0;
    if (stop_flag) stop_now();
}

int rtp_signals_stopped(void)
{
    (void)!write(STDERR_FILENO, message, message_len);
    return RTP_EXIT_INTERRUPTED;
}

void rtp_signals_track(const char *temp)
{
    tracked = 0;
    if (!temp || strlen(temp) >= sizeof temp_path) return;
    memcpy(temp_path, temp, strlen(temp) + 1);
    tracked = 1;
}

void rtp_signals_streaming(const char *name)
{
    if (name) {
        char what[PATH_MAX + 32];
        snprintf(what, sizeof what, "interrupted; %s is incomplete", strcmp(name, "-") ? name : "the standard output");
        stream_message_len =
            compose(stream_message, sizeof stream_message, command, has_subject ? subject_copy : NULL, what);
    }
    streaming = name != NULL;
}

static void mask(int how)
{
    sigset_t set;
    sigemptyset(&set);
    for (size_t i = 0; i < sizeof stop_signals / sizeof stop_signals[0]; i++) sigaddset(&set, stop_signals[i]);
    pthread_sigmask(how, &set, NULL);
}

/* Only for a command: the library (rtk_write_image) leaves its caller's signals alone. */
void rtp_signals_hold(void)
{
    if (installed) mask(SIG_BLOCK);
}
void rtp_signals_release(void)
{
    if (installed) mask(SIG_UNBLOCK);
}

/* Stopping on signals (platform/cli/signals.h), each case in a child process of its own,
 * as a command would run: the exit status, the one line on stderr, the file removed. */
#include "cli/signals.h"
#include "image/file_write.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64], temp[128];

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "signals"), "cannot create a scratch folder"); }

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(signals, .init = setup, .fini = teardown);

/* Runs body in a child with stderr into line; returns the exit status (-signal if killed). */
static int run_child(void (*body)(void), char *line, size_t size)
{
    int fds[2];
    cr_assert_eq(pipe(fds), 0);
    pid_t pid = fork();
    cr_assert(pid >= 0);
    if (pid == 0) {
        dup2(fds[1], STDERR_FILENO);
        close(fds[0]);
        body();
        _exit(0);
    }
    close(fds[1]);
    size_t got = 0;
    ssize_t n;
    while (got + 1 < size && (n = read(fds[0], line + got, size - 1 - got)) > 0) got += (size_t)n;
    line[got] = '\0';
    close(fds[0]);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

static void make_temp(void)
{
    snprintf(temp, sizeof temp, "%s/.rtk-1-0.tmp", dir);
    FILE *f = fopen(temp, "w");
    cr_assert_not_null(f);
    fclose(f);
}

static void stop_while_writing(void)
{
    rtp_signals_install("render", "scene.yaml");
    rtp_signals_track(temp);
    raise(SIGINT);
}

Test(signals, a_stop_removes_the_temporary_output_and_exits_6)
{
    char line[256];
    make_temp();
    cr_expect_eq(run_child(stop_while_writing, line, sizeof line), 6);
    cr_expect_str_eq(line, "rtk render: scene.yaml: interrupted; nothing written\n");
    struct stat st;
    cr_expect_neq(stat(temp, &st), 0, "the temporary file is still there");
}

static void stop_while_deferred(void)
{
    rtp_signals_install("render", "scene.yaml");
    volatile int *flag = rtp_signals_defer();
    raise(SIGTERM);
    if (*flag) _exit(rtp_signals_stopped());
}

Test(signals, a_deferred_stop_raises_the_flag_and_the_command_returns_6)
{
    char line[256];
    cr_expect_eq(run_child(stop_while_deferred, line, sizeof line), 6);
    cr_expect_str_eq(line, "rtk render: scene.yaml: interrupted; nothing written\n");
}

/* Eight threads each get a SIGTERM at once, as when timeout signals the command and then
 * its process group while the loader's workers run: one handler ends the process. */
enum { SIGNALLED_THREADS = 8 };
static pthread_barrier_t all_started;

static void *signal_myself(void *unused)
{
    (void)unused;
    pthread_barrier_wait(&all_started);
    pthread_kill(pthread_self(), SIGTERM);
    pause(); /* the handler does not return: it ends the process or waits for the end */
    return NULL;
}

static void stop_on_every_thread(void)
{
    rtp_signals_install("verify", "m.txt");
    pthread_t threads[SIGNALLED_THREADS];
    pthread_barrier_init(&all_started, NULL, SIGNALLED_THREADS + 1);
    for (int i = 0; i < SIGNALLED_THREADS; i++) pthread_create(&threads[i], NULL, signal_myself, NULL);
    pthread_barrier_wait(&all_started);
    for (;;) pause();
}

Test(signals, signals_on_several_threads_print_one_line)
{
    for (int run = 0; run < 50; run++) {
        char line[2048];
        cr_assert_eq(run_child(stop_on_every_thread, line, sizeof line), 6);
        cr_assert_str_eq(line, "rtk verify: m.txt: interrupted; nothing written\n", "run %d", run);
    }
}

static void ignored_by_the_parent(void)
{
    signal(SIGHUP, SIG_IGN); /* as nohup does */
    rtp_signals_install("info", "scene.yaml");
    raise(SIGHUP);
}

Test(signals, a_signal_the_parent_ignored_stays_ignored)
{
    char line[256];
    cr_expect_eq(run_child(ignored_by_the_parent, line, sizeof line), 0);
    cr_expect_str_eq(line, "");
}

static void after_the_output_is_in_place(void)
{
    rtp_signals_install("pack", "scene.yaml");
    rtp_signals_hold();
    raise(SIGINT);
}

Test(signals, once_held_the_command_finishes)
{
    char line[256];
    cr_expect_eq(run_child(after_the_output_is_in_place, line, sizeof line), 0);
    cr_expect_str_eq(line, "");
}

static void stop_while_streaming(void)
{
    rtp_signals_install("compare", NULL);
    rtp_signals_streaming("diff.ppm");
    raise(SIGINT);
}

Test(signals, a_stream_cut_short_is_named)
{
    char line[256];
    cr_expect_eq(run_child(stop_while_streaming, line, sizeof line), 6);
    cr_expect_str_eq(line, "rtk compare: interrupted; diff.ppm is incomplete\n");
}

static void stop_with_a_newline_in_the_name(void)
{
    rtp_signals_install("info", "a\nb.yaml");
    raise(SIGINT);
}

Test(signals, the_line_is_escaped)
{
    char line[256];
    cr_expect_eq(run_child(stop_with_a_newline_in_the_name, line, sizeof line), 6);
    cr_expect_str_eq(line, "rtk info: a\\nb.yaml: interrupted; nothing written\n");
}

static void sigpipe_is_an_error(void)
{
    rtp_signals_install("info", "scene.yaml");
    raise(SIGPIPE);
}

Test(signals, sigpipe_does_not_kill)
{
    char line[256];
    cr_expect_eq(run_child(sigpipe_is_an_error, line, sizeof line), 0);
}

/* The library (rtk_write_image) writes through the same writer, which blocks the signals
 * before its rename in a command; without rtp_signals_install they stay the caller's. */
Test(signals, a_write_without_install_leaves_the_signals_alone)
{
    char path[128], err[256];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    cr_assert(rtp_file_write(path, "x", 1, err, sizeof err), "%s", err);
    sigset_t now;
    cr_assert_eq(pthread_sigmask(SIG_BLOCK, NULL, &now), 0);
    cr_expect_not(sigismember(&now, SIGINT) || sigismember(&now, SIGTERM) || sigismember(&now, SIGHUP),
                  "the writer left the signals blocked");
}

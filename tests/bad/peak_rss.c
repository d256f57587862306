/* Runs a command and writes its peak resident set size in KiB (getrusage of the
 * child: ru_maxrss) to the file named by the first argument; exits as the command did
 * (128 + n for signal n). SIGINT, SIGTERM and SIGHUP are passed on to the command, and
 * the command starts with the dispositions this was given (an ignored signal stays
 * ignored). Built and used by tests/bad/run.sh for the memory-cap checks.
 *   peak_rss OUT_FILE COMMAND [ARG...] */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

static pid_t child;

static void pass_on(int sig) { kill(child, sig); }

int main(int argc, char **argv)
{
    if (argc < 3) {
        fputs("usage: peak_rss OUT_FILE COMMAND [ARG...]\n", stderr);
        return 125;
    }
    pid_t pid = fork();
    if (pid < 0) return perror("fork"), 125;
    if (pid == 0) {
        execvp(argv[2], argv + 2);
        perror(argv[2]);
        _exit(127);
    }
    child = pid;
    static const int passed[] = {SIGINT, SIGTERM, SIGHUP};
    for (int i = 0; i < 3; i++) {
        struct sigaction old, sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = pass_on;
        sa.sa_flags = SA_RESTART;
        if (sigaction(passed[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(passed[i], &sa, NULL);
    }
    int status;
    struct rusage usage;
    pid_t got;
    while ((got = wait4(pid, &status, 0, &usage)) < 0 && errno == EINTR) {
    }
    if (got != pid) return perror("wait4"), 125;
    FILE *out = fopen(argv[1], "w");
    if (!out) return perror(argv[1]), 125;
    fprintf(out, "%ld\n", usage.ru_maxrss);
    fclose(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Running an rtk subcommand in-process with its standard output or error caught in a file. */
#ifndef RT_TEST_CAPTURE_H
#define RT_TEST_CAPTURE_H

/* Calls cmd(argc, argv) with stdout sent to a temporary file; returns its exit code and puts
 * everything it printed in *out (malloc'd, NUL-terminated; NULL if it could not be read). */
int capture_stdout(int (*cmd)(int, char **), int argc, char **argv, char **out);
/* The same for standard error. */
int capture_stderr(int (*cmd)(int, char **), int argc, char **argv, char **out);

#endif

/* The rtk command's exit codes (documented in README.md). */
#ifndef RT_EXIT_CODES_H
#define RT_EXIT_CODES_H

enum {
    RT_EXIT_OK = 0,
    RT_EXIT_THRESHOLD = 1, /* compare: a --min-psnr / --max-diff threshold was not met */
    RT_EXIT_USAGE = 2,     /* bad command line */
    RT_EXIT_INPUT = 3,     /* a scene, mesh, texture or image is missing, unreadable or invalid */
    RT_EXIT_OUTPUT = 4,    /* the output file could not be written */
    RT_EXIT_MEMORY = 5,    /* the scene needs more memory than --max-memory allows */
    RT_EXIT_INTERRUPTED = 6, /* stopped by a signal; nothing was written */
};

#endif

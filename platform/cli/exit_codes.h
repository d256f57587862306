/* The rtk command's exit codes (documented in README.md). */
#ifndef RTP_EXIT_CODES_H
#define RTP_EXIT_CODES_H

enum {
    RTP_EXIT_OK = 0,
    RTP_EXIT_THRESHOLD = 1,   /* compare: a --min-psnr / --max-diff threshold was not met */
    RTP_EXIT_USAGE = 2,       /* bad command line */
    RTP_EXIT_INPUT = 3,       /* a scene, mesh, texture or image is missing, unreadable or invalid */
    RTP_EXIT_OUTPUT = 4,      /* the output file could not be written */
    RTP_EXIT_MEMORY = 5,      /* the scene needs more memory than --max-memory allows */
    RTP_EXIT_INTERRUPTED = 6, /* stopped by a signal; nothing was written */
};

#endif

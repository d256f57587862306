/* What `rtk --version` prints: the library version, the build, the compiler, the commit. */
#ifndef RTP_VERSION_H
#define RTP_VERSION_H

/* One line without a newline, e.g. "rtk 0.5.0 (double build; gcc 12.2.0; commit 1a2b3c4d5e6f)".
 * Distributed parts carry it, so parts from different builds are never stitched together. */
const char *rtp_version_line(void);

#endif

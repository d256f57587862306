/* The checks `rtk stitch` makes before it trusts a set of parts: one render, and a frame
 * covered exactly once. Each failure is one line naming the part and the problem. */
#ifndef RTP_PART_STITCH_H
#define RTP_PART_STITCH_H

#include "part/part.h"

/* True when part (read from file `name`) names the same render as `reference` (fields
 * RTP_PART_BUILD .. RTP_PART_FRAME equal; the version lines may differ in the compiler
 * only); else false with e.g. "b.png: other settings than a.png: 'depth=3 aa=1' vs
 * 'depth=3 aa=0'" in err. */
bool rtp_stitch_same_render(const rtp_part *part, const char *name, const rtp_part *reference,
                            const char *reference_name, char *err, size_t err_size);

/* True when the parts (of one render) cover its frame exactly once; else false with the
 * first overlap or duplicate, or the first pixel no part covers (the missing part's
 * index when the parts are --part I/N of one N), in err. */
bool rtp_stitch_coverage(const rtp_part *parts, const char *const *names, uint32_t count, char *err, size_t err_size);

#endif

/* What `rtk render --region / --part` adds to a render: the rectangle to render and the
 * description a part carries (docs/distributed.md). */
#ifndef RTP_RENDER_PART_H
#define RTP_RENDER_PART_H

#include "load/scene_open.h"
#include "part/part.h"

typedef struct {
    bool wanted;
    rt_rect region;        /* --region, before it is checked against the frame */
    uint32_t index, count; /* --part I/N; count 0 for --region */
} rtp_part_request;

/* Parses --region or --part at argv[*i] into req. Returns 1 when it consumed the option
 * and its value (*i advanced), 0 when argv[*i] is neither, or the negated RTP_EXIT_USAGE
 * after printing a usage error for `cmd`. */
int rtp_part_request_option(const char *cmd, int argc, char **argv, int *i, rtp_part_request *req);

/* Checks req against the opened scene's frame, cuts the frame for --part, and describes
 * the part (everything but its pixel digest) in *part. Returns RTP_EXIT_OK, or an exit
 * code after printing one line for `cmd`. */
int rtp_part_plan(const char *cmd, const char *scene_path, const rtp_scene *scene, const rtp_part_request *req,
                  uint32_t threads, rtp_part *part);

#endif

/* rtp_part_request_option and rtp_part_plan; see render_part.h. */
#include "cli/render_part.h"

#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "cli/version.h"
#include "part/part_cut.h"
#include "part/part_identity.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rtp_part_request_option(const char *cmd, int argc, char **argv, int *i, rtp_part_request *req)
{
    const char *arg = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    bool region = !strcmp(arg, "--region");
    if (!region && strcmp(arg, "--part")) return 0;
    if (req->wanted) return -rtp_cli_usage_error(cmd, "give one --region or --part, not two: second is", arg);
    if (region && !rtp_part_parse_rect(val, &req->region))
        return -rtp_cli_usage_error(cmd, "expected X0,Y0,X1,Y1 with X0 < X1 and Y0 < Y1 after", arg);
    if (!region && !rtp_part_parse_index(val, RT_MAX_IMAGE_SIDE, &req->index, &req->count))
        return -rtp_cli_usage_error(cmd, "expected I/N with 0 <= I < N <= 16384 after", arg);
    req->wanted = true;
    (*i)++;
    return 1;
}

/* The rectangle the request stands for, or a usage error when it does not fit the frame. */
static int place(const char *cmd, const rtp_scene *scene, const rtp_part_request *req, uint32_t threads, rtp_part *part)
{
    const rt_camera *cam = &scene->scene.camera;
    char msg[160];
    if (!req->count) {
        if (req->region.x1 > cam->width || req->region.y1 > cam->height) {
            snprintf(msg, sizeof msg, "--region %u,%u,%u,%u lies outside the %ux%u frame", req->region.x0,
                     req->region.y0, req->region.x1, req->region.y1, cam->width, cam->height);
            return rtp_cli_usage_error(cmd, msg, NULL);
        }
        part->region = req->region;
        return RTP_EXIT_OK;
    }
    if (req->count > cam->height) {
        snprintf(msg, sizeof msg, "--part %u/%u: more parts than the frame's %u rows", req->index, req->count,
                 cam->height);
        return rtp_cli_usage_error(cmd, msg, NULL);
    }
    uint32_t *starts = malloc(((size_t)req->count + 1) * sizeof *starts);
    if (!starts || !rtp_part_cut(&scene->scene, req->count, threads, starts)) {
        free(starts);
        fprintf(stderr, "rtk %s: out of memory cutting the frame into %u parts\n", cmd, req->count);
        return RTP_EXIT_MEMORY;
    }
    part->region = rtp_part_band(&scene->scene, starts, req->index);
    part->index = req->index;
    part->count = req->count;
    free(starts);
    return RTP_EXIT_OK;
}

int rtp_part_plan(const char *cmd, const char *scene_path, const rtp_scene *scene, const rtp_part_request *req,
                  uint32_t threads, rtp_part *part)
{
    char err[RTP_ERR_SIZE];
    memset(part, 0, sizeof *part);
    int rc = rtp_part_identify(scene_path, rtp_version_line(), scene, part, err, sizeof err);
    if (rc != RTP_EXIT_OK) {
        fprintf(stderr, "rtk %s: %s\n", cmd, err);
        return rc;
    }
    rc = place(cmd, scene, req, threads, part);
    if (rc == RTP_EXIT_OK && !rtp_part_format_place(part)) {
        fprintf(stderr, "rtk %s: %s: out of memory describing the part\n", cmd, scene_path);
        rc = RTP_EXIT_MEMORY;
    }
    if (rc != RTP_EXIT_OK) rtp_part_free(part);
    return rc;
}

/* What names a render in its parts: rtk's version and build, the digests of the scene
 * file and of every asset file the loader read, and the settings that change pixels. */
#ifndef RTP_PART_IDENTITY_H
#define RTP_PART_IDENTITY_H

#include "load/scene_open.h"
#include "part/part.h"

/* Sets out's fields RTP_PART_BUILD .. RTP_PART_FRAME (and width, height) for the scene
 * opened from scene_path, by the rtk whose `rtk --version` line is version. The files are
 * read again to digest them, right after loading. Returns RTP_EXIT_OK, or RTP_EXIT_INPUT /
 * RTP_EXIT_MEMORY with one line in err. */
int rtp_part_identify(const char *scene_path, const char *version, const rtp_scene *scene, rtp_part *out, char *err,
                      size_t err_size);

#endif

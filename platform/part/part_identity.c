/* rtp_part_identify; see part_identity.h. */
#include "part/part_identity.h"

#include "cli/exit_codes.h"
#include "sha256.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#if defined(RT_REAL_FIXED)
#define RTP_BUILD_NAME "fixed"
#else
#define RTP_BUILD_NAME "double"
#endif

/* The SHA-256 of a file's bytes, as lowercase hex. */
static bool file_digest(const char *path, char hex[65], char *err, size_t err_size)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, err_size, "%s: cannot read it again to digest it: %s", path, strerror(errno));
        return false;
    }
    rt_sha256 h;
    rt_sha256_init(&h);
    uint8_t buf[1 << 16];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) != 0) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            snprintf(err, err_size, "%s: cannot read it again to digest it: %s", path, strerror(errno));
            close(fd);
            return false;
        }
        rt_sha256_update(&h, buf, (size_t)n);
    }
    close(fd);
    uint8_t digest[32];
    rt_sha256_final(&h, digest);
    rtp_part_hex(digest, hex);
    return true;
}

/* One digest per asset file, a line each, or "none". */
static int asset_digests(const rtp_loaded_scene *l, rtp_part *out, char *err, size_t err_size)
{
    if (l->asset_count == 0) return rtp_part_set(out, RTP_PART_ASSETS, "none") ? RTP_EXIT_OK : RTP_EXIT_MEMORY;
    char *text = malloc((size_t)l->asset_count * 65);
    if (!text) return RTP_EXIT_MEMORY;
    for (uint32_t i = 0; i < l->asset_count; i++) {
        if (!file_digest(l->asset_paths[i], text + (size_t)i * 65, err, err_size)) {
            free(text);
            return RTP_EXIT_INPUT;
        }
        text[(size_t)i * 65 + 64] = i + 1 < l->asset_count ? '\n' : '\0';
    }
    free(out->text[RTP_PART_ASSETS]);
    out->text[RTP_PART_ASSETS] = text;
    return RTP_EXIT_OK;
}

int rtp_part_identify(const char *scene_path, const char *version, const rtp_scene *scene, rtp_part *out, char *err,
                      size_t err_size)
{
    char scene_hex[65], settings[64];
    if (!file_digest(scene_path, scene_hex, err, err_size)) return RTP_EXIT_INPUT;
    const rt_camera *cam = &scene->scene.camera;
    /* Width and height are the frame's; the rest of the camera is in the scene file. */
    snprintf(settings, sizeof settings, "depth=%u aa=%u", cam->trace.max_depth, cam->trace.samples_per_pixel_index);
    out->width = cam->width;
    out->height = cam->height;
    int rc = asset_digests(&scene->loaded, out, err, err_size);
    if (rc == RTP_EXIT_OK &&
        !(rtp_part_set(out, RTP_PART_VERSION, version) && rtp_part_set(out, RTP_PART_BUILD, RTP_BUILD_NAME) &&
          rtp_part_set(out, RTP_PART_SCENE, scene_hex) && rtp_part_set(out, RTP_PART_SETTINGS, settings)))
        rc = RTP_EXIT_MEMORY;
    if (rc == RTP_EXIT_MEMORY) snprintf(err, err_size, "%s: out of memory describing the part", scene_path);
    return rc;
}

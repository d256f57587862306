/* A scene description as one flat little-endian byte string, so a scene loaded on a
 * host can be rendered where there is no file system or YAML parser (a bare-metal
 * board, a cross-compiled test driver). The bytes hold rt_real values as they are in
 * the build that wrote them: a blob made by the fixed build is read by a fixed build. */
#ifndef RT_BLOB_H
#define RT_BLOB_H

#include "scene.h"

/* Bytes rt_blob_write needs for desc. */
size_t rt_blob_size(const rt_scene_desc *desc);
/* Writes desc into out (capacity rt_blob_size(desc)); returns the bytes written, 0 if too small. */
size_t rt_blob_write(const rt_scene_desc *desc, uint8_t *out, size_t capacity);
/* Reads a blob; the description's arrays live in the arena. RT_ERR_INVALID for bytes that
 * are not a blob of this build (wrong magic, scalar type, truncated, counts that lie). */
rt_status rt_blob_read(const uint8_t *bytes, size_t size, rt_arena *arena, rt_scene_desc *out);

#endif

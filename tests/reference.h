/* Shared helpers of the tests that render corpus scenes: where the corpus is, and
 * a one-call render of a scene file to an image. */
#ifndef RT_TEST_REFERENCE_H
#define RT_TEST_REFERENCE_H

#include "image/image.h"
#include <stdbool.h>

/* The shared corpus folder (../shared/cse457/assets/trace unless RTK_SHARED says where shared/ is). */
const char *rt_test_trace_dir(void);

/* Renders a scene at its own settings on `threads` threads; false with err filled on failure. */
bool rt_test_render(const char *scene_path, unsigned threads, bool use_bvh, rtp_image *out, char *err, size_t err_size);

#endif

/* Which BVH kernel rtk runs (rt_kernel, core/scene.h): the best this CPU and build have,
 * or the one --kernel names. Asking the CPU happens here: the core never does. */
#ifndef RTP_KERNEL_H
#define RTP_KERNEL_H

#include "scene.h"
#include <stdbool.h>

/* The kernel's name: "portable", "sse2", "avx2" or "avx512". */
const char *rtp_kernel_name(rt_kernel k);
/* The kernel named s; false for an unknown name. */
bool rtp_kernel_parse(const char *s, rt_kernel *out);
/* Whether the core has kernel k and this CPU has its instructions. */
bool rtp_kernel_runs(rt_kernel k);
/* The fastest kernel that runs here. */
rt_kernel rtp_kernel_best(void);

#endif

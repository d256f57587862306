/* Kernel names and the CPU check; see kernel.h. */
#include "thread/kernel.h"

#include "bvh.h"
#include <string.h>

static const char *const names[] = {"portable", "sse2", "avx2", "avx512"};

const char *rtp_kernel_name(rt_kernel k) { return (unsigned)k < sizeof names / sizeof names[0] ? names[k] : "?"; }

bool rtp_kernel_parse(const char *s, rt_kernel *out)
{
    for (unsigned k = 0; s && k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(s, names[k])) {
            *out = (rt_kernel)k;
            return true;
        }
    return false;
}

/* Whether the CPU executes the instructions kernel k adds to the build's own. */
static bool cpu_has(rt_kernel k)
{
#if defined(__x86_64__) || defined(__i386__)
    if (k == RT_KERNEL_AVX2) return __builtin_cpu_supports("avx2");
    if (k == RT_KERNEL_AVX512)
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512dq");
#endif
    return k != RT_KERNEL_AVX2 && k != RT_KERNEL_AVX512;
}

bool rtp_kernel_runs(rt_kernel k) { return rt_bvh_kernel_compiled(k) && cpu_has(k); }

rt_kernel rtp_kernel_best(void)
{
    static const rt_kernel fastest_first[] = {RT_KERNEL_AVX512, RT_KERNEL_AVX2, RT_KERNEL_SSE2, RT_KERNEL_PORTABLE};
    for (unsigned i = 0; i < sizeof fastest_first / sizeof fastest_first[0]; i++)
        if (rtp_kernel_runs(fastest_first[i])) return fastest_first[i];
    return RT_KERNEL_PORTABLE;
}

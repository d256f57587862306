/* rtp_version_line; see version.h. RTK_COMMIT comes from the Makefile (git describe). */
#include "cli/version.h"

#include "rtk.h"

#ifndef RTK_COMMIT
#define RTK_COMMIT "unknown"
#endif
#define RTP_STR2(x) #x
#define RTP_STR(x) RTP_STR2(x)
#if defined(__clang__)
#define RTP_COMPILER "clang " RTP_STR(__clang_major__) "." RTP_STR(__clang_minor__) "." RTP_STR(__clang_patchlevel__)
#elif defined(__GNUC__)
#define RTP_COMPILER "gcc " RTP_STR(__GNUC__) "." RTP_STR(__GNUC_MINOR__) "." RTP_STR(__GNUC_PATCHLEVEL__)
#else
#define RTP_COMPILER "an unknown compiler"
#endif
#if defined(RT_REAL_FIXED)
#define RTP_BUILD "fixed"
#else
#define RTP_BUILD "double"
#endif

const char *rtp_version_line(void)
{
    return "rtk " RTK_VERSION_STRING " (" RTP_BUILD " build; " RTP_COMPILER "; commit " RTK_COMMIT ")";
}

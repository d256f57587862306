/* rtk.h — the public API of rtk (a first cut: version only; the manual follows). */
#ifndef RTK_H
#define RTK_H

#define RTK_VERSION_MAJOR 0
#define RTK_VERSION_MINOR 5
#define RTK_VERSION_PATCH 0
#define RTK_VERSION_STRING "0.5.0"

#endif

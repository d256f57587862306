/* Names of rt_status values, for messages. */
#include "status.h"

const char *rt_status_name(rt_status s)
{
    switch (s) {
    case RT_OK: return "ok";
    case RT_ERR_NOMEM: return "out of memory";
    case RT_ERR_INVALID: return "invalid input";
    case RT_ERR_RANGE: return "value out of range";
    }
    return "unknown error";
}

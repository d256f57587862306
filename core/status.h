/* Errors are values: every fallible core function returns an rt_status. */
#ifndef RT_STATUS_H
#define RT_STATUS_H

typedef enum {
    RT_OK = 0,
    RT_ERR_NOMEM,   /* the arena is too small; rt_arena.wanted says how much more */
    RT_ERR_INVALID, /* a value outside what the kernel accepts (the detail names it) */
    RT_ERR_RANGE,   /* a value the scalar type cannot represent (fixed build) */
} rt_status;

const char *rt_status_name(rt_status s);

#endif

/* Whether two hit records are the same: t, b1 and b2 bit for bit, and the part. */
#ifndef RT_TEST_SAME_HIT_H
#define RT_TEST_SAME_HIT_H

#include "intersect.h"
#include <stdbool.h>
#include <string.h>

static inline bool same_hit(const rt_prim_hit *a, const rt_prim_hit *b)
{
    return !memcmp(&a->t, &b->t, sizeof a->t) && !memcmp(&a->b1, &b->b1, sizeof a->b1) &&
           !memcmp(&a->b2, &b->b2, sizeof a->b2) && a->part == b->part;
}

#endif

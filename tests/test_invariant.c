/* RT_ASSERT is live in the core the tests link (librtcore-asserts.a): a broken invariant
 * aborts with its place, rather than passing unseen. */
#include "rng.h"
#include <criterion/criterion.h>
#include <signal.h>

Test(invariant, a_broken_invariant_aborts, .signal = SIGABRT)
{
    /* rt_rng_permute is a bijection of at most 30-bit words. */
    rt_rng_permute(0, 31, 0);
}

Test(invariant, a_kept_invariant_passes) { cr_expect_lt(rt_rng_permute(5, 30, 7), 1u << 30); }

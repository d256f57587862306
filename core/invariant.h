/* RT_ASSERT(condition): an invariant of the code (never a check of input, which returns
 * an rt_status). Off by default, so the freestanding core pays nothing and needs nothing;
 * built with -DRT_ASSERTS (the tests, the fuzzers and the ASan build) a broken invariant
 * calls rt_invariant_failed, which the program linking the core supplies and which must
 * not return. Compile-time facts use _Static_assert beside the code they protect. */
#ifndef RT_INVARIANT_H
#define RT_INVARIANT_H

#if defined(RT_ASSERTS)
_Noreturn void rt_invariant_failed(const char *file, int line, const char *condition);
#define RT_ASSERT(condition) ((condition) ? (void)0 : rt_invariant_failed(__FILE__, __LINE__, #condition))
#else
#define RT_ASSERT(condition) ((void)0)
#endif

#endif

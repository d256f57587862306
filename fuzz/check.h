/* Invariant checks in fuzz targets: a broken invariant prints what broke and aborts,
 * which libFuzzer reports as a crash (and saves the input that caused it). */
#ifndef FZ_CHECK_H
#define FZ_CHECK_H

#define FZ_CHECK(cond, ...)                                           \
    do {                                                              \
        if (!(cond)) fz_fail(__FILE__, __LINE__, #cond, __VA_ARGS__); \
    } while (0)

_Noreturn void fz_fail(const char *file, int line, const char *cond, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#endif

/* Declarations wasi-libc's headers lack, for functions web/wasm supplies; force-included
 * (-include) into the platform sources built for wasm32-wasi. */
#ifndef RT_WASI_COMPAT_H
#define RT_WASI_COMPAT_H

char *realpath(const char *restrict path, char *restrict resolved); /* web/wasm/realpath.c */

#endif

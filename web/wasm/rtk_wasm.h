/* Shared between the browser's entry points (rtk_wasm*.c). */
#ifndef RTK_WASM_H
#define RTK_WASM_H

#include "load/scene_open.h"

/* The scene rtk_open built: loader tables and all. */
const rtp_scene *rtk_wasm_scene(void);

#endif

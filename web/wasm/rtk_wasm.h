/* Shared between the browser's entry points (rtk_wasm*.c). */
#ifndef RTK_WASM_H
#define RTK_WASM_H

#include "scene_build.h"

/* The scene rtk_open built: loader tables and all. */
const rt_built_scene *rtk_wasm_scene(void);

#endif

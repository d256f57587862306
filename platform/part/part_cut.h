/* Where `--part I/N` cuts a frame: N bands of whole rows, balanced by a cheap estimate of
 * each row's cost that is a pure function of the scene and its settings, so every
 * machine cuts a frame the same way (docs/distributed.md). */
#ifndef RTP_PART_CUT_H
#define RTP_PART_CUT_H

#include "render.h"
#include <stdbool.h>

/* The estimate samples a grid of at most this many columns and rows of pixels. */
#define RTP_CUT_COLUMNS 32u
#define RTP_CUT_ROWS 128u

/* Sets starts[0..count] (count + 1 rows, starts[0] = 0, starts[count] = the camera's
 * height, strictly increasing) so that band i, rows [starts[i], starts[i + 1]), holds
 * about 1/count of the estimated cost. count must be 1..height. The estimate traces
 * sample 0 of each grid pixel with a ray log; a pixel costs 1 + the rays it traced
 * (capped). `threads` only spreads that work (0: all cores). False when out of memory. */
bool rtp_part_cut(const rt_scene *scene, uint32_t count, uint32_t threads, uint32_t *starts);

/* Band `index` of the cut as a rectangle of the frame. */
rt_rect rtp_part_band(const rt_scene *scene, const uint32_t *starts, uint32_t index);

#endif

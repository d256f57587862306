/* Joining identical vertices of a mesh read from a PLY file. */
#ifndef RTP_PLY_WELD_H
#define RTP_PLY_WELD_H

#include "load/ply.h"

/* Merges vertices whose position, normal and uv are bit-identical, keeping the first of
 * each in file order and renumbering the triangles. False (mesh unchanged) when out of memory. */
bool rtp_ply_weld(rtp_ply_mesh *mesh);

#endif

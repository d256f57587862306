/* Drawing a scene in an SVG panel: a view projects world space onto an axis-aligned
 * plane, and the objects' outlines are drawn through it (for `rtk debug --svg`). */
#ifndef RTP_SVG_VIEW_H
#define RTP_SVG_VIEW_H

#include "scene.h"
#include <stdio.h>

typedef struct {
    int h_axis, v_axis;               /* the world axes along the page's x and y (0 x, 1 y, 2 z) */
    bool v_down;                      /* true: the world v axis points down the page */
    double center_h, center_v, scale; /* world window centre and page units per world unit */
    double left, top, size;           /* the square panel on the page */
} rtp_svg_view;

/* Fits the world box [lo, hi] (its extent on the view's axes) into the panel. */
void rtp_svg_view_fit(rtp_svg_view *v, const double lo[3], const double hi[3]);
/* Page coordinates of a world point. */
void rtp_svg_view_map(const rtp_svg_view *v, const double p[3], double *x, double *y);

/* World bounds of every object (meshes: of their triangles), malloc'd; NULL when out of memory. */
rt_aabb *rtp_svg_object_bounds(const rt_scene *scene);

/* Draws every object's outline in the view: each triangle's edges when the scene has at most
 * max_triangles (else each mesh's bounding box), spheres as ellipses, cylinders as their
 * silhouette and caps. bounds is rtp_svg_object_bounds(scene). */
void rtp_svg_outlines(FILE *out, const rtp_svg_view *v, const rt_scene *scene, const rt_aabb *bounds,
                      uint32_t max_triangles);

#endif

/* One pixel traced with the ray log on, arranged as a tree for `rtk debug`: every ray
 * of its samples, the light terms at each hit, and the names of what the rays hit. */
#ifndef RTP_PIXEL_TRACE_H
#define RTP_PIXEL_TRACE_H

#include "load/scene_open.h"
#include "raylog.h"
#include "render.h"

#define RTP_PIXEL_ALL_SAMPLES UINT32_MAX
/* The rays (and light records) a pixel trace logs by default: more than any corpus pixel needs. */
#define RTP_PIXEL_TRACE_CAPACITY (1u << 16)

typedef struct {
    const rtp_scene *built;
    uint32_t x, y;    /* column and row, (0, 0) at the top left */
    uint32_t samples; /* samples per pixel */
    uint32_t sample;  /* the one sample traced, or RTP_PIXEL_ALL_SAMPLES */
    rt_ray_log log;
    /* The tree, as index lists (RT_NO_PARENT ends a list), children in log order.
     * Shadow rays hang under their light's record rather than the ray they light. */
    uint32_t first_root;    /* the camera rays */
    uint32_t *first_child;  /* per ray: its reflection and refraction rays */
    uint32_t *first_shadow; /* per light record: the shadow rays of that light */
    uint32_t *next_sibling; /* per ray */
    uint32_t *first_light;  /* per ray: its light records */
    uint32_t *next_light;   /* per light record */
    /* The pixel's averaged colour, exactly as rt_render_pixel computes it, and its bytes. */
    rt_vec3 color;
    uint8_t rgb[3];
} rtp_pixel_trace;

/* What a ray hit, in the scene file's words. */
typedef struct {
    const char *node;      /* the node's Name */
    const char *primitive; /* "sphere", "cylinder" or "triangle" */
    const char *part;      /* "body", "bottom cap", "top cap"; NULL for spheres and triangles */
    uint32_t triangle;     /* index within its mesh (after subdivision), or UINT32_MAX */
    const char *material;
} rtp_hit_names;

/* Traces pixel (x, y) of the built scene, every sample or only `sample`, logging at most
 * `capacity` rays and as many light records (log.overflow tells when the tree is cut short;
 * the colour is exact either way). False when out of memory. */
bool rtp_pixel_trace_run(rtp_pixel_trace *pt, const rtp_scene *built, uint32_t x, uint32_t y, uint32_t sample,
                         uint32_t capacity);
void rtp_pixel_trace_free(rtp_pixel_trace *pt);

/* The material terms that weight a hit's light, reflected and refracted colours. */
typedef struct {
    rt_vec3 kd, ks, kt;
    rt_real shininess, index_of_refraction;
} rtp_hit_material;

/* For a ray that hit something. */
rtp_hit_names rtp_pixel_trace_names(const rtp_pixel_trace *pt, const rt_ray_record *r);
rtp_hit_material rtp_pixel_trace_material(const rtp_pixel_trace *pt, const rt_ray_record *r);
const char *rtp_pixel_trace_ray_kind(rt_ray_kind kind);
const char *rtp_pixel_trace_light_kind(rt_light_kind kind);

#endif

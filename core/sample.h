/* Where the random numbers of one camera sample come from, and how they are shaped
 * into pixel positions, lens points, light points and bounce directions (format.md §11). */
#ifndef RT_SAMPLE_H
#define RT_SAMPLE_H

#include "rng.h"
#include "vec.h"

/* What a 2D draw is for; with the path node it keys the draw. Area light i uses
 * RT_PURPOSE_LIGHT + i. */
enum { RT_PURPOSE_PIXEL, RT_PURPOSE_LENS, RT_PURPOSE_BRANCH, RT_PURPOSE_DIFFUSE, RT_PURPOSE_GLOSSY, RT_PURPOSE_LIGHT };

typedef struct {
    uint64_t pixel;      /* rt_rng_pixel_key of the pixel */
    uint32_t sample;     /* this sample's index in the pixel, below 4^strata_log when stratified */
    uint32_t strata_log; /* each 2D draw is jittered in one of 4^strata_log strata; 0: plain uniform */
} rt_sampler;

/* A point of [0,1)^2 for one purpose at one path node. Sample k of a pixel lies in
 * stratum permute(k) of a 2^strata_log-square grid, the permutation keyed by pixel,
 * node and purpose: the pixel's samples cover every stratum once, and different
 * purposes are not correlated with each other. */
rt_vec2 rt_sample_2d(const rt_sampler *s, uint64_t node, uint32_t purpose);

/* A point of the unit disc, uniform in area for uniform u. */
rt_vec2 rt_sample_disc(rt_vec2 u);

/* A unit direction about unit n with density cos(theta)/pi (a disc point lifted to the hemisphere). */
rt_vec3 rt_sample_cosine_hemisphere(rt_vec2 u, rt_vec3 n);

/* A unit half vector about unit n with density proportional to (n.h)^exponent (the
 * Blinn-Phong lobe, format.md §11.6): cos(theta) = u^(1/(exponent+1)), phi = 2 pi v. */
rt_vec3 rt_sample_blinn_half_vector(rt_vec2 u, rt_vec3 n, rt_real exponent);

#endif

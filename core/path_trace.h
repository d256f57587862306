/* Monte Carlo tracing of one camera sample (format.md §11, §11.4): area lights as
 * Lambertian emitters sampled on their square (soft shadows) and seen by camera rays,
 * cosine-weighted diffuse bounces, glossy reflection about a sampled Blinn-Phong half
 * vector, the caustics rule and random single branching. Whitted scenes use rt_trace
 * instead. */
#ifndef RT_PATH_TRACE_H
#define RT_PATH_TRACE_H

#include "sample.h"
#include "trace.h"

/* The colour a camera ray brings back, its random numbers drawn from s. Not clamped. */
rt_vec3 rt_path_trace(const rt_tracer *tr, const rt_sampler *s, rt_ray ray);

#endif

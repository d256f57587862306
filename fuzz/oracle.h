/* Independent geometry in long double for the intersector targets: what the kernel
 * should have found, computed another way and with more precision. */
#ifndef FZ_ORACLE_H
#define FZ_ORACLE_H

#include <stdbool.h>

#include "vec.h"

/* Tolerances per scalar backend, all relative to the scene's scale S:
 * FZ_EPS      the backend's relative rounding unit, FZ_ABS its absolute one (fixed);
 * FZ_SIZE_LOG2_MIN/MAX  the range of object sizes (log2) the targets generate;
 * FZ_TOL      a point the kernel reports lies within FZ_TOL * S of the surface;
 * FZ_MARGIN   the oracle only insists on hit or miss when the ray clears the
 *             surface's boundary by FZ_MARGIN * S (else the case is ambiguous);
 * FZ_TOL_T    a reported t equals the oracle's within FZ_TOL_T * S / |d|. */
#if defined(RT_REAL_FIXED)
#define FZ_EPS 0x1p-32L
#define FZ_ABS 0x1p-32L
#define FZ_TOL 1e-6L
#define FZ_MARGIN 1e-6L
#define FZ_TOL_T 1e-6L
/* Q32.32 has one absolute lsb: geometry below ~1/4 and beyond ~2^10 leaves its
 * comfortable range (docs/fixed-point.md), so the targets stay inside it. */
#define FZ_SIZE_LOG2_MIN -2
#define FZ_SIZE_LOG2_MAX 10
#else
#define FZ_EPS 0x1p-52L
#define FZ_ABS 0.0L
#define FZ_TOL 1e-12L
#define FZ_MARGIN 1e-9L
#define FZ_TOL_T 1e-9L
#define FZ_SIZE_LOG2_MIN -40
#define FZ_SIZE_LOG2_MAX 40
#endif

typedef struct {
    long double x, y, z;
} fz_v3l;

/* A transform as a scene describes it: world point = translation + Rx Ry Rz S object
 * point (rotations in degrees, as rt_affine_trs reads them). */
typedef struct {
    rt_vec3 translation, rotation_degrees, scale;
} fz_trs;
/* World to object space from the description alone, in long double: an oracle that does
 * not share the kernel's inverse (rt_affine_inverse), so a wrong inverse cannot move
 * kernel and oracle together. */
fz_v3l fz_trs_point_to_object(const fz_trs *trs, rt_vec3 p);
fz_v3l fz_trs_vector_to_object(const fz_trs *trs, rt_vec3 v);

fz_v3l fz_l(rt_vec3 v);
fz_v3l fz_l_add(fz_v3l a, fz_v3l b);
fz_v3l fz_l_sub(fz_v3l a, fz_v3l b);
fz_v3l fz_l_scale(fz_v3l a, long double s);
long double fz_l_dot(fz_v3l a, fz_v3l b);
fz_v3l fz_l_cross(fz_v3l a, fz_v3l b);
long double fz_l_len(fz_v3l a);
/* The point o + t d. */
fz_v3l fz_l_along(fz_v3l o, fz_v3l d, long double t);
/* Distance from point c to the line through o along d (d not zero). */
long double fz_line_distance(fz_v3l o, fz_v3l d, fz_v3l c);
/* Real roots t0 <= t1 of a t^2 + b t + c (a > 0); false when there are none. */
bool fz_quadratic(long double a, long double b, long double c, long double *t0, long double *t1);
/* Where the line o + t d is inside the box [-h, h]^3: entry and exit parameters
 * (either may be negative); false when the line misses the box. */
bool fz_slab(fz_v3l o, fz_v3l d, long double h, long double *t_in, long double *t_out);
/* How far beyond radius^2 a line's squared distance from a quadric's centre may be
 * while rounding still lets the kernel see a hit, for an object-space ray with
 * o2 = |o|^2, d2 = |d|^2; negative when the backend makes no promise there (the fixed
 * build saturates far outside its range). */
long double fz_quadric_slack(long double o2, long double d2);
/* True when every component of v is finite. */
bool fz_finite3(rt_vec3 v);

/* A surface crossing the oracle predicts at t (within tol); robust ones are certain,
 * the others (grazing the boundary of the surface) may or may not be reported. */
typedef struct {
    long double t, tol;
    bool robust;
} fz_crossing;

/* The nearest-hit contract against the oracle's crossings of the line: a reported
 * hit is one of them, no robust crossing lies between t_min and it, and a robust
 * crossing inside (t_min, t_max) is always found. */
void fz_check_crossings(const fz_crossing *c, int n, bool found, rt_real t, rt_real t_min, rt_real t_max);
/* A reported hit's t is finite and inside (t_min, t_max). */
void fz_check_t(rt_real t, rt_real t_min, rt_real t_max);
/* n is unit length (within a backend-dependent tolerance). */
void fz_check_unit(rt_vec3 n, const char *what);

/* A line that rt_line_clears_ball clears of the sphere's (or the cylinder's) ball misses
 * that shape as bvh_leaf.h solves it: direction normalised, over any t. */
void fz_check_cleared_line(rt_vec3 o, rt_vec3 d, bool sphere);

/* Where the line o + t d (d unit) crosses the plane of triangle abc, in long double:
 * t, the barycentric weights of b and c, and how uncertain the kernel's own values
 * may be (slack on weights, tol_t on t), which grows as the line grazes the plane. */
typedef struct {
    long double t, b1, b2, slack, tol_t;
} fz_plane_crossing;

/* False when the line is parallel to the plane, or nearly so, or the triangle is
 * degenerate: then the oracle claims nothing. */
bool fz_triangle_crossing(rt_vec3 a, rt_vec3 b, rt_vec3 c, rt_vec3 o, rt_vec3 d, fz_plane_crossing *out);

#endif

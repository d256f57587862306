/* Scenes and rays shared by the intersector targets: bounded transforms, one-object
 * scenes built by rt_scene_build, and rays aimed or free. */
#ifndef FZ_FIXTURE_H
#define FZ_FIXTURE_H

#include "bytes.h"
#include "oracle.h"
#include "ray.h"
#include "scene.h"

/* Builds desc with rt_scene_build into a static arena; the scene is valid until the
 * next call. */
rt_status fz_build(const rt_scene_desc *desc, rt_scene *out, rt_build_error *err);
/* A scene of one object (mesh is used by RT_SHAPE_MESH only); a refusal is a bug. */
void fz_scene_one(rt_scene *out, rt_shape_kind kind, const rt_mesh_desc *mesh, rt_affine world);
/* The object-space ray of object 0 for the oracle, from the scene's description in long
 * double (fz_trs_point_to_object), never from the kernel's inverse alone: the kernel's
 * to_object must map the ray within its rounding of that (checked here, so a wrong
 * inverse fails), and the double build's oracle uses the description's ray. The fixed
 * build's oracle takes the kernel's ray: Q32.32's rounding of a matrix scaled by 1/16
 * moves object space by up to ~1e-6, beyond the intersector margins of oracle.h, so
 * there the transform is held to its own bound and the intersector to its own. */
void fz_object_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray, fz_v3l *o, fz_v3l *d);
/* A camera rt_scene_build accepts, for scenes that are not rendered. */
rt_camera_desc fz_camera(void);
/* Translate-rotate-scale with translations in [-8, 8] and scales in [1/16, 16] per
 * axis; the identity for one input in four, so edges stay exactly representable. */
rt_affine fz_transform(fz_bytes *in);
/* The same, also returning the description it was built from (for the oracles). */
rt_affine fz_transform_trs(fz_bytes *in, fz_trs *described);
/* Mostly the renderer's interval (epsilon, max); sometimes from 0 or to a finite end. */
void fz_ray_interval(fz_bytes *in, rt_ray *ray);
/* A ray through world point target, starting some distance away from it. */
rt_ray fz_ray_through(fz_bytes *in, rt_vec3 target);
/* A ray along a coordinate axis through target, from a power-of-two distance: with
 * exact targets the whole setup is exact, so edge functions come out exactly 0. */
rt_ray fz_ray_axis(fz_bytes *in, rt_vec3 target);
/* True when prim is a triangle the ray runs parallel to (within 1e-9) or a degenerate
 * one: there the watertight test's edge functions are rounding noise and it may report
 * a hit anywhere along the plane, which BVH culling legitimately disagrees with (see
 * docs/robustness.md). */
bool fz_grazing(const rt_scene *scene, uint32_t prim, const rt_ray *ray);
/* A ray from a random origin in [-r, r]^3 along a random direction. */
rt_ray fz_ray_free(fz_bytes *in, double r);

#endif

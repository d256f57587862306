/* Projected views and object outlines for SVG drawings; see svg_view.h. */
#include "debug/svg_view.h"

#include "bvh.h"
#include <math.h>
#include <stdlib.h>

#define CAP_POINTS 32 /* points per cylinder cap circle */

static void to_doubles(rt_vec3 v, double out[3])
{
    out[0] = rt_to_double(v.x);
    out[1] = rt_to_double(v.y);
    out[2] = rt_to_double(v.z);
}

void rtp_svg_view_fit(rtp_svg_view *v, const double lo[3], const double hi[3])
{
    double span_h = hi[v->h_axis] - lo[v->h_axis], span_v = hi[v->v_axis] - lo[v->v_axis];
    double span = span_h > span_v ? span_h : span_v;
    v->center_h = 0.5 * (lo[v->h_axis] + hi[v->h_axis]);
    v->center_v = 0.5 * (lo[v->v_axis] + hi[v->v_axis]);
    v->scale = span > 0 ? v->size / span : 1.0;
}

void rtp_svg_view_map(const rtp_svg_view *v, const double p[3], double *x, double *y)
{
    double dv = (p[v->v_axis] - v->center_v) * v->scale;
    *x = v->left + 0.5 * v->size + (p[v->h_axis] - v->center_h) * v->scale;
    *y = v->top + 0.5 * v->size + (v->v_down ? dv : -dv);
}

rt_aabb *rtp_svg_object_bounds(const rt_scene *scene)
{
    rt_aabb *b = malloc((scene->object_count ? scene->object_count : 1) * sizeof *b);
    if (!b) return NULL;
    rt_aabb empty = {{RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX},
                     {rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX)}};
    for (uint32_t i = 0; i < scene->object_count; i++) b[i] = empty;
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object *obj = &scene->objects[i];
        for (uint32_t t = obj->first_triangle; t < obj->first_triangle + obj->triangle_count; t++)
            for (int k = 0; k < 3; k++) {
                rt_vec3 p = scene->positions[scene->triangles[t].v[k]];
                b[i].lo = rt_v3_min(b[i].lo, p);
                b[i].hi = rt_v3_max(b[i].hi, p);
            }
    }
    for (uint32_t p = scene->triangle_count; p < scene->prim_count; p++)
        b[scene->quadric_objects[p - scene->triangle_count]] = rt_bvh_prim_bounds(scene, p);
    return b;
}

static void move_to(FILE *out, const rtp_svg_view *v, const double p[3], char cmd)
{
    double x, y;
    rtp_svg_view_map(v, p, &x, &y);
    fprintf(out, "%c%.1f %.1f", cmd, x, y);
}

static void triangle_edges(FILE *out, const rtp_svg_view *v, const rt_scene *scene)
{
    fputs("<path class=\"mesh\" d=\"", out);
    for (uint32_t t = 0; t < scene->triangle_count; t++) {
        for (int k = 0; k < 3; k++) {
            double p[3];
            to_doubles(scene->positions[scene->triangles[t].v[k]], p);
            move_to(out, v, p, k ? 'L' : 'M');
        }
        fputc('Z', out);
    }
    fputs("\"/>\n", out);
}

static void mesh_box(FILE *out, const rtp_svg_view *v, const rt_aabb *b)
{
    double lo[3], hi[3], x0, y0, x1, y1;
    to_doubles(b->lo, lo);
    to_doubles(b->hi, hi);
    rtp_svg_view_map(v, lo, &x0, &y0);
    rtp_svg_view_map(v, hi, &x1, &y1);
    fprintf(out, "<rect class=\"mesh\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>\n", fmin(x0, x1),
            fmin(y0, y1), fabs(x1 - x0), fabs(y1 - y0));
}

/* The image of the radius-0.5 ball under the linear map L (rows h and v of the object's
 * transform) is the ellipse with shape matrix L L^T: its eigenvalues give the axes. */
static void sphere_ellipse(FILE *out, const rtp_svg_view *v, const rt_object *obj)
{
    const rt_mat3 *m = &obj->to_world.linear;
    double a = 0, b = 0, c = 0;
    for (int k = 0; k < 3; k++) {
        double lh = rt_to_double(m->m[v->h_axis][k]), lv = rt_to_double(m->m[v->v_axis][k]);
        a += lh * lh;
        b += lh * lv;
        c += lv * lv;
    }
    double mean = 0.5 * (a + c), root = sqrt(0.25 * (a - c) * (a - c) + b * b);
    double major = 0.5 * sqrt(mean + root) * v->scale, minor = 0.5 * sqrt(fmax(mean - root, 0.0)) * v->scale;
    double angle = 0.5 * atan2(2 * b, a - c) * 180.0 / M_PI, centre[3], x, y;
    to_doubles(obj->to_world.translation, centre);
    rtp_svg_view_map(v, centre, &x, &y);
    fprintf(out,
            "<ellipse class=\"quadric\" cx=\"%.1f\" cy=\"%.1f\" rx=\"%.2f\" ry=\"%.2f\" "
            "transform=\"rotate(%.2f %.1f %.1f)\"/>\n",
            x, y, major, minor, v->v_down ? angle : -angle, x, y);
}

static double cross(const double o[2], const double a[2], const double b[2])
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static int by_x_then_y(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return a[1] < b[1] ? -1 : a[1] > b[1];
}

/* Convex hull of n page points (Andrew's monotone chain) into hull; returns its size. */
static int convex_hull(double (*pts)[2], int n, double (*hull)[2])
{
    qsort(pts, (size_t)n, sizeof pts[0], by_x_then_y);
    int k = 0;
    for (int i = 0; i < n; i++) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) k--;
        hull[k][0] = pts[i][0], hull[k][1] = pts[i][1], k++;
    }
    for (int i = n - 2, lower = k + 1; i >= 0; i--) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) k--;
        hull[k][0] = pts[i][0], hull[k][1] = pts[i][1], k++;
    }
    return k - 1; /* the last point repeats the first */
}

static void polygon(FILE *out, const char *cls, double (*pts)[2], int n)
{
    fprintf(out, "<polygon class=\"%s\" points=\"", cls);
    for (int i = 0; i < n; i++) fprintf(out, "%s%.1f,%.1f", i ? " " : "", pts[i][0], pts[i][1]);
    fputs("\"/>\n", out);
}

/* The cylinder's two cap circles, and the convex hull of both: its silhouette. */
static void cylinder_outline(FILE *out, const rtp_svg_view *v, const rt_object *obj)
{
    double pts[2 * CAP_POINTS][2], hull[2 * CAP_POINTS + 1][2];
    for (int cap = 0; cap < 2; cap++) {
        for (int i = 0; i < CAP_POINTS; i++) {
            double phi = 2 * M_PI * i / CAP_POINTS, p[3];
            rt_vec3 local =
                rt_v3(rt_from_double(0.5 * cos(phi)), rt_from_double(cap ? 0.5 : -0.5), rt_from_double(0.5 * sin(phi)));
            to_doubles(rt_affine_point(&obj->to_world, local), p);
            rtp_svg_view_map(v, p, &pts[cap * CAP_POINTS + i][0], &pts[cap * CAP_POINTS + i][1]);
        }
        polygon(out, "cap", pts + cap * CAP_POINTS, CAP_POINTS);
    }
    polygon(out, "quadric", hull, convex_hull(pts, 2 * CAP_POINTS, hull));
}

void rtp_svg_outlines(FILE *out, const rtp_svg_view *v, const rt_scene *scene, const rt_aabb *bounds,
                      uint32_t max_triangles)
{
    if (scene->triangle_count > 0 && scene->triangle_count <= max_triangles) triangle_edges(out, v, scene);
    for (uint32_t i = 0; i < scene->object_count; i++) {
        const rt_object *obj = &scene->objects[i];
        if (obj->kind == RT_SHAPE_SPHERE)
            sphere_ellipse(out, v, obj);
        else if (obj->kind == RT_SHAPE_CYLINDER)
            cylinder_outline(out, v, obj);
        else if (scene->triangle_count > max_triangles && bounds[i].lo.x <= bounds[i].hi.x)
            mesh_box(out, v, &bounds[i]);
    }
}

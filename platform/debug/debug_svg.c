/* `rtk debug --svg`: the rendered image with the pixel marked, beside the pixel's ray
 * tree projected on the Z-Y (side) and X-Z (top) planes over the objects' outlines. */
#include "debug/debug_output.h"

#include "debug/svg_view.h"
#include "image/file_write.h"
#include "mem/mem.h"
#include "mem/mem_stream.h"
#include <math.h>
#include <stdlib.h>

#define PANEL 400.0 /* side of each panel, in page units */
#define GAP 24.0
#define TOP 56.0                  /* the panels' top edge, below the title */
#define MAX_EDGES_TRIANGLES 20000 /* above this, meshes are drawn as boxes */

static const char style[] = "<style>\n"
                            "text{font:13px sans-serif;fill:#222}\n"
                            ".frame{fill:#fafafa;stroke:#999}\n"
                            ".mesh,.quadric,.cap{fill:none;stroke:#9a9a9a;stroke-width:0.6}\n"
                            ".cap{stroke-dasharray:2 2}\n"
                            ".ray{stroke-width:1.4;fill:none}\n"
                            ".camera{stroke:#1f5fbf;fill:#1f5fbf}\n"
                            ".reflection{stroke:#1a9850;fill:#1a9850}\n"
                            ".refraction{stroke:#d7301f;fill:#d7301f}\n"
                            ".shadow{stroke:#e69500;fill:#e69500;stroke-dasharray:5 3}\n"
                            ".diffuse{stroke:#7b3fa0;fill:#7b3fa0}\n"
                            ".glossy{stroke:#0f9d9a;fill:#0f9d9a}\n"
                            ".light{fill:#ffd700;stroke:#8a6d00}\n"
                            ".mark{fill:none;stroke-width:2}\n"
                            "</style>\n";

static void base64(FILE *out, const uint8_t *data, size_t size)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < size; i += 3) {
        uint32_t n = (uint32_t)data[i] << 16;
        if (i + 1 < size) n |= (uint32_t)data[i + 1] << 8;
        if (i + 2 < size) n |= data[i + 2];
        fputc(digits[n >> 18], out);
        fputc(digits[(n >> 12) & 63], out);
        fputc(i + 1 < size ? digits[(n >> 6) & 63] : '=', out);
        fputc(i + 2 < size ? digits[n & 63] : '=', out);
    }
}

static void to_doubles(rt_vec3 v, double out[3])
{
    out[0] = rt_to_double(v.x);
    out[1] = rt_to_double(v.y);
    out[2] = rt_to_double(v.z);
}

static void grow(double lo[3], double hi[3], const double p[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(lo[k], p[k]);
        hi[k] = fmax(hi[k], p[k]);
    }
}

/* The world box the views show: every ray's origin and hit point, the objects hit, and the
 * point lights tested; the whole scene when that is a single point (a lone miss). */
static void world_window(const rtp_pixel_trace *pt, const rt_aabb *bounds, double lo[3], double hi[3])
{
    const rt_scene *scene = &pt->built->scene;
    double p[3];
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (uint32_t i = 0; i < pt->log.ray_count; i++) {
        const rt_ray_record *r = &pt->log.rays[i];
        to_doubles(r->ray.origin, p);
        grow(lo, hi, p);
        if (r->hit) {
            to_doubles(bounds[r->surface.object].lo, p);
            grow(lo, hi, p);
            to_doubles(bounds[r->surface.object].hi, p);
            grow(lo, hi, p);
        }
        if (r->on_light) {
            to_doubles(rt_v3_madd(r->ray.origin, r->ray.direction, r->ray.t_max), p);
            grow(lo, hi, p);
        }
        if (r->kind == RT_RAY_SHADOW && scene->lights[r->light].kind != RT_LIGHT_DIRECTIONAL) {
            to_doubles(scene->lights[r->light].position, p);
            grow(lo, hi, p);
        }
    }
    if (lo[0] == hi[0] && lo[1] == hi[1] && lo[2] == hi[2]) {
        for (uint32_t i = 0; i < scene->object_count; i++) {
            if (!(bounds[i].lo.x <= bounds[i].hi.x)) continue;
            to_doubles(bounds[i].lo, p);
            grow(lo, hi, p);
            to_doubles(bounds[i].hi, p);
            grow(lo, hi, p);
        }
    }
    double span = 0;
    for (int k = 0; k < 3; k++) span = fmax(span, hi[k] - lo[k]);
    double margin = span > 0 ? 0.08 * span : 1.0;
    for (int k = 0; k < 3; k++) lo[k] -= margin, hi[k] += margin;
}

/* A ray from its origin to its hit (or the light's square it ends on), or (a miss) on
 * past the panel's edge. */
static void draw_ray(FILE *out, const rtp_svg_view *v, const rt_ray_record *r)
{
    const char *cls = rtp_pixel_trace_ray_kind(r->kind);
    double o[3], d[3], e[3], x0, y0, x1, y1;
    to_doubles(r->ray.origin, o);
    to_doubles(r->ray.direction, d);
    if (r->hit) {
        to_doubles(r->surface.point, e);
    } else {
        double reach = fmin(rt_to_double(r->ray.t_max), 2.0 * v->size / v->scale);
        for (int k = 0; k < 3; k++) e[k] = o[k] + reach * d[k];
    }
    rtp_svg_view_map(v, o, &x0, &y0);
    rtp_svg_view_map(v, e, &x1, &y1);
    fprintf(out,
            "<line class=\"ray %s\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\">"
            "<title>%s ray, depth %u</title></line>\n",
            cls, x0, y0, x1, y1, cls, r->depth);
    if (r->hit || r->on_light) fprintf(out, "<circle class=\"%s\" cx=\"%.2f\" cy=\"%.2f\" r=\"2.5\"/>\n", cls, x1, y1);
}

/* An area light's square (what Monte Carlo mode samples and camera rays see). */
static void area_light(FILE *out, const rtp_svg_view *v, const rt_light *l)
{
    rt_vec3 corners[4] = {l->corner, rt_v3_add(l->corner, l->edge_u),
                          rt_v3_add(rt_v3_add(l->corner, l->edge_u), l->edge_v), rt_v3_add(l->corner, l->edge_v)};
    fputs("<path class=\"light\" fill-opacity=\"0.5\" d=\"", out);
    for (int k = 0; k < 4; k++) {
        double p[3], x, y;
        to_doubles(corners[k], p);
        rtp_svg_view_map(v, p, &x, &y);
        fprintf(out, "%c%.2f %.2f", k ? 'L' : 'M', x, y);
    }
    fputs("Z\"/>\n", out);
}

static void projection(FILE *out, const rtp_pixel_trace *pt, const rt_aabb *bounds, rtp_svg_view *v, const double lo[3],
                       const double hi[3], const char *title, int id)
{
    const rt_scene *scene = &pt->built->scene;
    rtp_svg_view_fit(v, lo, hi);
    fprintf(out, "<text x=\"%.0f\" y=\"%.0f\">%s</text>\n", v->left, v->top - 8, title);
    fprintf(out, "<clipPath id=\"clip%d\"><rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\"/></clipPath>\n",
            id, v->left, v->top, v->size, v->size);
    fprintf(out, "<rect class=\"frame\" x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\"/>\n", v->left, v->top,
            v->size, v->size);
    fprintf(out, "<g clip-path=\"url(#clip%d)\">\n", id);
    rtp_svg_outlines(out, v, scene, bounds, MAX_EDGES_TRIANGLES);
    for (uint32_t i = 0; i < scene->light_count; i++) {
        if (scene->lights[i].kind == RT_LIGHT_DIRECTIONAL) continue;
        double p[3], x, y;
        to_doubles(scene->lights[i].position, p);
        rtp_svg_view_map(v, p, &x, &y);
        fprintf(out, "<circle class=\"light\" cx=\"%.1f\" cy=\"%.1f\" r=\"5\"><title>light %u</title></circle>\n", x, y,
                i);
        if (scene->lights[i].kind == RT_LIGHT_AREA) area_light(out, v, &scene->lights[i]);
    }
    for (uint32_t i = 0; i < pt->log.ray_count; i++) draw_ray(out, v, &pt->log.rays[i]);
    fputs("</g>\n", out);
}

static bool image_panel(FILE *out, const rtp_pixel_trace *pt, const rtp_image *img, char *err, size_t err_size)
{
    size_t size;
    uint8_t *png = rtp_image_encode_png(img, &size, err, err_size);
    if (!png) return false;
    double s = PANEL / (img->width > img->height ? img->width : img->height);
    double w = s * img->width, h = s * img->height, left = GAP;
    fprintf(out, "<text x=\"%.0f\" y=\"%.0f\">image %ux%u, pixel (%u, %u)</text>\n", left, TOP - 8, img->width,
            img->height, pt->x, pt->y);
    fprintf(out,
            "<image x=\"%.0f\" y=\"%.0f\" width=\"%.1f\" height=\"%.1f\" preserveAspectRatio=\"none\" "
            "style=\"image-rendering:pixelated\" xlink:href=\"data:image/png;base64,",
            left, TOP, w, h);
    base64(out, png, size);
    rtp_mem_free(png);
    fputs("\"/>\n", out);
    /* The pixel itself, and two rings (dark and light) that show on any background. */
    double x = left + s * pt->x, y = TOP + s * pt->y, cell = s > 1 ? s : 1;
    fprintf(out, "<rect class=\"mark\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" stroke=\"#00e5ff\"/>\n", x,
            y, cell, cell);
    x += cell / 2, y += cell / 2;
    fprintf(out, "<circle class=\"mark\" cx=\"%.2f\" cy=\"%.2f\" r=\"9\" stroke=\"#000\"/>\n", x, y);
    fprintf(out, "<circle class=\"mark\" cx=\"%.2f\" cy=\"%.2f\" r=\"11\" stroke=\"#fff\"/>\n", x, y);
    return true;
}

static void legend(FILE *out, double y)
{
    double x = GAP;
    for (rt_ray_kind k = RT_RAY_CAMERA; k <= RT_RAY_GLOSSY; k++, x += 130) {
        const char *kind = rtp_pixel_trace_ray_kind(k);
        fprintf(out, "<line class=\"ray %s\" x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\"/>", kind, x, y - 4, x + 28,
                y - 4);
        fprintf(out, "<text x=\"%.0f\" y=\"%.0f\">%s ray</text>\n", x + 34, y, kind);
    }
    fprintf(out, "<circle class=\"light\" cx=\"%.0f\" cy=\"%.0f\" r=\"5\"/>", x + 8, y - 4);
    fprintf(out, "<text x=\"%.0f\" y=\"%.0f\">light (and area square)</text>\n", x + 18, y);
    fprintf(out,
            "<line class=\"mesh\" x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\"/><text x=\"%.0f\" y=\"%.0f\">"
            "object outline (dots: hits)</text>\n",
            x + 180, y - 4, x + 208, y - 4, x + 214, y);
}

static bool draw(FILE *out, const rtp_pixel_trace *pt, const rtp_image *img, const rt_aabb *bounds, char *err,
                 size_t err_size)
{
    double width = 4 * GAP + 3 * PANEL, height = TOP + PANEL + 2 * GAP + 8, lo[3], hi[3];
    fprintf(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
            "width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\">\n%s"
            "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
            width, height, width, height, style);
    fprintf(out, "<text x=\"%.0f\" y=\"22\" style=\"font-weight:bold\">rtk debug: pixel (%u, %u), %u ray%s%s</text>\n",
            GAP, pt->x, pt->y, pt->log.ray_count, pt->log.ray_count == 1 ? "" : "s",
            pt->log.overflow ? " (log full: the tree is cut short)" : "");
    if (!image_panel(out, pt, img, err, err_size)) return false;
    world_window(pt, bounds, lo, hi);
    rtp_svg_view side = {2, 1, false, 0, 0, 0, 2 * GAP + PANEL, TOP, PANEL};
    rtp_svg_view top = {0, 2, true, 0, 0, 0, 3 * GAP + 2 * PANEL, TOP, PANEL};
    projection(out, pt, bounds, &side, lo, hi, "side: Z to the right, Y up", 0);
    projection(out, pt, bounds, &top, lo, hi, "top: X to the right, Z down", 1);
    legend(out, TOP + PANEL + GAP + 6);
    fputs("</svg>\n", out);
    return true;
}

bool rtp_debug_write_svg(const char *path, const rtp_pixel_trace *pt, const rtp_image *render, char *err,
                         size_t err_size)
{
    rtp_mem_buffer text = {.what = "the SVG"};
    rt_aabb *bounds = rtp_svg_object_bounds(&pt->built->scene);
    FILE *out = bounds ? rtp_mem_stream_open(&text) : NULL;
    if (!out) {
        rtp_mem_free(bounds);
        snprintf(err, err_size, "%s: %s", path, rtp_mem_refusal());
        return false;
    }
    bool drawn = draw(out, pt, render, bounds, err, err_size), closed = fclose(out) == 0;
    if (drawn && !closed) snprintf(err, err_size, "%s: %s", path, rtp_mem_refusal());
    bool ok = drawn && closed && rtp_file_write(path, text.data, text.size, err, err_size);
    rtp_mem_buffer_free(&text);
    rtp_mem_free(bounds);
    return ok;
}

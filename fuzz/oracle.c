/* Long double geometry for the oracles; see oracle.h. */
#include "oracle.h"

#include <math.h>

#include "check.h"
#include "intersect.h"

fz_v3l fz_l(rt_vec3 v)
{
    fz_v3l r = {rt_to_double(v.x), rt_to_double(v.y), rt_to_double(v.z)};
    return r;
}

fz_v3l fz_l_add(fz_v3l a, fz_v3l b)
{
    fz_v3l r = {a.x + b.x, a.y + b.y, a.z + b.z};
    return r;
}

fz_v3l fz_l_sub(fz_v3l a, fz_v3l b)
{
    fz_v3l r = {a.x - b.x, a.y - b.y, a.z - b.z};
    return r;
}

fz_v3l fz_l_scale(fz_v3l a, long double s)
{
    fz_v3l r = {a.x * s, a.y * s, a.z * s};
    return r;
}

long double fz_l_dot(fz_v3l a, fz_v3l b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

fz_v3l fz_l_cross(fz_v3l a, fz_v3l b)
{
    fz_v3l r = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return r;
}

long double fz_l_len(fz_v3l a) { return sqrtl(fz_l_dot(a, a)); }

fz_v3l fz_l_along(fz_v3l o, fz_v3l d, long double t) { return fz_l_add(o, fz_l_scale(d, t)); }

long double fz_line_distance(fz_v3l o, fz_v3l d, fz_v3l c)
{
    return fz_l_len(fz_l_cross(fz_l_sub(c, o), d)) / fz_l_len(d);
}

bool fz_quadratic(long double a, long double b, long double c, long double *t0, long double *t1)
{
    long double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    long double q = -0.5L * (b < 0 ? b - sqrtl(disc) : b + sqrtl(disc));
    if (q == 0) {
        *t0 = *t1 = 0;
        return true;
    }
    long double r0 = q / a, r1 = c / q;
    *t0 = fminl(r0, r1);
    *t1 = fmaxl(r0, r1);
    return true;
}

bool fz_slab(fz_v3l o, fz_v3l d, long double h, long double *t_in, long double *t_out)
{
    long double lo = -INFINITY, hi = INFINITY;
    long double oc[3] = {o.x, o.y, o.z}, dc[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; k++) {
        if (dc[k] == 0) {
            if (oc[k] < -h || oc[k] > h) return false;
            continue;
        }
        long double ta = (-h - oc[k]) / dc[k], tb = (h - oc[k]) / dc[k];
        lo = fmaxl(lo, fminl(ta, tb));
        hi = fminl(hi, fmaxl(ta, tb));
    }
    *t_in = lo;
    *t_out = hi;
    return lo <= hi;
}

long double fz_quadric_slack(long double o2, long double d2)
{
    /* c = |o|^2 - r^2 cancels: distances blur by about eps |o|^2 (docs/robustness.md). */
    if (FZ_ABS > 0 && !(o2 <= 1e6L && d2 >= 1e-2L && d2 <= 1e2L)) return -1;
    return 64 * FZ_EPS * (o2 + 1) + 1e4L * FZ_ABS * (o2 + 1) / d2;
}

/* v rotated by -degrees about axis (the transpose of rt_affine_trs's rotation). */
static fz_v3l unrotate(fz_v3l v, int axis, rt_real degrees)
{
    const long double pi = 3.141592653589793238462643383279502884L;
    long double rad = rt_to_double(degrees) * (pi / 180), c = cosl(rad), s = sinl(rad);
    long double *k[3] = {&v.x, &v.y, &v.z};
    long double a = *k[(axis + 1) % 3], b = *k[(axis + 2) % 3];
    *k[(axis + 1) % 3] = c * a + s * b;
    *k[(axis + 2) % 3] = -s * a + c * b;
    return v;
}

fz_v3l fz_trs_vector_to_object(const fz_trs *trs, rt_vec3 v)
{
    fz_v3l r = unrotate(unrotate(unrotate(fz_l(v), 0, trs->rotation_degrees.x), 1, trs->rotation_degrees.y), 2,
                        trs->rotation_degrees.z);
    fz_v3l s = fz_l(trs->scale);
    return (fz_v3l){r.x / s.x, r.y / s.y, r.z / s.z};
}

fz_v3l fz_trs_point_to_object(const fz_trs *trs, rt_vec3 p)
{
    fz_v3l q = fz_l_sub(fz_l(p), fz_l(trs->translation));
    fz_v3l r = unrotate(unrotate(unrotate(q, 0, trs->rotation_degrees.x), 1, trs->rotation_degrees.y), 2,
                        trs->rotation_degrees.z);
    fz_v3l s = fz_l(trs->scale);
    return (fz_v3l){r.x / s.x, r.y / s.y, r.z / s.z};
}

bool fz_finite3(rt_vec3 v) { return rt_is_finite(v.x) && rt_is_finite(v.y) && rt_is_finite(v.z); }

void fz_check_crossings(const fz_crossing *c, int n, bool found, rt_real t, rt_real t_min, rt_real t_max)
{
    long double lo = rt_to_double(t_min), hi = rt_to_double(t_max), th = rt_to_double(t);
    bool matched = false;
    for (int i = 0; i < n; i++) {
        bool inside = c[i].t > lo + c[i].tol && c[i].t < hi - c[i].tol;
        if (c[i].robust && inside)
            FZ_CHECK(found, "missed a crossing at t = %.17Lg (interval %.17Lg .. %.17Lg)", c[i].t, lo, hi);
        if (!found) continue;
        if (fabsl(th - c[i].t) <= c[i].tol) matched = true;
        if (c[i].robust && inside)
            FZ_CHECK(c[i].t >= th - c[i].tol, "reported t = %.17Lg but a crossing at t = %.17Lg is nearer", th, c[i].t);
    }
    if (found) FZ_CHECK(matched, "reported t = %.17Lg matches no crossing of the surface", th);
}

void fz_check_t(rt_real t, rt_real t_min, rt_real t_max)
{
    FZ_CHECK(rt_is_finite(t) && t > t_min && t < t_max, "hit t = %.17g outside (%.17g, %.17g)", rt_to_double(t),
             rt_to_double(t_min), rt_to_double(t_max));
}

void fz_check_unit(rt_vec3 n, const char *what)
{
    long double len = fz_l_len(fz_l(n));
    FZ_CHECK(fabsl(len - 1) <= FZ_TOL * 16, "%s has length %.17Lg", what, len);
}

bool fz_triangle_crossing(rt_vec3 a, rt_vec3 b, rt_vec3 c, rt_vec3 o, rt_vec3 d, fz_plane_crossing *out)
{
    fz_v3l A = fz_l(a), B = fz_l(b), C = fz_l(c), O = fz_l(o), D = fz_l(d);
    fz_v3l ab = fz_l_sub(B, A), ac = fz_l_sub(C, A);
    fz_v3l n = fz_l_cross(ab, ac);
    long double nn = fz_l_dot(n, n), nd = fz_l_dot(n, D);
    long double l2 = fmaxl(fz_l_dot(ab, ab), fz_l_dot(ac, ac));
    /* Rounding tilts a plane by about FZ_ABS / edge in the fixed build. */
    long double l_min =
        sqrtl(fminl(fminl(fz_l_dot(ab, ab), fz_l_dot(ac, ac)), fz_l_dot(fz_l_sub(C, B), fz_l_sub(C, B))));
    if (!(nn > 1e-12L * l2 * l2) || !(fabsl(nd) >= (1e-9L + 1e3L * FZ_ABS / l_min) * sqrtl(nn))) return false;
    long double t = fz_l_dot(n, fz_l_sub(A, O)) / nd;
    fz_v3l ap = fz_l_sub(fz_l_along(O, D, t), A);
    out->t = t;
    out->b1 = fz_l_dot(fz_l_cross(ap, ac), n) / nn;
    out->b2 = fz_l_dot(fz_l_cross(ab, ap), n) / nn;
    /* The kernel works relative to the ray origin: its edge functions carry errors
     * of about eps * S^2 against a determinant of about |n . d|. */
    long double far = fmaxl(fmaxl(fz_l_len(fz_l_sub(A, O)), fz_l_len(fz_l_sub(B, O))), fz_l_len(fz_l_sub(C, O)));
    long double big = fmaxl(fmaxl(fz_l_len(A), fz_l_len(B)), fmaxl(fz_l_len(C), fz_l_len(O)));
    long double s = far + big;
    out->slack = (1e4L * FZ_EPS * s * s + 1e4L * FZ_ABS * s) / fabsl(nd);
    out->tol_t = out->slack * s + 1e4L * FZ_EPS * fabsl(t);
    return true;
}

void fz_check_cleared_line(rt_vec3 o, rt_vec3 d, bool sphere)
{
    if (!rt_line_clears_ball(o, d, sphere ? RT_C(0.25) : RT_C(0.5))) return;
    rt_real len = rt_v3_length(d);
    FZ_CHECK(len > RT_ZERO, "a cleared line has no direction");
    rt_vec3 unit = rt_v3_scale(d, rt_div(RT_ONE, len));
    const rt_real far = RT_C(1e9);
    rt_prim_hit h;
    bool hit = sphere ? rt_intersect_sphere(o, unit, rt_neg(far), far, &h)
                      : rt_intersect_cylinder(o, unit, rt_neg(far), far, &h);
    FZ_CHECK(!hit, "a line cleared of the %s's ball hits it at t = %.17g", sphere ? "sphere" : "cylinder",
             rt_to_double(h.t));
}

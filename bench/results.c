/* Result files and their comparison; see results.h. */
#include "results.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char magic[8] = {'R', 'T', 'K', 'R', 'E', 'S', 'U', '1'};

/* How many differing rays `agree` lists per set. */
#define LISTED 20

bool bench_results_alloc(const bench_workload *w, bench_results *r)
{
    r->primary_count = w->primary_count;
    r->shadow_count = w->shadow_count;
    r->primary_hit = calloc((size_t)w->primary_count + 1, 1);
    r->primary_prim = calloc((size_t)w->primary_count + 1, sizeof *r->primary_prim);
    r->shadow_blocked = calloc((size_t)w->shadow_count + 1, 1);
    if (r->primary_hit && r->primary_prim && r->shadow_blocked) return true;
    fprintf(stderr, "bench: out of memory for the results\n");
    bench_results_free(r);
    return false;
}

void bench_results_free(bench_results *r)
{
    free(r->primary_hit);
    free(r->primary_prim);
    free(r->shadow_blocked);
    memset(r, 0, sizeof *r);
}

bool bench_results_write(const char *path, const bench_results *r)
{
    FILE *f = fopen(path, "wb");
    uint32_t counts[2] = {r->primary_count, r->shadow_count};
    bool ok = f && fwrite(magic, 1, sizeof magic, f) == sizeof magic && fwrite(counts, sizeof counts[0], 2, f) == 2 &&
              fwrite(r->primary_prim, sizeof *r->primary_prim, r->primary_count, f) == r->primary_count &&
              fwrite(r->shadow_blocked, 1, r->shadow_count, f) == r->shadow_count;
    if (f && fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "%s: cannot write the results\n", path);
    return ok;
}

static bool read_results(const char *path, const bench_workload *w, bench_results *r)
{
    if (!bench_results_alloc(w, r)) return false;
    FILE *f = fopen(path, "rb");
    char m[sizeof magic];
    uint32_t counts[2];
    bool ok = f && fread(m, 1, sizeof m, f) == sizeof m && !memcmp(m, magic, sizeof m) &&
              fread(counts, sizeof counts[0], 2, f) == 2 && counts[0] == w->primary_count &&
              counts[1] == w->shadow_count &&
              fread(r->primary_prim, sizeof *r->primary_prim, counts[0], f) == counts[0] &&
              fread(r->shadow_blocked, 1, counts[1], f) == counts[1];
    if (f) fclose(f);
    if (!ok) fprintf(stderr, "%s: not the results of this workload\n", path);
    return ok;
}

static void describe(char *out, size_t size, uint32_t prim)
{
    if (prim == BENCH_MISS)
        snprintf(out, size, "miss");
    else
        snprintf(out, size, "triangle %u", prim);
}

/* Whether triangles a and b share a vertex: a ray through their common edge or corner,
 * which float and double arithmetic may round to either side. */
static bool share_a_vertex(const bench_workload *w, uint32_t a, uint32_t b)
{
    if (a == BENCH_MISS || b == BENCH_MISS || a >= w->triangle_count || b >= w->triangle_count) return false;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (w->indices[3 * a + i] == w->indices[3 * b + j]) return true;
    return false;
}

int bench_agree(const char *workload, const char *path_a, const char *path_b, double min_percent, bool neighbours)
{
    bench_workload w;
    bench_results a = {0}, b = {0};
    if (!bench_workload_read(workload, &w)) return 2;
    if (!read_results(path_a, &w, &a) || !read_results(path_b, &w, &b)) {
        bench_results_free(&a);
        bench_results_free(&b);
        bench_workload_free(&w);
        return 2;
    }
    uint32_t primary_differ = 0, primary_neighbours = 0, shadow_differ = 0;
    for (uint32_t i = 0; i < w.primary_count; i++) {
        if (a.primary_prim[i] == b.primary_prim[i]) continue;
        primary_neighbours += share_a_vertex(&w, a.primary_prim[i], b.primary_prim[i]);
        if (primary_differ++ < LISTED) {
            char sa[32], sb[32];
            describe(sa, sizeof sa, a.primary_prim[i]);
            describe(sb, sizeof sb, b.primary_prim[i]);
            fprintf(stderr, "  camera ray %u (pixel %u, %u): %s / %s\n", i, i % w.width, i / w.width, sa, sb);
        }
    }
    for (uint32_t i = 0; i < w.shadow_count; i++) {
        if (a.shadow_blocked[i] == b.shadow_blocked[i]) continue;
        uint32_t source = w.shadow_source[i];
        if (shadow_differ++ < LISTED)
            fprintf(stderr, "  shadow ray %u (from pixel %u, %u): %s / %s\n", i, source % w.width, source / w.width,
                    a.shadow_blocked[i] ? "blocked" : "clear", b.shadow_blocked[i] ? "blocked" : "clear");
    }
    if (primary_differ > LISTED || shadow_differ > LISTED) fprintf(stderr, "  (the first %d of each listed)\n", LISTED);
    double primary = w.primary_count ? 100.0 * (w.primary_count - primary_differ) / w.primary_count : 100.0;
    double shadow = w.shadow_count ? 100.0 * (w.shadow_count - shadow_differ) / w.shadow_count : 100.0;
    /* Camera rays that hit neighbouring triangles are counted apart from the others. */
    double elsewhere =
        w.primary_count ? 100.0 * (w.primary_count - (primary_differ - primary_neighbours)) / w.primary_count : 100.0;
    printf("primary_agree %.4f\nprimary_differ %u\nprimary_differ_neighbours %u\nprimary_agree_but_neighbours %.4f\n"
           "shadow_agree %.4f\nshadow_differ %u\n",
           primary, primary_differ, primary_neighbours, elsewhere, shadow, shadow_differ);
    bench_results_free(&a);
    bench_results_free(&b);
    bench_workload_free(&w);
    return (neighbours ? elsewhere : primary) >= min_percent && shadow >= min_percent ? 0 : 1;
}

/* Reading and writing the benchmark workload file; see workload.h. */
#include "workload.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char magic[8] = {'R', 'T', 'K', 'B', 'E', 'N', 'C', '1'};

static bool put(FILE *f, const void *p, size_t size, size_t count)
{
    return count == 0 || fwrite(p, size, count, f) == count;
}

static bool get(FILE *f, void *p, size_t size, size_t count) { return count == 0 || fread(p, size, count, f) == count; }

bool bench_workload_write(const char *path, const bench_workload *w)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    uint32_t counts[6] = {w->vertex_count, w->triangle_count, w->width, w->height, w->primary_count, w->shadow_count};
    bool ok = put(f, magic, 1, sizeof magic) && put(f, counts, sizeof counts[0], 6) &&
              put(f, w->positions, sizeof(double), 3 * (size_t)w->vertex_count) &&
              put(f, w->indices, sizeof(uint32_t), 3 * (size_t)w->triangle_count) &&
              put(f, w->primary, sizeof(bench_ray), w->primary_count) &&
              put(f, w->shadow, sizeof(bench_ray), w->shadow_count);
    if (fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "%s: write failed\n", path);
    return ok;
}

bool bench_workload_read(const char *path, bench_workload *w)
{
    memset(w, 0, sizeof *w);
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return false;
    }
    char m[sizeof magic];
    uint32_t counts[6];
    bool ok = get(f, m, 1, sizeof m) && !memcmp(m, magic, sizeof magic) && get(f, counts, sizeof counts[0], 6);
    if (ok) {
        w->vertex_count = counts[0];
        w->triangle_count = counts[1];
        w->width = counts[2];
        w->height = counts[3];
        w->primary_count = counts[4];
        w->shadow_count = counts[5];
        w->positions = malloc(3 * (size_t)w->vertex_count * sizeof(double) + 1);
        w->indices = malloc(3 * (size_t)w->triangle_count * sizeof(uint32_t) + 1);
        w->primary = malloc((size_t)w->primary_count * sizeof(bench_ray) + 1);
        w->shadow = malloc((size_t)w->shadow_count * sizeof(bench_ray) + 1);
        ok = w->positions && w->indices && w->primary && w->shadow &&
             get(f, w->positions, sizeof(double), 3 * (size_t)w->vertex_count) &&
             get(f, w->indices, sizeof(uint32_t), 3 * (size_t)w->triangle_count) &&
             get(f, w->primary, sizeof(bench_ray), w->primary_count) &&
             get(f, w->shadow, sizeof(bench_ray), w->shadow_count);
    }
    fclose(f);
    for (size_t i = 0; ok && i < 3 * (size_t)w->triangle_count; i++) ok = w->indices[i] < w->vertex_count;
    if (!ok) {
        fprintf(stderr, "%s: not a complete benchmark workload file\n", path);
        bench_workload_free(w);
    }
    return ok;
}

void bench_workload_free(bench_workload *w)
{
    free(w->positions);
    free(w->indices);
    free(w->primary);
    free(w->shadow);
    memset(w, 0, sizeof *w);
}

/* Reading and writing the benchmark workload file; see workload.h. */
#include "workload.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char magic[8] = {'R', 'T', 'K', 'B', 'E', 'N', 'C', '2'};

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
              put(f, w->shadow, sizeof(bench_ray), w->shadow_count) &&
              put(f, w->shadow_source, sizeof(uint32_t), w->shadow_count);
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
        w->shadow_source = malloc((size_t)w->shadow_count * sizeof(uint32_t) + 1);
        ok = w->positions && w->indices && w->primary && w->shadow && w->shadow_source &&
             get(f, w->positions, sizeof(double), 3 * (size_t)w->vertex_count) &&
             get(f, w->indices, sizeof(uint32_t), 3 * (size_t)w->triangle_count) &&
             get(f, w->primary, sizeof(bench_ray), w->primary_count) &&
             get(f, w->shadow, sizeof(bench_ray), w->shadow_count) &&
             get(f, w->shadow_source, sizeof(uint32_t), w->shadow_count);
    }
    fclose(f);
    for (size_t i = 0; ok && i < 3 * (size_t)w->triangle_count; i++) ok = w->indices[i] < w->vertex_count;
    ok = ok && (uint64_t)w->width * w->height == w->primary_count;
    for (uint32_t i = 0; ok && i < w->shadow_count; i++)
        ok = w->shadow_source[i] < w->primary_count && (i == 0 || w->shadow_source[i] > w->shadow_source[i - 1]);
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
    free(w->shadow_source);
    memset(w, 0, sizeof *w);
}

/* The 4 x 2 block of pixel (x, y), numbered row by row over the image. */
static uint32_t block_of(const bench_workload *w, uint32_t ray)
{
    uint32_t x = ray % w->width, y = ray / w->width;
    return y / 2 * ((w->width + 3) / 4) + x / 4;
}

bool bench_make_packets(const bench_workload *w, bool shadow, bench_packets *out)
{
    uint32_t n = shadow ? w->shadow_count : w->primary_count;
    uint32_t blocks = (w->height + 1) / 2 * ((w->width + 3) / 4);
    uint32_t *fill = calloc((size_t)blocks + 1, sizeof *fill);
    out->start = malloc(((size_t)blocks + 1) * sizeof *out->start);
    out->ray = malloc((size_t)n * sizeof *out->ray + 1);
    if (!fill || !out->start || !out->ray) {
        free(fill);
        bench_packets_free(out);
        fprintf(stderr, "bench: out of memory for the packets\n");
        return false;
    }
    /* Count each block's rays, then place them in block order (empty blocks dropped). */
    for (uint32_t i = 0; i < n; i++) fill[block_of(w, shadow ? w->shadow_source[i] : i)]++;
    uint32_t packets = 0, at = 0;
    for (uint32_t b = 0; b < blocks; b++) {
        uint32_t c = fill[b];
        fill[b] = at;
        if (c) out->start[packets++] = at;
        at += c;
    }
    out->start[packets] = n;
    out->count = packets;
    for (uint32_t i = 0; i < n; i++) out->ray[fill[block_of(w, shadow ? w->shadow_source[i] : i)]++] = i;
    free(fill);
    return true;
}

void bench_packets_free(bench_packets *p)
{
    free(p->start);
    free(p->ray);
    memset(p, 0, sizeof *p);
}

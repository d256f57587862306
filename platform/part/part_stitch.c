/* rtp_stitch_same_render and rtp_stitch_coverage; see part_stitch.h. */
#include "part/part_stitch.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How much of a differing value an error shows. */
#define RTP_SHOWN 80

/* The first RTP_SHOWN characters of a field on one line. */
static void shown(const char *text, char out[RTP_SHOWN + 4])
{
    size_t n = 0;
    for (; text[n] && n < RTP_SHOWN; n++) out[n] = text[n] == '\n' ? ' ' : text[n];
    strcpy(out + n, text[n] ? "..." : "");
}

/* Whether two `rtk --version` lines name the same rtk: "rtk 0.5.0 (double build; gcc
 * 12.2.0; commit 1a2b3c4d5e6f)" equal but for the compiler, which does not change a
 * pixel (make check-determinism); lines of another shape must be equal. */
static bool same_version(const char *a, const char *b)
{
    const char *a_compiler = strchr(a, ';'), *b_compiler = strchr(b, ';');
    const char *a_commit = strstr(a, "; commit "), *b_commit = strstr(b, "; commit ");
    if (!a_compiler || !b_compiler || !a_commit || !b_commit || a_commit <= a_compiler || b_commit <= b_compiler)
        return !strcmp(a, b);
    return a_compiler - a == b_compiler - b && !strncmp(a, b, (size_t)(a_compiler - a)) && !strcmp(a_commit, b_commit);
}

bool rtp_stitch_same_render(const rtp_part *part, const char *name, const rtp_part *reference,
                            const char *reference_name, char *err, size_t err_size)
{
    for (int f = RTP_PART_BUILD; f < RTP_PART_REGION; f++) {
        if (f == RTP_PART_VERSION ? same_version(part->text[f], reference->text[f])
                                  : !strcmp(part->text[f], reference->text[f]))
            continue;
        char a[RTP_SHOWN + 4], b[RTP_SHOWN + 4];
        shown(part->text[f], a);
        shown(reference->text[f], b);
        return rtp_part_fail(err, err_size, "%s: other %s than %s: '%s' vs '%s'", name, rtp_part_field_names[f],
                             reference_name, a, b);
    }
    return true;
}

static bool intersect(const rt_rect *a, const rt_rect *b, rt_rect *out)
{
    *out = (rt_rect){a->x0 > b->x0 ? a->x0 : b->x0, a->y0 > b->y0 ? a->y0 : b->y0, a->x1 < b->x1 ? a->x1 : b->x1,
                     a->y1 < b->y1 ? a->y1 : b->y1};
    return out->x0 < out->x1 && out->y0 < out->y1;
}

typedef struct {
    uint32_t x0, x1;
} span;

static int by_start(const void *a, const void *b)
{
    const span *s = a, *t = b;
    return s->x0 < t->x0 ? -1 : s->x0 > t->x0;
}

/* The first uncovered column of row y, or the frame's width when the row is covered. */
static uint32_t row_gap(const rtp_part *parts, uint32_t count, uint32_t y, span *spans)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < count; i++)
        if (parts[i].region.y0 <= y && y < parts[i].region.y1)
            spans[n++] = (span){parts[i].region.x0, parts[i].region.x1};
    qsort(spans, n, sizeof *spans, by_start);
    uint32_t covered = 0;
    for (uint32_t i = 0; i < n && spans[i].x0 <= covered; i++)
        if (spans[i].x1 > covered) covered = spans[i].x1;
    return covered;
}

/* The topmost uncovered pixel, then leftmost in its row. Such a pixel lies in row 0 or
 * right below a part, so only those rows need looking at. False when there is none
 * (or no memory to look). */
static bool first_gap(const rtp_part *parts, uint32_t count, uint32_t *gx, uint32_t *gy)
{
    span *spans = malloc(((size_t)count + 1) * sizeof *spans);
    bool found = false;
    *gy = UINT32_MAX;
    for (uint32_t i = 0; spans && i <= count; i++) {
        uint32_t y = i == count ? 0 : parts[i].region.y1;
        if (y >= parts[0].height || y >= *gy) continue;
        uint32_t x = row_gap(parts, count, y, spans);
        if (x < parts[0].width) *gx = x, *gy = y, found = true;
    }
    free(spans);
    return found;
}

/* The index of --part I/N missing from parts that all share count N, or UINT32_MAX. */
static uint32_t missing_index(const rtp_part *parts, uint32_t count)
{
    uint32_t n = parts[0].count;
    for (uint32_t i = 0; i < count; i++)
        if (parts[i].count != n || n == 0) return UINT32_MAX;
    bool *seen = calloc(n, sizeof *seen);
    uint32_t missing = UINT32_MAX;
    for (uint32_t i = 0; seen && i < count; i++) seen[parts[i].index] = true;
    for (uint32_t i = 0; seen && i < n && missing == UINT32_MAX; i++)
        if (!seen[i]) missing = i;
    free(seen);
    return missing;
}

bool rtp_stitch_coverage(const rtp_part *parts, const char *const *names, uint32_t count, char *err, size_t err_size)
{
    for (uint32_t i = 1; i < count; i++)
        for (uint32_t k = 0; k < i; k++) {
            rt_rect both;
            if (!intersect(&parts[i].region, &parts[k].region, &both)) continue;
            if (!strcmp(names[i], names[k])) return rtp_part_fail(err, err_size, "%s: given twice", names[i]);
            if (!memcmp(&parts[i].region, &parts[k].region, sizeof both))
                return rtp_part_fail(err, err_size, "%s: a duplicate: %s holds the same region %s", names[i], names[k],
                                     parts[i].text[RTP_PART_REGION]);
            return rtp_part_fail(err, err_size, "%s: overlaps %s in pixels %u,%u,%u,%u", names[i], names[k], both.x0,
                                 both.y0, both.x1, both.y1);
        }
    /* Without overlaps, the frame is covered exactly when the areas add up to it. */
    uint64_t area = 0;
    for (uint32_t i = 0; i < count; i++)
        area += (uint64_t)(parts[i].region.x1 - parts[i].region.x0) * (parts[i].region.y1 - parts[i].region.y0);
    if (area == (uint64_t)parts[0].width * parts[0].height) return true;
    uint32_t x, y;
    if (!first_gap(parts, count, &x, &y))
        return rtp_part_fail(err, err_size, "a gap: the parts cover %llu of the %s frame's pixels",
                             (unsigned long long)area, parts[0].text[RTP_PART_FRAME]);
    uint32_t missing = missing_index(parts, count);
    if (missing != UINT32_MAX)
        return rtp_part_fail(err, err_size, "part %u/%u is missing: no part covers pixel (%u, %u) of the %s frame",
                             missing, parts[0].count, x, y, parts[0].text[RTP_PART_FRAME]);
    return rtp_part_fail(err, err_size, "a gap: no part covers pixel (%u, %u) of the %s frame", x, y,
                         parts[0].text[RTP_PART_FRAME]);
}

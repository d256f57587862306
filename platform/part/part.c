/* The fields of a part and their text forms; see part.h. */
#include "part/part.h"

#include "mem/mem.h"
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const rtp_part_keys[RTP_PART_FIELDS] = {
    "rtk build", "rtk version", "rtk scene", "rtk assets", "rtk settings",
    "rtk frame", "rtk region",  "rtk part",  "rtk pixels",
};

const char *const rtp_part_field_names[RTP_PART_FIELDS] = {
    "build",      "rtk version", "scene file", "asset files",  "settings",
    "frame size", "region",      "part index", "pixel digest",
};

void rtp_part_free(rtp_part *p)
{
    for (int f = 0; f < RTP_PART_FIELDS; f++) rtp_mem_free(p->text[f]);
    memset(p, 0, sizeof *p);
}

bool rtp_part_set(rtp_part *p, rtp_part_field f, const char *value)
{
    char *copy = rtp_mem_strdup(value, "a part's text");
    if (!copy) return false;
    rtp_mem_free(p->text[f]);
    p->text[f] = copy;
    return true;
}

bool rtp_part_format_place(rtp_part *p)
{
    char frame[32], region[64], index[32];
    const rt_rect *r = &p->region;
    snprintf(frame, sizeof frame, "%ux%u", p->width, p->height);
    snprintf(region, sizeof region, "%u,%u,%u,%u", r->x0, r->y0, r->x1, r->y1);
    if (p->count)
        snprintf(index, sizeof index, "%u/%u", p->index, p->count);
    else
        snprintf(index, sizeof index, "region");
    return rtp_part_set(p, RTP_PART_FRAME, frame) && rtp_part_set(p, RTP_PART_REGION, region) &&
           rtp_part_set(p, RTP_PART_INDEX, index);
}

/* A whole decimal number at *s, up to the next byte not a digit; false on none or overflow. */
static bool number(const char **s, uint32_t *out)
{
    if (**s < '0' || **s > '9') return false;
    errno = 0;
    char *end;
    unsigned long v = strtoul(*s, &end, 10);
    if (errno || v > UINT32_MAX) return false;
    *s = end;
    *out = (uint32_t)v;
    return true;
}

/* Numbers separated by sep, exactly n of them and nothing after. */
static bool numbers(const char *s, char sep, uint32_t *out, int n)
{
    for (int i = 0; i < n; i++) {
        if (i > 0 && *s++ != sep) return false;
        if (!number(&s, &out[i])) return false;
    }
    return *s == '\0';
}

bool rtp_part_parse_rect(const char *s, rt_rect *out)
{
    uint32_t v[4];
    if (!s || !numbers(s, ',', v, 4) || v[0] >= v[2] || v[1] >= v[3]) return false;
    *out = (rt_rect){v[0], v[1], v[2], v[3]};
    return true;
}

bool rtp_part_parse_index(const char *s, uint32_t max_count, uint32_t *index, uint32_t *count)
{
    uint32_t v[2];
    if (!s || !numbers(s, '/', v, 2) || v[1] == 0 || v[1] > max_count || v[0] >= v[1]) return false;
    *index = v[0];
    *count = v[1];
    return true;
}

bool rtp_part_fail(char *err, size_t err_size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (err_size > 0) vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
    return false;
}

bool rtp_part_parse_place(rtp_part *p, char *err, size_t err_size)
{
    const char *frame = p->text[RTP_PART_FRAME], *region = p->text[RTP_PART_REGION], *index = p->text[RTP_PART_INDEX];
    uint32_t wh[2];
    if (!numbers(frame, 'x', wh, 2) || wh[0] == 0 || wh[1] == 0 || wh[0] > RT_MAX_IMAGE_SIDE ||
        wh[1] > RT_MAX_IMAGE_SIDE)
        return rtp_part_fail(err, err_size, "malformed '%s' text '%s'", rtp_part_keys[RTP_PART_FRAME], frame);
    p->width = wh[0], p->height = wh[1];
    if (!rtp_part_parse_rect(region, &p->region))
        return rtp_part_fail(err, err_size, "malformed '%s' text '%s'", rtp_part_keys[RTP_PART_REGION], region);
    if (p->region.x1 > p->width || p->region.y1 > p->height)
        return rtp_part_fail(err, err_size, "its region %s lies outside its %s frame", region, frame);
    /* rtk render cuts a frame into at most as many parts as it has rows. */
    if (!strcmp(index, "region"))
        p->index = p->count = 0;
    else if (!rtp_part_parse_index(index, p->height, &p->index, &p->count))
        return rtp_part_fail(err, err_size, "malformed '%s' text '%s'", rtp_part_keys[RTP_PART_INDEX], index);
    return true;
}

void rtp_part_hex(const uint8_t digest[32], char hex[65])
{
    static const char digits[] = "0123456789abcdef";
    for (int i = 0; i < 32; i++) {
        hex[2 * i] = digits[digest[i] >> 4];
        hex[2 * i + 1] = digits[digest[i] & 15];
    }
    hex[64] = '\0';
}

char *rtp_part_file_name(const char *dir, uint32_t index, uint32_t count)
{
    size_t size = strlen(dir) + 48;
    char *name = malloc(size);
    if (name)
        snprintf(name, size, "%s%spart-%u-of-%u.png", dir, *dir && dir[strlen(dir) - 1] != '/' ? "/" : "", index,
                 count);
    return name;
}

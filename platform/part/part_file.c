/* Parts as PNG files with text chunks, through libspng; see part_file.h. */
#include "part/part_file.h"

#include "image/file_write.h"
#include "image/image.h"
#include "load/input_file.h"
#include "mem/mem.h"
#include "sha256.h"
#include <spng.h>
#include <stdio.h>
#include <string.h>

/* As image.c: refuse absurd headers and oversized ancillary chunks before reading them. */
#define RTP_PART_CHUNK_LIMIT (16u << 20)
/* Larger than any part within the side limit, so a huge file is refused before reading. */
#define RTP_PART_MAX_FILE (1u << 30)

static void pixel_digest(const uint8_t *rgb, const rt_rect *r, char hex[65])
{
    uint8_t digest[32];
    rt_sha256 h;
    rt_sha256_init(&h);
    rt_sha256_update(&h, rgb, (size_t)(r->x1 - r->x0) * (r->y1 - r->y0) * 3);
    rt_sha256_final(&h, digest);
    rtp_part_hex(digest, hex);
}

/* The PNG (rtp_mem's, allocated by spng) or NULL with *rc set. */
static void *encode(const rtp_part *p, const uint8_t *rgb, size_t *size, int *rc)
{
    spng_ctx *ctx = rtp_png_ctx_new(SPNG_CTX_ENCODER);
    if (!ctx) {
        *rc = SPNG_EMEM;
        return NULL;
    }
    uint32_t w = p->region.x1 - p->region.x0, h = p->region.y1 - p->region.y0;
    struct spng_ihdr ihdr = {.width = w, .height = h, .bit_depth = 8, .color_type = SPNG_COLOR_TYPE_TRUECOLOR};
    struct spng_text text[RTP_PART_FIELDS];
    memset(text, 0, sizeof text);
    for (int f = 0; f < RTP_PART_FIELDS; f++) {
        snprintf(text[f].keyword, sizeof text[f].keyword, "%s", rtp_part_keys[f]);
        text[f].type = SPNG_TEXT;
        text[f].text = p->text[f];
        text[f].length = strlen(p->text[f]);
    }
    void *png = NULL;
    *rc = spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
    if (*rc == 0) *rc = spng_set_ihdr(ctx, &ihdr);
    if (*rc == 0) *rc = spng_set_text(ctx, text, RTP_PART_FIELDS);
    if (*rc == 0) *rc = spng_encode_image(ctx, rgb, (size_t)w * h * 3, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    if (*rc == 0) png = spng_get_png_buffer(ctx, size, rc);
    spng_ctx_free(ctx);
    return png;
}

bool rtp_part_write(const char *path, rtp_part *p, const uint8_t *rgb, char *err, size_t err_size)
{
    char hex[65];
    pixel_digest(rgb, &p->region, hex);
    if (!rtp_part_set(p, RTP_PART_PIXELS, hex)) {
        snprintf(err, err_size, "%s: %s", path, rtp_mem_refusal());
        return false;
    }
    int rc;
    size_t size = 0;
    void *png = encode(p, rgb, &size, &rc);
    if (!png) {
        snprintf(err, err_size, "%s: cannot encode the part: %s", path,
                 rc == SPNG_EMEM ? rtp_mem_refusal() : spng_strerror(rc));
        return false;
    }
    bool ok = rtp_file_write(path, png, size, err, err_size);
    rtp_mem_free(png);
    return ok;
}

/* Copies the part's fields out of the decoded text chunks; other keywords are ignored. */
static bool take_fields(spng_ctx *ctx, rtp_part *p, char *err, size_t err_size)
{
    uint32_t n = 0;
    if (spng_get_text(ctx, NULL, &n) != 0) n = 0;
    struct spng_text *text = n ? rtp_mem_calloc(n, sizeof *text, "a part's text chunks") : NULL;
    if (n && (!text || spng_get_text(ctx, text, &n) != 0)) {
        rtp_mem_free(text);
        snprintf(err, err_size, "%s", rtp_mem_refusal());
        return false;
    }
    bool ok = true;
    for (uint32_t i = 0; ok && i < n; i++)
        for (int f = 0; ok && f < RTP_PART_FIELDS; f++) {
            if (strcmp(text[i].keyword, rtp_part_keys[f])) continue;
            if (p->text[f])
                ok = rtp_part_fail(err, err_size, "corrupt: two '%s' text chunks", rtp_part_keys[f]);
            else if (!rtp_part_set(p, f, text[i].text))
                ok = rtp_part_fail(err, err_size, "%s", rtp_mem_refusal());
        }
    rtp_mem_free(text);
    for (int f = 0; ok && f < RTP_PART_FIELDS; f++)
        if (!p->text[f]) ok = rtp_part_fail(err, err_size, "not an rtk part: no '%s' text chunk", rtp_part_keys[f]);
    return ok && rtp_part_parse_place(p, err, err_size);
}

/* Decodes the whole PNG (so a truncated or corrupt file is caught) into *rgb. */
static bool decode(const uint8_t *png, size_t png_size, rtp_part *p, uint8_t **rgb, char *err, size_t err_size)
{
    spng_ctx *ctx = rtp_png_ctx_new(0);
    if (!ctx) return rtp_part_fail(err, err_size, "%s", rtp_mem_refusal());
    struct spng_ihdr ihdr;
    size_t len = 0;
    char what[64];
    int rc = spng_set_image_limits(ctx, RT_MAX_IMAGE_SIDE, RT_MAX_IMAGE_SIDE);
    if (rc == 0) rc = spng_set_chunk_limits(ctx, RTP_PART_CHUNK_LIMIT, RTP_PART_CHUNK_LIMIT);
    /* A damaged text chunk is an error, not a chunk silently dropped. */
    if (rc == 0) rc = spng_set_crc_action(ctx, SPNG_CRC_ERROR, SPNG_CRC_ERROR);
    if (rc == 0) rc = spng_set_png_buffer(ctx, png, png_size);
    if (rc == 0) rc = spng_get_ihdr(ctx, &ihdr);
    if (rc == 0) rc = spng_decoded_image_size(ctx, SPNG_FMT_RGB8, &len);
    /* The pixels are allocated from the header, before any is decoded. */
    if (rc == 0) snprintf(what, sizeof what, "the part's pixels (%ux%u)", ihdr.width, ihdr.height);
    if (rc == 0 && !(*rgb = rtp_mem_alloc(len, what))) rc = SPNG_EMEM;
    if (rc == 0) rc = spng_decode_image(ctx, *rgb, len, SPNG_FMT_RGB8, 0);
    if (rc == 0) rc = spng_decode_chunks(ctx); /* on to IEND: a part cut short after its pixels is truncated too */
    bool ok = rc == 0;
    if (rc == SPNG_IO_EOF || rc == SPNG_EOF)
        rtp_part_fail(err, err_size, "truncated (the PNG ends early)");
    else if (rc == SPNG_EMEM)
        rtp_part_fail(err, err_size, "%s", rtp_mem_refusal());
    else if (rc != 0)
        rtp_part_fail(err, err_size, "corrupt PNG: %s", spng_strerror(rc));
    ok = ok && take_fields(ctx, p, err, err_size);
    if (ok && (ihdr.width != p->region.x1 - p->region.x0 || ihdr.height != p->region.y1 - p->region.y0))
        ok = rtp_part_fail(err, err_size, "its image is %ux%u but its region %s is %ux%u", ihdr.width, ihdr.height,
                           p->text[RTP_PART_REGION], p->region.x1 - p->region.x0, p->region.y1 - p->region.y0);
    spng_ctx_free(ctx);
    return ok;
}

/* The file's first and last bytes: a PNG signature, and the IEND chunk rtk writes last
 * (libspng does not insist on IEND's checksum, so a part missing its last bytes would pass). */
static bool check_ends(const uint8_t *png, size_t size, char *err, size_t err_size)
{
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    if (size == 0) return rtp_part_fail(err, err_size, "empty file");
    if (size < 8 || memcmp(png, signature, 8)) return rtp_part_fail(err, err_size, "not an rtk part (not a PNG file)");
    if (size < 20 || memcmp(png + size - 12, iend, 12))
        return rtp_part_fail(err, err_size, "truncated (the PNG ends early)");
    return true;
}

bool rtp_part_read(const char *path, rtp_part *p, uint8_t **rgb, char *err, size_t err_size)
{
    memset(p, 0, sizeof *p);
    rtp_input in;
    char why[512];
    uint8_t *png = NULL;
    size_t size = 0;
    if (!rtp_input_open(&in, path, false, why, sizeof why))
        return rtp_part_fail(err, err_size, "%s%s", in.open_failed ? "cannot open: " : "", why);
    if (!rtp_input_read(&in, RTP_PART_MAX_FILE, "a part", &png, &size, err, err_size)) return false;
    uint8_t *pixels = NULL;
    bool ok = check_ends(png, size, err, err_size) && decode(png, size, p, &pixels, err, err_size);
    rtp_mem_free(png);
    char hex[65];
    if (ok) pixel_digest(pixels, &p->region, hex);
    if (ok && strcmp(hex, p->text[RTP_PART_PIXELS]))
        ok = rtp_part_fail(err, err_size, "corrupt: its pixels do not match their digest");
    if (ok && rgb)
        *rgb = pixels;
    else
        rtp_mem_free(pixels);
    if (!ok) rtp_part_free(p);
    return ok;
}

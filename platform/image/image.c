/* Image files: PNG through libspng, binary PPM (P6, maxval 255) by hand; 8-bit RGB in memory. */
#include "image/image.h"
#include "image/file_write.h"
#include "scene.h"

#include "mem/mem.h"
#include <spng.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

/* Against decompression bombs and absurd headers: the scene's image limit, RT_MAX_IMAGE_SIDE. */
/* Larger than any PNG or PPM within the side limit, so a huge file is refused before reading. */
#define RTP_IMAGE_MAX_FILE (1u << 30)
/* Ancillary chunks (text, ICC profiles) are skipped, but spng still buffers them. */
#define RTP_PNG_CHUNK_LIMIT (16u << 20)

static const uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static bool fail(char *err, size_t err_size, const char *path, const char *fmt, ...)
{
    if (err_size == 0) return false;
    int n = snprintf(err, err_size, "%s: ", path);
    if (n >= 0 && (size_t)n < err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err + n, err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

static bool check_size(const char *path, uint32_t w, uint32_t h, char *err, size_t err_size)
{
    if (w == 0 || h == 0) return fail(err, err_size, path, "image has zero width or height");
    if (w > RT_MAX_IMAGE_SIDE || h > RT_MAX_IMAGE_SIDE)
        return fail(err, err_size, path, "image %ux%u exceeds the %ux%u limit", w, h, RT_MAX_IMAGE_SIDE,
                    RT_MAX_IMAGE_SIDE);
    return true;
}

/* libspng allocates through these, so its buffers count against --max-memory too. */
static void *codec_malloc(size_t size) { return rtp_mem_alloc(size, "the PNG codec's buffers"); }
static void *codec_realloc(void *p, size_t size) { return rtp_mem_realloc(p, size, "the PNG codec's buffers"); }
static void *codec_calloc(size_t count, size_t size) { return rtp_mem_calloc(count, size, "the PNG codec's buffers"); }
spng_ctx *rtp_png_ctx_new(int flags)
{
    struct spng_alloc counted = {codec_malloc, codec_realloc, codec_calloc, rtp_mem_free};
    return spng_ctx_new2(&counted, flags);
}

bool rtp_image_alloc(rtp_image *img, uint32_t width, uint32_t height, const char *what)
{
    char described[96];
    snprintf(described, sizeof described, "%s (%ux%u)", what, width, height);
    *img = (rtp_image){.width = width, .height = height};
    img->rgb = rtp_mem_calloc((size_t)width * height, 3, described);
    return img->rgb != NULL;
}

static bool png_decode(const char *path, const uint8_t *data, size_t size, rtp_image *out, char *err, size_t err_size)
{
    spng_ctx *ctx = rtp_png_ctx_new(0);
    if (!ctx) return fail(err, err_size, path, "%s", rtp_mem_refusal());
    struct spng_ihdr ihdr;
    size_t len = 0;
    uint8_t *rgb = NULL;
    int rc = spng_set_image_limits(ctx, RT_MAX_IMAGE_SIDE, RT_MAX_IMAGE_SIDE);
    if (rc == 0) rc = spng_set_chunk_limits(ctx, RTP_PNG_CHUNK_LIMIT, RTP_PNG_CHUNK_LIMIT);
    if (rc == 0) rc = spng_set_png_buffer(ctx, data, size);
    if (rc == 0) rc = spng_get_ihdr(ctx, &ihdr);
    if (rc == 0) rc = spng_decoded_image_size(ctx, SPNG_FMT_RGB8, &len);
    /* The pixels are allocated from the header, before any is decoded. */
    char what[64];
    if (rc == 0) snprintf(what, sizeof what, "the decoded image (%ux%u)", ihdr.width, ihdr.height);
    if (rc == 0 && !(rgb = rtp_mem_alloc(len, what))) rc = SPNG_EMEM;
    /* No SPNG_DECODE_GAMMA / _TRNS: the stored 8-bit values, as the reference tools read them. */
    if (rc == 0) rc = spng_decode_image(ctx, rgb, len, SPNG_FMT_RGB8, 0);
    spng_ctx_free(ctx);
    if (rc != 0) {
        rtp_mem_free(rgb);
        if (rc == SPNG_EMEM) return fail(err, err_size, path, "%s", rtp_mem_refusal());
        if (rc == SPNG_EUSER_WIDTH || rc == SPNG_EUSER_HEIGHT)
            return fail(err, err_size, path, "PNG exceeds the %ux%u image limit", RT_MAX_IMAGE_SIDE, RT_MAX_IMAGE_SIDE);
        if (rc == SPNG_EOF || rc == SPNG_IO_EOF) return fail(err, err_size, path, "truncated PNG (file ends early)");
        return fail(err, err_size, path, "invalid PNG: %s", spng_strerror(rc));
    }
    *out = (rtp_image){.width = ihdr.width, .height = ihdr.height, .rgb = rgb};
    return true;
}

static bool ppm_space(uint8_t c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }

/* Reads one decimal header field at *pos, skipping whitespace and '#' comments before it. */
static bool ppm_field(const uint8_t *d, size_t n, size_t *pos, uint32_t *value)
{
    size_t p = *pos;
    for (;;) {
        while (p < n && ppm_space(d[p])) p++;
        if (p >= n || d[p] != '#') break;
        while (p < n && d[p] != '\n' && d[p] != '\r') p++;
    }
    if (p >= n || d[p] < '0' || d[p] > '9') return false;
    uint64_t v = 0;
    for (; p < n && d[p] >= '0' && d[p] <= '9'; p++) {
        v = v * 10 + (uint64_t)(d[p] - '0');
        if (v > UINT32_MAX) return false;
    }
    *pos = p;
    *value = (uint32_t)v;
    return true;
}

static bool ppm_decode(const char *path, const uint8_t *d, size_t n, rtp_image *out, char *err, size_t err_size)
{
    if (d[1] != '6') return fail(err, err_size, path, "Netpbm type P%c is not supported (only binary P6 PPM)", d[1]);
    static const char *const names[3] = {"width", "height", "maxval"};
    uint32_t v[3];
    size_t pos = 2;
    for (int i = 0; i < 3; i++)
        if (!ppm_field(d, n, &pos, &v[i]))
            return fail(err, err_size, path, "bad PPM header: expected the %s", names[i]);
    if (v[2] != 255) return fail(err, err_size, path, "PPM maxval %u is not supported (only 255)", v[2]);
    if (pos >= n || !ppm_space(d[pos]))
        return fail(err, err_size, path, "bad PPM header: expected whitespace after maxval");
    pos++; /* exactly one whitespace byte separates the header from the raster */
    if (!check_size(path, v[0], v[1], err, err_size)) return false;
    size_t want = (size_t)v[0] * v[1] * 3;
    if (n - pos < want) return fail(err, err_size, path, "truncated PPM: %zu of %zu pixel bytes", n - pos, want);
    char what[64];
    snprintf(what, sizeof what, "the decoded image (%ux%u)", v[0], v[1]);
    uint8_t *rgb = rtp_mem_alloc(want, what);
    if (!rgb) return fail(err, err_size, path, "%s", rtp_mem_refusal());
    memcpy(rgb, d + pos, want);
    *out = (rtp_image){.width = v[0], .height = v[1], .rgb = rgb};
    return true;
}

bool rtp_image_read(const char *path, rtp_image *out, char *err, size_t err_size)
{
    rtp_input in;
    char why[256];
    *out = (rtp_image){0};
    if (!rtp_input_open(&in, path, false, why, sizeof why))
        return fail(err, err_size, path, "%s%s", in.open_failed ? "cannot open: " : "", why);
    return rtp_image_read_input(&in, out, err, err_size);
}

bool rtp_image_read_input(rtp_input *in, rtp_image *out, char *err, size_t err_size)
{
    *out = (rtp_image){0};
    uint8_t *data = NULL;
    size_t size = 0;
    char why[256];
    if (!rtp_input_read(in, RTP_IMAGE_MAX_FILE, "an image", &data, &size, why, sizeof why))
        return fail(err, err_size, in->path, "%s", why);
    bool ok;
    if (size == 0)
        ok = fail(err, err_size, in->path, "empty file");
    else if (size >= sizeof png_signature && memcmp(data, png_signature, sizeof png_signature) == 0)
        ok = png_decode(in->path, data, size, out, err, err_size);
    else if (size >= 2 && data[0] == 'P' && data[1] >= '1' && data[1] <= '7')
        ok = ppm_decode(in->path, data, size, out, err, err_size);
    else
        ok = fail(err, err_size, in->path, "not a PNG or PPM file (unrecognised signature)");
    rtp_mem_free(data);
    return ok;
}

static bool ends_with_png(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".png") == 0;
}

/* The exact bytes the render hash is defined on: "P6\n<w> <h>\n255\n" + rgb. */
static uint8_t *ppm_encode(const rtp_image *img, size_t rgb_size, size_t *size)
{
    char header[48];
    int h = snprintf(header, sizeof header, "P6\n%u %u\n255\n", img->width, img->height);
    uint8_t *buf = rtp_mem_alloc((size_t)h + rgb_size, "the encoded image");
    if (!buf) return NULL;
    memcpy(buf, header, (size_t)h);
    memcpy(buf + h, img->rgb, rgb_size);
    *size = (size_t)h + rgb_size;
    return buf;
}

/* Most pixels of a Whitted render repeat their left neighbour (its background and flat
 * shading: 83-98% on the corpus), and such images compress smaller and encode 2.5-3 times
 * faster unfiltered than with libspng's adaptive choice of row filters; noisy ones (a
 * Monte Carlo render: 4%) gain a quarter in size from the filters. Decided from the
 * pixels alone, so an image always gives the same bytes whoever writes it. */
static int png_filter_choice(const rtp_image *img)
{
    uint64_t repeats = 0, pairs = (uint64_t)(img->width - 1) * img->height;
    for (uint32_t y = 0; y < img->height; y++) {
        const uint8_t *row = img->rgb + (size_t)y * img->width * 3;
        for (uint32_t x = 1; x < img->width; x++) repeats += memcmp(row + 3 * x, row + 3 * x - 3, 3) == 0;
    }
    return repeats * 2 > pairs ? SPNG_FILTER_CHOICE_NONE : SPNG_FILTER_CHOICE_ALL;
}

/* Returns the PNG (allocated by spng through rtp_mem) or NULL with *rc set. */
static void *png_encode(const rtp_image *img, size_t rgb_size, size_t *size, int *rc)
{
    spng_ctx *ctx = rtp_png_ctx_new(SPNG_CTX_ENCODER);
    if (!ctx) {
        *rc = SPNG_EMEM;
        return NULL;
    }
    struct spng_ihdr ihdr = {
        .width = img->width,
        .height = img->height,
        .bit_depth = 8,
        .color_type = SPNG_COLOR_TYPE_TRUECOLOR,
    };
    void *png = NULL;
    *rc = spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
    if (*rc == 0) *rc = spng_set_ihdr(ctx, &ihdr);
    if (*rc == 0) *rc = spng_set_option(ctx, SPNG_FILTER_CHOICE, png_filter_choice(img));
    if (*rc == 0) *rc = spng_encode_image(ctx, img->rgb, rgb_size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    if (*rc == 0) png = spng_get_png_buffer(ctx, size, rc);
    spng_ctx_free(ctx);
    return png;
}

/* path only names the image in error messages. */
static void *encode_png(const char *path, const rtp_image *img, size_t *size, char *err, size_t err_size)
{
    int rc;
    void *bytes = png_encode(img, (size_t)img->width * img->height * 3, size, &rc);
    if (!bytes && rc == SPNG_EMEM) fail(err, err_size, path, "%s", rtp_mem_refusal());
    if (!bytes && rc != SPNG_EMEM) fail(err, err_size, path, "cannot encode PNG: %s", spng_strerror(rc));
    return bytes;
}

void *rtp_image_encode_png(const rtp_image *img, size_t *size, char *err, size_t err_size)
{
    if (!img->rgb) {
        fail(err, err_size, "image", "no pixels to encode");
        return NULL;
    }
    if (!check_size("image", img->width, img->height, err, err_size)) return NULL;
    return encode_png("image", img, size, err, err_size);
}

bool rtp_image_write(const char *path, const rtp_image *img, char *err, size_t err_size)
{
    if (!img->rgb) return fail(err, err_size, path, "no pixels to write");
    if (!check_size(path, img->width, img->height, err, err_size)) return false;
    size_t rgb_size = (size_t)img->width * img->height * 3;
    size_t size = 0;
    void *bytes;
    if (ends_with_png(path)) {
        if (!(bytes = encode_png(path, img, &size, err, err_size))) return false;
    } else if (!(bytes = ppm_encode(img, rgb_size, &size))) {
        return fail(err, err_size, path, "%s", rtp_mem_refusal());
    }
    bool ok = rtp_file_write(path, bytes, size, err, err_size);
    rtp_mem_free(bytes);
    return ok;
}

void rtp_image_free(rtp_image *img)
{
    rtp_mem_free(img->rgb);
    *img = (rtp_image){0};
}

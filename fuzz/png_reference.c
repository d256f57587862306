/* libpng as fuzz_png's reference decoder; see png_reference.h. */
#include "png_reference.h"

#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const uint8_t *data;
    size_t size, pos;
} source;

static void read_bytes(png_structp png, png_bytep out, size_t n)
{
    source *s = png_get_io_ptr(png);
    if (n > s->size - s->pos) png_error(png, "read past the end");
    memcpy(out, s->data + s->pos, n);
    s->pos += n;
}

static void quiet(png_structp png, png_const_charp message) { (void)png, (void)message; }

uint8_t *fz_png_reference_decode(const uint8_t *data, size_t size, size_t max_pixels, uint32_t *width, uint32_t *height)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, quiet);
    if (!png) return NULL;
    png_infop info = png_create_info_struct(png);
    source src = {data, size, 0};
    uint8_t *volatile rgb = NULL;
    png_bytep *volatile rows = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        free(rgb);
        free(rows);
        png_destroy_read_struct(&png, info ? &info : NULL, NULL);
        return NULL;
    }
    png_set_read_fn(png, &src, read_bytes);
    png_read_info(png, info);
    uint32_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if ((size_t)w * h > max_pixels) png_error(png, "too large for the check");
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_gray_to_rgb(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)w * 3) png_error(png, "not 8-bit RGB after the transforms");
    rgb = malloc((size_t)w * h * 3 + 1);
    rows = malloc(sizeof *rows * (h ? h : 1));
    if (!rgb || !rows) png_error(png, "out of memory");
    for (uint32_t y = 0; y < h; y++) rows[y] = rgb + (size_t)y * w * 3;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    *width = w;
    *height = h;
    return rgb;
}

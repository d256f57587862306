/* libFuzzer target: the image reader (platform/image/image.c: PNG through libspng, and
 * P6 PPM) on arbitrary bytes. It must refuse or return width * height * 3 readable
 * bytes, never crash, never leak. Differential: a PNG that both libspng (through
 * rtp_image_read) and libpng (fuzz/png_reference.c) decode gives the same size and
 * the same bytes. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image/image.h"
#include "png_reference.h"
#include "scratch.h"

static volatile uint8_t sink;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_scratch_write("input.png", data, size);
    rtp_image img;
    char err[512];
    if (!rtp_image_read(path, &img, err, sizeof err)) {
        FZ_CHECK(err[0] != 0, "refused without a message");
        return 0;
    }
    FZ_CHECK(img.width > 0 && img.height > 0 && img.rgb, "accepted an empty %ux%u image", img.width, img.height);
    /* Reading every byte lets ASan check the buffer is as large as claimed. */
    for (size_t i = 0; i < (size_t)img.width * img.height * 3; i++) sink = img.rgb[i];
    uint32_t w, h;
    uint8_t *ref =
        size >= 8 && memcmp(data, "\x89PNG", 4) == 0 ? fz_png_reference_decode(data, size, 1u << 22, &w, &h) : NULL;
    if (ref) {
        FZ_CHECK(w == img.width && h == img.height, "libspng reads %ux%u, libpng %ux%u", img.width, img.height, w, h);
        size_t n = (size_t)w * h * 3, at = 0;
        while (at < n && ref[at] == img.rgb[at]) at++;
        FZ_CHECK(at == n, "byte %zu of %zu: libspng %u, libpng %u", at, n, img.rgb[at], ref[at]);
        free(ref);
    }
    rtp_image_free(&img);
    return 0;
}

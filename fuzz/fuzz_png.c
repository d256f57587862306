/* libFuzzer target: the image reader (platform/image/image.c: PNG through libspng, and
 * P6 PPM) on arbitrary bytes. It must refuse or return width * height * 3 readable
 * bytes, never crash, never leak. */
#include "check.h"
#include "image/image.h"
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
    rtp_image_free(&img);
    return 0;
}

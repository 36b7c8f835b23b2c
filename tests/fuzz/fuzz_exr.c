/* fuzz_exr.c — the EXR reader (sh_exr_read_mem, which sh_exr_read and so
 * every command reading an EXR uses) on arbitrary bytes, with limits small
 * enough that a refused size is cheap: 64 MB, 2^22 pixels. */
#include "fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sh_exr_limits lim;
    sh_exr_limits_default(&lim);
    lim.max_bytes = 64LL << 20;
    lim.max_pixels = 1LL << 22;
    sh_image img;
    int fb = -1;
    const int st = sh_exr_read_mem(data, size, "fuzz.exr", &lim, &img, &fb);
    if (st == SH_OK) {
        FUZZ_CHECK(img.data && img.width >= 1 && img.height >= 1, "empty image on success");
        FUZZ_CHECK(img.nchan == 1 || img.nchan == 3, "%d channels", img.nchan);
        FUZZ_CHECK((long long)img.width * img.height <= lim.max_pixels, "limit ignored");
        FUZZ_CHECK(fb == 0 || fb == 1, "fallback flag %d", fb);
        /* touch every pixel (ASan sees a short allocation) */
        double s = 0;
        const size_t n = (size_t)img.width * img.height * img.nchan;
        for (size_t i = 0; i < n; i++) s += isfinite(img.data[i]) ? 0.0 : 1.0;
        (void)s;
    } else {
        FUZZ_CHECK(!img.data && img.width == 0 && img.nchan == 0, "image left after an error");
        FUZZ_CHECK(st == SH_EFORMAT || st == SH_ENOMEM || st == SH_ENOTSUP, "status %d", st);
        fuzz_check_reason();
    }
    sh_image_free(&img);
    return 0;
}

/* fuzz_coeffs.c — coefficient files (cli_read_coeffs_mem: JSON
 * {"coeffs"}/{"channels"} or plain numbers, as --in of reconstruct, rotate,
 * convert and scale reads them), then a conversion of what was read. */
#include "fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *s = fuzz_cstr(data, size);
    double *v = NULL;
    int len = 0, nchan = 0;
    char names[SH_IMAGE_MAX_CHANNELS][8];
    const int rc = cli_read_coeffs_mem(s, size, "fuzz.json", &v, &len, &nchan, names);
    if (rc == 0) {
        FUZZ_CHECK(v && len >= 1 && nchan >= 1 && nchan <= SH_IMAGE_MAX_CHANNELS, "len %d nchan %d",
                   len, nchan);
        for (long i = 0; i < (long)len * nchan; i++) FUZZ_CHECK(isfinite(v[i]), "value %ld", i);
        for (int c = 0; c < nchan; c++) FUZZ_CHECK(memchr(names[c], '\0', 8) && names[c][0], "name");
        const int order = (int)lround(sqrt((double)len));
        if (order * order == len && order <= 64)
            for (int c = 0; c < nchan; c++) sh_convert(order, SH_NORM_CS, SH_NORM_SCHMIDT, v + (size_t)c * len);
        free(v);
    } else {
        FUZZ_CHECK(rc == CLI_EXIT_USAGE, "exit code %d", rc);
    }
    free(s);
    return 0;
}

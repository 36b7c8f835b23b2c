/* fuzz_candidate.c — candidate files of `shlab verify --candidate`
 * (sh_fixture_load_candidate_mem) against a small fixed fixture: an order-3 case,
 * a band-2 case and an order-1 case with a non-ASCII id. */
#include "fuzz.h"

static sh_fixture fx;
static int loaded;

static const char fixture[] =
    "{\"format\":\"shlab-rotation-fixtures/1\",\"cases\":["
    "{\"id\":\"o3\",\"order\":3,\"convention\":\"cs\",\"rotation\":{\"euler\":[0.1,0.2,0.3]},"
    "\"input\":[1,0,0,0,0,0,0,0,0],\"expected\":[1,0,0,0,0,0,0,0,0],"
    "\"expected_float32\":[1,0,0,0,0,0,0,0,0],\"tolerance\":{\"double\":1e-12,\"float32\":1e-5}},"
    "{\"id\":\"b2\",\"order\":3,\"band\":2,\"convention\":\"nocs\",\"rotation\":{\"euler\":[1,2,3]},"
    "\"input\":[0,0,1,0,0],\"expected\":[0,0,1,0,0],\"expected_float32\":[0,0,1,0,0],"
    "\"tolerance\":{\"double\":1e-12,\"float32\":1e-5}},"
    "{\"id\":\"\\u00e91\",\"order\":1,\"convention\":\"cs\",\"rotation\":{\"euler\":[0,0,0]},"
    "\"input\":[2],\"expected\":[2],\"expected_float32\":[2],"
    "\"tolerance\":{\"double\":1e-12,\"float32\":1e-5}}]}";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!loaded) {
        if (sh_fixture_load_mem(fixture, sizeof fixture - 1, "built-in fixture", &fx)) abort();
        loaded = 1;
    }
    char *s = fuzz_cstr(data, size);
    double *out[3];
    for (int k = 0; k < fx.ncases; k++) {
        out[k] = malloc((size_t)fx.cases[k].n * sizeof **out);
        if (!out[k]) abort();
    }
    /* every case wanted, then only the first (the others may be absent) */
    static const unsigned char first_only[3] = {1, 0, 0};
    unsigned char present[3];
    int rc = sh_fixture_load_candidate_mem(s, size, "fuzz.json", &fx, NULL, out, NULL);
    FUZZ_CHECK(rc == SH_OK || rc == SH_EFORMAT, "status %d", rc);
    if (rc) fuzz_check_reason();
    rc = sh_fixture_load_candidate_mem(s, size, "fuzz.json", &fx, first_only, out, present);
    FUZZ_CHECK(rc == SH_OK || rc == SH_EFORMAT, "status %d", rc);
    if (rc) fuzz_check_reason();
    for (int k = 0; k < fx.ncases; k++) free(out[k]);
    free(s);
    return 0;
}

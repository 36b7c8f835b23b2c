/* fuzz_fixture.c — rotation fixture files (sh_fixture_load_mem, as `shlab verify
 * --fixture` and the fixture tests read them), then what verify does with a
 * loaded case: rotate its input with an exact method and compare. */
#include "fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *s = fuzz_cstr(data, size);
    sh_fixture fx;
    const int rc = sh_fixture_load_mem(s, size, "fuzz.json", &fx);
    if (rc == 0) {
        FUZZ_CHECK(fx.ncases >= 1 && fx.cases, "no cases after success");
        for (int k = 0; k < fx.ncases; k++) {
            const sh_fixture_case *c = &fx.cases[k];
            FUZZ_CHECK(c->order >= 1 && c->order <= 1001 && c->band < c->order && c->band >= -1,
                       "order %d band %d", c->order, c->band);
            FUZZ_CHECK(c->n == (c->band >= 0 ? 2 * c->band + 1 : c->order * c->order), "n %d", c->n);
            /* small cases only: the harness must stay fast */
            if (c->n > 400) continue;
            double *out = malloc((size_t)c->n * sizeof *out);
            if (!out) abort();
            if (sh_fixture_apply(SH_ROT_IVANIC, SH_PREC_DOUBLE, SH_KERNEL_AUTO, 0, c, &c->rot, c->conv, c->input, out) == SH_OK) {
                double e = 0;
                for (int i = 0; i < c->n; i++) e = fmax(e, fabs(out[i] - c->expected[i]));
                (void)e;
            } else {
                fuzz_check_reason();
            }
            free(out);
        }
        sh_fixture_free(&fx);
    } else {
        FUZZ_CHECK(rc == SH_EFORMAT && fx.ncases == 0 && !fx.cases, "state after an error");
        fuzz_check_reason();
    }
    free(s);
    return 0;
}

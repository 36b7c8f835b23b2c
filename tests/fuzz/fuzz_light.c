/* fuzz_light.c — the text specs the commands take: light specs (--light,
 * sh_light_parse, then the light evaluated and, where it has one, its
 * closed-form projection), windows (--window), and the named choices
 * (--rule, --method, --precision, --convention, --from/--to, --layout,
 * --family, --measure, ...).  The first byte picks the parser and flags. */
#include "fuzz.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    const unsigned sel = data[0];
    char *s = fuzz_cstr(data + 1, size - 1);
    int st;
    switch (sel % 12) {
    case 0:
    case 1: {
        sh_light L;
        st = sh_light_parse(s, sel & 16, &L);
        if (st == SH_OK) {
            static const double dirs[5][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.6, 0, 0.8}, {0, 0.6, -0.8}};
            for (int k = 0; k < 5; k++) {
                const double th = acos(dirs[k][2]), ph = atan2(dirs[k][1], dirs[k][0]);
                const double v = sh_light_eval(&L, dirs[k], th, ph);
                FUZZ_CHECK(!isnan(v), "light '%s' is NaN at direction %d", s, k);
            }
            if (sh_light_has_closed_form(&L)) {
                const int order = 1 + (int)(sel >> 5);
                double c[64];
                if (sh_light_closed_form(&L, order, SH_CS, c) != SH_OK) fuzz_check_reason();
            }
        }
        break;
    }
    case 2: {
        sh_window w;
        st = sh_window_parse(s, &w);
        if (st == SH_OK)
            for (int l = 0; l < 20; l++)
                FUZZ_CHECK(isfinite(sh_window_factor(&w, l, 8)), "window '%s' factor %d", s, l);
        break;
    }
    case 3: { sh_rule r; st = sh_rule_parse(s, &r); break; }
    case 4: { sh_rot_method m; st = sh_rot_method_parse(s, &m); break; }
    case 5: { sh_precision p; st = sh_precision_parse(s, &p); break; }
    case 6: { sh_convention c; st = sh_convention_parse(s, &c); break; }
    case 7: { sh_norm n; st = sh_norm_parse(s, &n); break; }
    case 8: { sh_layout l; st = sh_layout_parse(s, &l); break; }
    case 9: { sh_scale_family f; st = sh_scale_family_parse(s, &f); break; }
    case 10: { sh_error_measure m; st = sh_error_measure_parse(s, &m); break; }
    default: {
        sh_scale_spacing sp;
        sh_scale_interp_kind ik;
        sh_scale_scene_kind sk;
        st = (sel & 16) ? sh_scale_spacing_parse(s, &sp)
           : (sel & 32) ? sh_scale_interp_parse(s, &ik) : sh_scale_scene_parse(s, &sk);
        break;
    }
    }
    if (st != SH_OK) {
        FUZZ_CHECK(st == SH_EINVAL || st == SH_ENOTSUP, "status %d", st);
        fuzz_check_reason();
    }
    free(s);
    return 0;
}

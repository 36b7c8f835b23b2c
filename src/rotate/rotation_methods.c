/* rotation_methods.c — the registry of rotation methods: one ops table per
 * method (defined in the method's own file, rot_internal.h), their names,
 * limits and the default choice by order. */
#include "rotate/rot_internal.h"

#include <string.h>

static const sh__rot_ops *const methods[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = &sh__rot_z_ops,
    [SH_ROT_IVANIC] = &sh__rot_ivanic_ops,
    [SH_ROT_ZXZXZ] = &sh__rot_zxzxz_ops,
    [SH_ROT_CHOI] = &sh__rot_choi_ops,
    [SH_ROT_BLANCO] = &sh__rot_blanco_ops,
    [SH_ROT_WIGNER] = &sh__rot_wigner_ops,
    [SH_ROT_REFERENCE] = &sh__rot_reference_ops,
    [SH_ROT_TAYLOR1] = &sh__rot_taylor1_ops, [SH_ROT_TAYLOR15] = &sh__rot_taylor15_ops, [SH_ROT_TAYLOR2] = &sh__rot_taylor2_ops,
    [SH_ROT_HALFPI] = &sh__rot_halfpi_ops,
    [SH_ROT_DIRECT] = &sh__rot_direct_ops,
    [SH_ROT_ZH] = &sh__rot_zh_ops,
};

static const char *const method_names[SH_ROT_NMETHODS] = {
    [SH_ROT_Z] = "z",           [SH_ROT_IVANIC] = "ivanic", [SH_ROT_ZXZXZ] = "zxzxz",
    [SH_ROT_CHOI] = "choi",     [SH_ROT_BLANCO] = "blanco", [SH_ROT_WIGNER] = "wigner",
    [SH_ROT_REFERENCE] = "reference", [SH_ROT_TAYLOR1] = "taylor1", [SH_ROT_TAYLOR15] = "taylor1.5",
    [SH_ROT_TAYLOR2] = "taylor2", [SH_ROT_HALFPI] = "halfpi",
    [SH_ROT_DIRECT] = "direct", [SH_ROT_ZH] = "zh",
};

const char *sh_rot_method_name(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS) ? method_names[m] : "?";
}

int sh_rot_method_parse(const char *s, sh_rot_method *out)
{
    for (int m = 0; m < SH_ROT_NMETHODS; m++)
        if (s && !strcmp(s, method_names[m])) {
            if (!methods[m]) return sh_error(SH_ENOTSUP, "method '%s' is not built in", s);
            *out = (sh_rot_method)m;
            return SH_OK;
        }
    return sh_error(SH_EINVAL,
                    "unknown method '%s' (z, ivanic, zxzxz, choi, blanco, wigner, reference, "
                    "halfpi, direct, zh, taylor1, taylor1.5, taylor2)",
                    s ? s : "");
}

sh_rot_method sh_rot_method_default(int order, int one_band)
{
    if (one_band) return SH_ROT_BLANCO;
    return order <= SH_ROT_DEFAULT_ZXZXZ_MAX ? SH_ROT_ZXZXZ : SH_ROT_HALFPI;
}

int sh_rot_method_is_exact(sh_rot_method m)
{
    return m >= 0 && m < SH_ROT_NMETHODS && methods[m] && !methods[m]->approximate;
}

const char *sh_precision_name(sh_precision p) { return p == SH_PREC_FLOAT ? "float" : "double"; }

int sh_precision_parse(const char *s, sh_precision *out)
{
    if (s && !strcmp(s, "double")) *out = SH_PREC_DOUBLE;
    else if (s && !strcmp(s, "float")) *out = SH_PREC_FLOAT;
    else return sh_error(SH_EINVAL, "unknown precision '%s' (float or double)", s ? s : "");
    return SH_OK;
}

int sh_rot_method_max_order(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS && methods[m]) ? methods[m]->max_order : 0;
}

const sh__rot_ops *sh__rot_ops_of(sh_rot_method m)
{
    return (m >= 0 && m < SH_ROT_NMETHODS) ? methods[m] : NULL;
}

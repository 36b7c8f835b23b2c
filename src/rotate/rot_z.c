/* rot_z.c — the `z` method: rotation about the z axis alone, O(n²).
 *
 * A rotation with β = 0 is Rz(α+γ); each band's (m, −m) pair turns by mθ
 * (sh__rot_z_band), with cos(mθ), sin(mθ) from the Chebyshev recurrence
 * (sh__rot_multiple_angles).  Any other rotation is refused.
 */
#include "rotate/rot_internal.h"
#include "rotate/rot_real.h"

SH__ROT_DECLARE_BLOCKS(z);
SH__ROT_DECLARE_APPLY(z);

#include <string.h>

static int z_angle(const sh_rotation *rot, double *theta)
{
    /* sinβ is below rounding for a z rotation built from any input form */
    if (!(rot->beta <= 1e-15))
        return sh_error(SH_EINVAL,
                        "method z: rotation is not about z (beta = %.3g); use another method",
                        rot->beta);
    *theta = rot->alpha + rot->gamma;
    return SH_OK;
}

/* state: cos, sin of mθ, m = 0..order−1 (2·order values) */
int SH_R(sh__rot_z_set)(int order, const sh_rotation *rot, const void *tables, void *state,
                        uint64_t *mults)
{
    double theta = 0;
    int st = z_angle(rot, &theta);
    if (st) return st;
    SH_R(sh__rot_multiple_angles)((sh_real)theta, order - 1, state);
    if (mults && order > 2) *mults += 2u * (uint64_t)(order - 2); /* recurrence, m ≥ 2 */
    return SH_OK;
}

void SH_R(sh__rot_z_apply)(int order, const void *tables, const void *state, const sh_real *in,
                           sh_real *out, void *work, uint64_t *mults)
{
    const sh_real *cs = state;
    if (out != in) memcpy(out, in, (size_t)order * order * sizeof *out);
    for (int l = 1; l < order; l++) SH_R(sh__rot_z_band)(l, cs, out + (size_t)l * l, mults);
}

int SH_R(sh__rot_z_blocks)(int order, const sh_rotation *rot, const void *tables, sh_real *blocks,
                           void *work, uint64_t *mults)
{
    double theta = 0;
    int st = z_angle(rot, &theta);
    if (st) return st;
    sh_real *cs = work;
    SH_R(sh__rot_multiple_angles)((sh_real)theta, order - 1, cs);
    for (int l = 0; l < order; l++) {
        const int w = 2 * l + 1;
        sh_real *B = blocks + sh_rot_block_offset(l);
        memset(B, 0, (size_t)w * w * sizeof *B);
        B[(size_t)l * w + l] = 1;
        for (int m = 1; m <= l; m++) {
            const sh_real c = cs[2 * m], s = cs[2 * m + 1];
            B[(size_t)(l + m) * w + (l + m)] = c;
            B[(size_t)(l + m) * w + (l - m)] = -s;
            B[(size_t)(l - m) * w + (l + m)] = s;
            B[(size_t)(l - m) * w + (l - m)] = c;
        }
    }
    return SH_OK;
}

#ifndef SH_REAL_FLOAT
static size_t z_work(int order) { return 2 * (size_t)(order + 1) * sizeof(double); }
const sh__rot_ops sh__rot_z_ops = {
    .name = "z",
    .max_order = SHLAB_MAX_ORDER,
    .work_bytes = z_work,
    .state_bytes = z_work,
    .set_d = sh__rot_z_set_d,
    .set_f = sh__rot_z_set_f,
    .blocks_d = sh__rot_z_blocks_d,
    .blocks_f = sh__rot_z_blocks_f,
    .apply_d = sh__rot_z_apply_d,
    .apply_f = sh__rot_z_apply_f,
};
#endif

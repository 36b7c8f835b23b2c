/* rotation_generator.c — J = dR_Y/dβ at β = 0, the generator of SH
 * rotations about y, in closed form.  The Taylor rotations (rot_taylor.c)
 * are polynomials in J; the derivatives of R_Y (taylor/rotation_deriv.c) are
 * R_Y(β) J^k.
 *
 * References
 *  [1] A. R. Edmonds, "Angular Momentum in Quantum Mechanics" (1957), 4.1:
 *      d^l_{m'm}(β) = <m'|exp(−iβJ_y)|m>, J_± = J_x ± iJ_y,
 *      J_±|m> = √((l∓m)(l±m+1)) |m±1>.
 *  [2] J. Křivánek, J. Konttinen, S. Pattanaik, K. Bouatouch, "Fast
 *      Approximation to Spherical Harmonic Rotation", IRISA PI 1728 (2005),
 *      Figure 2 (J and J² for l = 1..3).
 *
 * Closed form of J ([1]).  d/dβ d^l(β) at 0 = −i<m'|J_y|m> = −½<m'|J_+ − J_−|m>:
 *   d'_{m+1,m}(0) = −½√((l−m)(l+m+1)),  d'_{m−1,m}(0) = +½√((l+m)(l−m+1)).
 * The real block from d (rot_internal.h, sh__rot_block_from_d: R[m',m] =
 * d_{m'm} ± (−1)^m d_{m',−m} for m, m' > 0, √2 d at row or column 0) is
 * linear in d, so J's real (CS) entries are, with s_m = J[m][m−1]:
 *   m ≥ 2:  s_m = −½√((l−m+1)(l+m))
 *   m = 1:  s_1 = −√(l(l+1)/2)              (the √2 of row/column 0)
 *   m = 0:  s_0 = J[0][−1] = 0                (cos and sin functions never mix)
 *   m ≤ −1: s_m = +½√((l−m+1)(l+m))
 * and J[m−1][m] = −s_m (antisymmetric).  In nocs every entry of J changes sign
 * (each couples m to m ± 1, of the other parity); J² is the same in both.
 */
#include "core/shlab_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sh_rot_deriv_J_subdiag(int l, double *s)
{
    s[0] = 0;
    for (int j = 1; j <= 2 * l; j++) {
        const int m = j - l;
        const double h = 0.5 * sqrt((double)(l - m + 1) * (double)(l + m));
        if (m >= 2) s[j] = -h;
        else if (m == 1) s[j] = -sqrt(0.5 * l * (l + 1.0));
        else if (m == 0) s[j] = 0;
        else s[j] = h;
    }
}

int sh_rot_deriv_J_band(int l, sh_convention conv, double *block)
{
    if (l < 0 || l >= SHLAB_MAX_ORDER) return sh_error(SH_EINVAL, "deriv: band %d out of range", l);
    const int w = 2 * l + 1;
    double *s = malloc((size_t)w * sizeof *s);
    if (!s) return sh_error(SH_ENOMEM, "deriv: out of memory");
    sh_rot_deriv_J_subdiag(l, s);
    memset(block, 0, (size_t)w * w * sizeof *block);
    const double sg = conv == SH_NOCS ? -1.0 : 1.0;
    for (int j = 1; j < w; j++) {
        block[(size_t)j * w + (j - 1)] = sg * s[j] + 0.0; /* no −0 */
        block[(size_t)(j - 1) * w + j] = -sg * s[j] + 0.0;
    }
    free(s);
    return SH_OK;
}


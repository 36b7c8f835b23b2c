/* identify_fixture.c — the inputs `shlab identify` compares with
 * (data/fixtures/basis/README.md): 32 directions, and a light of three
 * directional lights whose projection is exact.  Every direction is an
 * integer vector over its integer length (a Pythagorean quadruple
 * a² + b² + c² = n²), so a user can type it exactly; they were chosen
 * greedily, each the farthest from those before (26.4° apart at least),
 * starting from (2,3,6)/7, among vectors of three distinct non-zero
 * magnitudes with n <= 27. */
#include "shlab.h"

static const int dirs[SH_IDENTIFY_NDIRS][4] = {
    {2, 3, 6, 7},
    {-2, -3, -6, 7},
    {-6, -2, 3, 7},
    {-3, 6, -2, 7},
    {3, -6, 2, 7},
    {6, 2, -3, 7},
    {-8, 1, -4, 9},
    {-4, -8, -1, 9},
    {-1, -4, 8, 9},
    {1, 4, -8, 9},
    {4, 8, 1, 9},
    {8, -1, 4, 9},
    {-12, 9, 8, 17},
    {8, -12, -9, 17},
    {-1, 8, 4, 9},
    {4, -1, -8, 9},
    {-4, 1, 8, 9},
    {8, -4, -1, 9},
    {-6, -3, -2, 7},
    {-3, 2, -6, 7},
    {-2, -6, 3, 7},
    {2, 6, -3, 7},
    {3, -2, 6, 7},
    {6, 3, 2, 7},
    {-23, 14, -2, 27},
    {-2, -23, -14, 27},
    {-2, 6, 9, 11},
    {9, -2, -6, 11},
    {-9, -8, 12, 17},
    {8, 12, 9, 17},
    {9, 8, -12, 17},
    {12, -9, 8, 17},
};

/* Three directional lights (weights 1, 1/2, 1/4) with no signed
 * permutation of the axes mapping the set onto itself. */
static const int lights[SH_IDENTIFY_NLIGHTS][4] = {{2, -3, 6, 7}, {-8, 4, 1, 9}, {9, -2, -6, 11}};
static const double weights[SH_IDENTIFY_NLIGHTS] = {1.0, 0.5, 0.25};

void sh_identify_directions(double *d, int exact[][4])
{
    for (int j = 0; j < SH_IDENTIFY_NDIRS; j++)
        for (int k = 0; k < 4; k++) {
            if (k < 3) d[3 * j + k] = (double)dirs[j][k] / dirs[j][3];
            if (exact) exact[j][k] = dirs[j][k];
        }
}

void sh_identify_light(double *d, double *w, int exact[][4])
{
    for (int j = 0; j < SH_IDENTIFY_NLIGHTS; j++) {
        for (int k = 0; k < 4; k++) {
            if (k < 3) d[3 * j + k] = (double)lights[j][k] / lights[j][3];
            if (exact) exact[j][k] = lights[j][k];
        }
        w[j] = weights[j];
    }
}

/* The light f = Σ_j w_j δ(d_j) projected on shlab's orthonormal basis:
 * c_i = ∫ f y_i dΩ = Σ_j w_j y_i(d_j). */
int sh_identify_light_coeffs(int order, double *c)
{
    int st = sh_check_order(order);
    if (st) return st;
    const int n = order * order;
    double d[3 * SH_IDENTIFY_NLIGHTS], w[SH_IDENTIFY_NLIGHTS];
    sh_identify_light(d, w, NULL);
    for (int i = 0; i < n; i++) c[i] = 0;
    double y[SH_IDENTIFY_MAX_ORDER * SH_IDENTIFY_MAX_ORDER];
    if (order > SH_IDENTIFY_MAX_ORDER)
        return sh_error(SH_EINVAL, "the light's coefficients are kept to order %d, not %d", SH_IDENTIFY_MAX_ORDER, order);
    for (int j = 0; j < SH_IDENTIFY_NLIGHTS; j++) {
        if ((st = sh_eval_dir(order, SH_CS, d + 3 * j, y))) return st;
        for (int i = 0; i < n; i++) c[i] += w[j] * y[i];
    }
    return SH_OK;
}

/* rotate_one.c — rotate an order-3 SH vector with libshlab's rotator and
 * check the result against the basis: rotating f by R must give g(s) = f(Rᵀs).
 * (docs/library.md shows it, and make check builds and runs it.) */
#include <math.h>
#include <stdio.h>
#include <shlab.h>

int main(void)
{
    enum { N = 3, NC = N * N };
    const double c[NC] = {0.9, 0.1, -0.3, 0.25, 0.05, -0.2, 0.4, 0.1, -0.15};
    sh_rotation rot;        /* R = Rz(0.3) Ry(1.1) Rz(-0.7): its matrix and angles */
    sh_rotator_opts o = SH_ROTATOR_OPTS(N);
    sh_rotator *r = NULL;
    double g[NC];
    if (sh_rotation_from_euler(0.3, 1.1, -0.7, &rot) != SH_OK || sh_rotator_create(&o, &r) != SH_OK
        || sh_rotator_apply(r, &rot, 0, 1, c, g) != SH_OK) {
        fprintf(stderr, "rotate_one: %s\n", sh_last_error());
        return 1;
    }
    printf("method %s\n", sh_rot_method_name(sh_rotator_method(r)));
    /* g at s equals f at Rᵀs, at a few directions */
    double worst = 0;
    for (int k = 0; k < 5; k++) {
        const double th = 0.3 + 0.5 * k, ph = 1.7 * k;
        const double s[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
        const double *R = rot.R;
        const double t[3] = {R[0] * s[0] + R[3] * s[1] + R[6] * s[2], R[1] * s[0] + R[4] * s[1] + R[7] * s[2],
                             R[2] * s[0] + R[5] * s[1] + R[8] * s[2]};
        double ys[NC], yt[NC], fg = 0, ff = 0;
        if (sh_eval_dir(N, SH_CS, s, ys) != SH_OK || sh_eval_dir(N, SH_CS, t, yt) != SH_OK) {
            fprintf(stderr, "rotate_one: %s\n", sh_last_error());
            return 1;
        }
        for (int i = 0; i < NC; i++) fg += g[i] * ys[i], ff += c[i] * yt[i];
        worst = fmax(worst, fabs(fg - ff));
    }
    printf("g(s) = f(R^T s) at 5 directions: %s\n", worst < 1e-14 ? "yes" : "NO");
    sh_rotator_free(r);
    return worst < 1e-14 ? 0 : 1;
}

/* testutil.h — tolerance helpers in GSL's style: relative error away from
 * zero, absolute near zero, NaN never passes; every failure names the call. */
#ifndef SHLAB_TESTUTIL_H
#define SHLAB_TESTUTIL_H

#include <check.h>
#include <float.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>

#include "shlab.h"

/* GSL's tolerance ladder in units of DBL_EPSILON */
#define TOL0 (2.0 * DBL_EPSILON)
#define TOL1 (16.0 * DBL_EPSILON)
#define TOL2 (256.0 * DBL_EPSILON)
#define TOL3 (2048.0 * DBL_EPSILON)
#define TOL4 (16384.0 * DBL_EPSILON)
#define TOL5 (131072.0 * DBL_EPSILON)
#define TOL6 (1048576.0 * DBL_EPSILON)

/* |val-exp| <= tol·max(|exp|, floor): relative, absolute below `floor`. */
#define ck_close(val, exp, tol, floor, ...)                                             \
    do {                                                                                \
        const double v_ = (val), e_ = (exp);                                            \
        const double s_ = fabs(e_) > (floor) ? fabs(e_) : (floor);                      \
        if (!(isfinite(v_) && fabs(v_ - e_) <= (tol) * s_)) {                           \
            char m_[256];                                                               \
            snprintf(m_, sizeof m_, __VA_ARGS__);                                       \
            ck_abort_msg("%s: got %.17g expected %.17g (err %.3g, tol %.3g)", m_, v_, e_, \
                         fabs(v_ - e_) / s_, (double)(tol));                            \
        }                                                                               \
    } while (0)

/* Run one suite; the main of every test file. */
#define SHLAB_TEST_MAIN(suite_fn)                                   \
    int main(void)                                                  \
    {                                                               \
        SRunner *sr = srunner_create(suite_fn());                   \
        srunner_run_all(sr, CK_NORMAL);                             \
        int nf = srunner_ntests_failed(sr);                         \
        srunner_free(sr);                                           \
        return nf == 0 ? EXIT_SUCCESS : EXIT_FAILURE;               \
    }

#endif

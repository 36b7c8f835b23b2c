/* test_rotator.c — the front door of rotation (src/rotate/rotator.c).
 *
 *  - shared by threads: one rotator, two threads applying it at once (each
 *    with its own plan, and through the one-shot calls) give results bit for
 *    bit equal to one thread's, for every path the rotator can take (the
 *    unrolled kernels in double and float, a loop kernel, a Taylor method, the
 *    halfpi stream); run under ASan in `make check SANITIZE=1`;
 *  - the one-shot calls agree bit for bit with a plan of the same rotator
 *    (they are that path), and with the legacy sh_rot_plan_create;
 *  - truths: the stream against ivanic's recursion (a second method) at
 *    order 20, R(g)⁻¹R(g) = I through SH_ROTATE_INVERSE, and the MPFR
 *    reference band at order 6;
 *  - `auto` resolves by order, bad arguments are refused once, in one line. */
#include "testutil.h"

#include <pthread.h>
#include <string.h>

#define NROT 24

static void rotations(sh_rotation *rots, int n)
{
    for (int k = 0; k < n; k++)
        sh_rotation_from_euler(0.37 * k - 2.0, 0.131 * k, 1.1 - 0.29 * k, &rots[k]);
}

static void vector(int order, int seed, double *v)
{
    unsigned s = 12345u + (unsigned)seed;
    for (int i = 0; i < order * order; i++) {
        s = s * 1103515245u + 12345u;
        v[i] = ((s >> 8) & 0xffff) / 65536.0 - 0.5;
    }
}

/* What one worker computes with a shared rotator: for each rotation, the
 * plan's result (set by angles), then the one-shot results by angles and by
 * matrix, into out[3·k·n² ...]. */
typedef struct {
    const sh_rotator *r;
    const sh_rotation *rots;
    int order, status;
    double *out;
} job;

static void *work(void *arg)
{
    job *j = arg;
    const int n2 = j->order * j->order;
    double *x = malloc(sizeof(double) * n2);
    sh_rot_plan *p = NULL;
    j->status = sh_rotator_plan(j->r, &p);
    for (int k = 0; k < NROT && !j->status; k++) {
        vector(j->order, k, x);
        double *o = j->out + (size_t)3 * k * n2;
        j->status = sh_rot_plan_set(p, &j->rots[k]);
        if (!j->status) j->status = sh_rot_plan_apply(p, x, o);
        if (!j->status) j->status = sh_rotator_apply(j->r, &j->rots[k], 0, 1, x, o + n2);
        if (!j->status) j->status = sh_rotator_apply_matrix(j->r, j->rots[k].R, 0, 1, x, o + 2 * n2);
    }
    sh_rot_plan_free(p);
    free(x);
    return NULL;
}

static const struct {
    int order;
    sh_rot_method method;
    sh_precision prec;
    int stream;
} PATHS[] = {
    {6, SH_ROT_AUTO, SH_PREC_DOUBLE, 0},    /* zxzxz, unrolled */
    {6, SH_ROT_ZXZXZ, SH_PREC_FLOAT, 0},    /* unrolled, float arithmetic */
    {5, SH_ROT_IVANIC, SH_PREC_DOUBLE, 0},  /* unrolled ivanic (reads R) */
    {9, SH_ROT_BLANCO, SH_PREC_DOUBLE, 0},  /* loop kernel, blocks */
    {8, SH_ROT_TAYLOR15, SH_PREC_DOUBLE, 0},/* Taylor, unrolled */
    {40, SH_ROT_AUTO, SH_PREC_DOUBLE, 1},   /* halfpi, the stream */
};
#define NPATHS ((int)(sizeof PATHS / sizeof PATHS[0]))

/* Two threads at once equal one thread, bit for bit. */
START_TEST(shared_by_threads)
{
    sh_rotation rots[NROT];
    rotations(rots, NROT);
    const int i = _i;
    sh_rotator_opts o = {.order = PATHS[i].order, .method = PATHS[i].method, .prec = PATHS[i].prec,
                         .threads = 2};
    sh_rotator *r;
    ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
    ck_assert_int_eq(sh_rotator_streams(r), PATHS[i].stream);
    const int n2 = o.order * o.order;
    const size_t nout = (size_t)3 * NROT * n2;
    double *one = calloc(nout, sizeof *one), *two[2] = {calloc(nout, sizeof(double)), calloc(nout, sizeof(double))};
    job j1 = {r, rots, o.order, 0, one};
    work(&j1);
    ck_assert_int_eq(j1.status, SH_OK);
    pthread_t t[2];
    job jt[2] = {{r, rots, o.order, 0, two[0]}, {r, rots, o.order, 0, two[1]}};
    for (int k = 0; k < 2; k++) ck_assert_int_eq(pthread_create(&t[k], NULL, work, &jt[k]), 0);
    for (int k = 0; k < 2; k++) pthread_join(t[k], NULL);
    for (int k = 0; k < 2; k++) {
        ck_assert_int_eq(jt[k].status, SH_OK);
        ck_assert_msg(!memcmp(one, two[k], nout * sizeof *one), "%s order %d: thread %d differs from one thread",
                      sh_rot_method_name(sh_rotator_method(r)), o.order, k);
    }
    /* the one-shot call by angles is the plan's path: the same bits */
    for (int k = 0; k < NROT; k++)
        ck_assert_msg(!memcmp(one + (size_t)3 * k * n2, one + (size_t)(3 * k + 1) * n2, n2 * sizeof *one),
                      "%s order %d rotation %d: one-shot differs from the plan", sh_rot_method_name(sh_rotator_method(r)),
                      o.order, k);
    /* by matrix: the same rotation, computed by algebra (zxzxz, Taylor) —
     * equal to rounding */
    double worst = 0;
    for (size_t q = 0; q < (size_t)NROT * n2; q++) {
        const size_t k = q / n2, c = q % n2;
        worst = fmax(worst, fabs(one[(3 * k + 2) * n2 + c] - one[3 * k * n2 + c]));
    }
    ck_assert_msg(worst <= (PATHS[i].prec == SH_PREC_FLOAT ? 2e-5 : 1e-12), "%s: matrix vs angles %.3g",
                  sh_rot_method_name(sh_rotator_method(r)), worst);
    printf("test_rotator: %s %s order %d (%s): 2 threads bit-identical to 1; matrix vs angles %.2g\n",
           sh_rot_method_name(sh_rotator_method(r)), sh_precision_name(PATHS[i].prec), o.order,
           PATHS[i].stream ? "stream" : sh_rot_kernel_name(sh_rotator_kernel(r)), worst);
    free(one), free(two[0]), free(two[1]);
    sh_rotator_free(r);
}
END_TEST

/* The legacy door gives the same bits as a rotator's plan. */
START_TEST(legacy_same_bits)
{
    sh_rotation rot;
    sh_rotation_from_euler(0.4, 1.2, -2.2, &rot);
    const sh_rot_method ms[] = {SH_ROT_ZXZXZ, SH_ROT_IVANIC, SH_ROT_CHOI, SH_ROT_BLANCO, SH_ROT_TAYLOR2, SH_ROT_HALFPI};
    for (size_t m = 0; m < sizeof ms / sizeof *ms; m++) {
        const int order = 7, n2 = order * order;
        double x[49], a[49], b[49];
        vector(order, (int)m, x);
        sh_rot_plan *p;
        ck_assert_int_eq(sh_rot_plan_create(order, ms[m], SH_PREC_DOUBLE, SH_NOCS, &p), SH_OK);
        ck_assert_int_eq(sh_rot_plan_set(p, &rot), SH_OK);
        ck_assert_int_eq(sh_rot_plan_apply(p, x, a), SH_OK);
        sh_rot_plan_free(p);
        sh_rotator_opts o = {.order = order, .method = ms[m], .conv = SH_NOCS, .threads = 1};
        sh_rotator *r;
        ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
        ck_assert_int_eq(sh_rotator_apply(r, &rot, 0, 1, x, b), SH_OK);
        sh_rotator_free(r);
        if (ms[m] == SH_ROT_HALFPI) { /* stream vs one-thread plan: the same kernel, batches differ */
            for (int i = 0; i < n2; i++) ck_close(b[i], a[i], 1e-13, 1.0, "halfpi stream vs plan [%d]", i);
        } else {
            ck_assert_msg(!memcmp(a, b, sizeof a), "%s: rotator and legacy plan differ", sh_rot_method_name(ms[m]));
        }
    }
}
END_TEST

/* Truths: the stream against a second method, the inverse, the MPFR band. */
START_TEST(truths)
{
    sh_rotation rot;
    sh_rotation_from_euler(2.1, 0.7, -0.4, &rot);
    const int order = 20, n2 = order * order;
    double *x = malloc(sizeof(double) * n2), *y = malloc(sizeof(double) * n2), *z = malloc(sizeof(double) * n2);
    vector(order, 7, x);
    sh_rotator_opts os = {.order = order, .method = SH_ROT_HALFPI, .threads = 2};
    sh_rotator_opts oi = {.order = order, .method = SH_ROT_IVANIC};
    sh_rotator *rs, *ri;
    ck_assert_int_eq(sh_rotator_create(&os, &rs), SH_OK);
    ck_assert_int_eq(sh_rotator_create(&oi, &ri), SH_OK);
    ck_assert_int_eq(sh_rotator_apply(rs, &rot, 0, 1, x, y), SH_OK);
    ck_assert_int_eq(sh_rotator_apply(ri, &rot, 0, 1, x, z), SH_OK);
    for (int i = 0; i < n2; i++) ck_close(y[i], z[i], 1e-13, 1.0, "stream vs ivanic, order 20 [%d]", i);
    /* R⁻¹(R x) = x, in place */
    ck_assert_int_eq(sh_rotator_apply(rs, &rot, SH_ROTATE_INVERSE, 1, y, y), SH_OK);
    for (int i = 0; i < n2; i++) ck_close(y[i], x[i], 1e-13, 1.0, "stream inverse round trip [%d]", i);
    ck_assert_int_eq(sh_rotator_apply_matrix(ri, rot.R, 0, 1, x, z), SH_OK);
    ck_assert_int_eq(sh_rotator_apply_matrix(ri, rot.R, SH_ROTATE_INVERSE, 1, z, z), SH_OK);
    for (int i = 0; i < n2; i++) ck_close(z[i], x[i], 1e-12, 1.0, "ivanic matrix inverse round trip [%d]", i);
    sh_rotator_free(rs);
    sh_rotator_free(ri);
    /* band 5 of an order-6 zxzxz rotator against the MPFR reference */
    double ref[121], e[36], col[36];
    ck_assert_int_eq(sh_rot_reference_band(5, SH_CS, &rot, 30, ref, NULL), SH_OK);
    sh_rotator_opts oz = SH_ROTATOR_OPTS(6);
    sh_rotator *rz;
    ck_assert_int_eq(sh_rotator_create(&oz, &rz), SH_OK);
    for (int j = 0; j < 11; j++) {
        memset(e, 0, sizeof e);
        e[25 + j] = 1;
        ck_assert_int_eq(sh_rotator_apply(rz, &rot, 0, 1, e, col), SH_OK);
        for (int i = 0; i < 11; i++) ck_close(col[25 + i], ref[i * 11 + j], 4e-15, 1.0, "band 5 [%d][%d]", i, j);
    }
    sh_rotator_free(rz);
    free(x), free(y), free(z);
}
END_TEST

START_TEST(choices_and_errors)
{
    sh_rotator *r;
    sh_rotator_opts o = SH_ROTATOR_OPTS(SH_ROT_DEFAULT_ZXZXZ_MAX);
    ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
    ck_assert_int_eq(sh_rotator_method(r), SH_ROT_ZXZXZ);
    ck_assert_int_eq(sh_rotator_streams(r), 0);
    sh_rotator_free(r);
    o.order = SH_ROT_DEFAULT_ZXZXZ_MAX + 1;
    ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
    ck_assert_int_eq(sh_rotator_method(r), SH_ROT_HALFPI);
    ck_assert_int_eq(sh_rotator_streams(r), 1);
    sh_rotator_free(r);
    o.prec = SH_PREC_FLOAT; /* halfpi in float: a plan, not the stream */
    ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
    ck_assert_int_eq(sh_rotator_streams(r), 0);
    sh_rotator_free(r);
    sh_rotator_opts bad[] = {
        {.order = 0},
        {.order = SHLAB_MAX_ORDER + 1},
        {.order = 12, .method = SH_ROT_WIGNER + 100},
        {.order = 4, .kernel = SH_KERNEL_N},
        {.order = 4, .conv = (sh_convention)7},
        {.order = 4, .threads = -1},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        r = (sh_rotator *)1;
        ck_assert_int_ne(sh_rotator_create(&bad[k], &r), SH_OK);
        ck_assert_ptr_null(r);
        ck_assert_ptr_null(strchr(sh_last_error(), '\n'));
    }
    /* a float call on a double rotator, no rotation */
    o = SH_ROTATOR_OPTS(4);
    ck_assert_int_eq(sh_rotator_create(&o, &r), SH_OK);
    float R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, v[16] = {0};
    ck_assert_int_eq(sh_rotator_apply_matrix_f(r, R, v, v), SH_EINVAL);
    double d[16] = {0}, Rn[9] = {NAN, 0, 0, 0, 1, 0, 0, 0, 1};
    ck_assert_int_eq(sh_rotator_apply_matrix(r, Rn, 0, 1, d, d), SH_EINVAL);
    ck_assert_int_eq(sh_rotator_apply(r, NULL, 0, 1, d, d), SH_EINVAL);
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    ck_assert_int_eq(sh_rotator_apply_matrix(r, I, 4, 1, d, d), SH_EINVAL); /* unknown flag */
    sh_rotator_free(r);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("rotator");
    TCase *tc = tcase_create("rotator");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, shared_by_threads, 0, NPATHS);
    tcase_add_test(tc, legacy_same_bits);
    tcase_add_test(tc, truths);
    tcase_add_test(tc, choices_and_errors);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)

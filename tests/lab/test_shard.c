/* test_shard.c — the assignment of sweep items to shards (sh_shard_*).
 *
 * Truths: the shards of a sweep partition its items (each item exactly one
 * owner, for every N); shard 0/1 owns everything; the serpentine deal is
 * checked against its definition written out as a sequence; the shares of a
 * sweep whose item costs grow like j² or j³ differ by less than a few
 * items' worth; parse accepts exactly "I/N" with 0 <= I < N. */
#include "testutil.h"

#include "lab/lab.h"

START_TEST(test_partition)
{
    for (int N = 1; N <= 9; N++) {
        for (long j = 0; j < 1000; j++) {
            int owners = 0;
            for (int i = 0; i < N; i++) {
                const sh_shard s = {i, N};
                owners += sh_shard_owns(&s, j) != 0;
            }
            ck_assert_int_eq(owners, 1);
        }
    }
    const sh_shard all = SH_SHARD_ALL;
    for (long j = 0; j < 100; j++) ck_assert(sh_shard_owns(&all, j) && sh_shard_owns(NULL, j));
}
END_TEST

START_TEST(test_serpentine)
{
    /* N = 3: 0 1 2 2 1 0 0 1 2 2 1 0 ... */
    static const int want[12] = {0, 1, 2, 2, 1, 0, 0, 1, 2, 2, 1, 0};
    for (long j = 0; j < 12; j++) {
        const sh_shard s = {want[j], 3};
        ck_assert_msg(sh_shard_owns(&s, j), "item %ld should go to shard %d", j, want[j]);
    }
    const sh_shard s = {0, 2};
    ck_assert(!sh_shard_owns(&s, -1));
}
END_TEST

/* Items of cost (j+1)^p, p = 2, 3: the largest share exceeds the smallest
 * by less than twice the dearest item (plain j mod N gives the last shard
 * one dear item more per round: n/N items' worth). */
START_TEST(test_balance)
{
    const int p = 2 + _i;
    for (int N = 2; N <= 8; N *= 2) {
        const long n = 1001;
        double share[8] = {0}, top = 0;
        for (long j = 0; j < n; j++) {
            const double c = p == 2 ? (double)(j + 1) * (j + 1) : (double)(j + 1) * (j + 1) * (j + 1);
            top = c;
            for (int i = 0; i < N; i++) {
                const sh_shard s = {i, N};
                if (sh_shard_owns(&s, j)) share[i] += c;
            }
        }
        double lo = share[0], hi = share[0];
        for (int i = 1; i < N; i++) {
            if (share[i] < lo) lo = share[i];
            if (share[i] > hi) hi = share[i];
        }
        ck_assert_msg(hi - lo < 2 * top, "N %d p %d: shares %g .. %g, dearest item %g", N, p, lo, hi, top);
    }
}
END_TEST

START_TEST(test_parse)
{
    sh_shard s;
    ck_assert_int_eq(sh_shard_parse("0/1", &s), SH_OK);
    ck_assert(s.index == 0 && s.count == 1);
    ck_assert_int_eq(sh_shard_parse("6/7", &s), SH_OK);
    ck_assert(s.index == 6 && s.count == 7);
    static const char *const bad[] = {"", "1", "/2", "1/", "2/2", "-1/2", "+1/2", "1/0", " 1/2", "1/2 ",
                                      "1/2/3", "a/2", "1.0/2", "0/100001", "99999999999999999999/2"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        ck_assert_msg(sh_shard_parse(bad[k], &s) == SH_EINVAL, "'%s' accepted", bad[k]);
        ck_assert_str_ne(sh_last_error(), "");
    }
    ck_assert_int_eq(sh_shard_parse(NULL, &s), SH_EINVAL);
}
END_TEST

static Suite *shard_suite(void)
{
    Suite *s = suite_create("shard");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_partition);
    tcase_add_test(tc, test_serpentine);
    tcase_add_loop_test(tc, test_balance, 0, 2);
    tcase_add_test(tc, test_parse);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(shard_suite)

/* test_signal_cleanup.c — the CLI's signal handlers (cli_signals_install,
 * src/cli/cli_output.c) remove every temporary output, even when two signals
 * arrive back to back in a process with several threads.
 *
 * Regression: the handlers were installed with SA_RESETHAND, so the first
 * signal restored the default action on entry; a second one (what `timeout`
 * sends: one to the child, one to its group) was then delivered to another
 * thread, where it was not blocked, and killed the process before the first
 * handler had removed the files (`render` left OUT.tmp.* in 9 of 9 runs).
 * To make that window wide enough to hit every time, the child here holds
 * 60 temporaries (the handler unlinks them one by one, a few hundred µs)
 * and two spinning threads besides the main one; the parent sends the pair
 * with two kill(2) calls 0 to 300 µs apart (two identical signals sent
 * before the first is delivered merge into one, so the second must come
 * while the first handler runs).  Truth: the folder's listing afterwards. */
#include "testutil.h"

#include "cli/cli.h"
#include "core/shlab_internal.h"

#include <dirent.h>
#include <pthread.h>
#include <signal.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define NFILES 60

static void *spin(void *arg)
{
    volatile unsigned long *x = arg;
    for (;;) (*x)++;
    return NULL;
}

static int count_temps(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (strstr(e->d_name, ".tmp.")) n++;
    if (d) closedir(d);
    return n;
}

/* The child: handlers, NFILES temporaries, two spinning threads, then "ready". */
static void child(const char *dir, int ready_fd)
{
    cli_signals_install();
    for (int k = 0; k < NFILES; k++) {
        char path[512], *tmp;
        snprintf(path, sizeof path, "%s/out%02d.exr", dir, k);
        if (sh__make_temp_path(path, &tmp)) _exit(3);
    }
    static volatile unsigned long c1, c2;
    pthread_t t1, t2;
    pthread_create(&t1, NULL, spin, (void *)&c1);
    pthread_create(&t2, NULL, spin, (void *)&c2);
    if (write(ready_fd, "r", 1) != 1) _exit(4);
    for (volatile unsigned long i = 0;; i++) {
    }
}

START_TEST(two_signals_in_a_row)
{
    static const int pairs[][2] = {{SIGTERM, SIGTERM}, {SIGINT, SIGTERM}, {SIGHUP, SIGTERM},
                                   {SIGINT, SIGINT},   {SIGTERM, 0},       {SIGTERM, SIGINT}};
    const int npairs = (int)(sizeof pairs / sizeof pairs[0]), rounds = 144;
    char dir[] = "/tmp/shlab_sigtest_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    int left_total = 0, bad_runs = 0;
    for (int r = 0; r < rounds; r++) {
        const int *p = pairs[r % npairs];
        int fds[2];
        ck_assert_int_eq(pipe(fds), 0);
        const pid_t pid = fork();
        ck_assert_int_ge(pid, 0);
        if (pid == 0) {
            close(fds[0]);
            child(dir, fds[1]);
        }
        close(fds[1]);
        char c;
        ck_assert_int_eq(read(fds[0], &c, 1), 1);
        close(fds[0]);
        usleep(2000 + 500 * (r % 7)); /* let the threads run */
        static const int gap_us[] = {0, 20, 60, 120, 200, 300};
        kill(pid, p[0]);
        if (p[1]) {
            if (gap_us[(r / npairs) % 6]) usleep(gap_us[(r / npairs) % 6]);
            kill(pid, p[1]);
        }
        int status;
        ck_assert_int_eq(waitpid(pid, &status, 0), pid);
        ck_assert_msg(WIFSIGNALED(status), "round %d: the child was not killed by a signal (status %d)", r, status);
        const int left = count_temps(dir);
        if (left) {
            bad_runs++;
            left_total += left;
            /* clean up for the next round */
            DIR *d = opendir(dir);
            for (struct dirent *e; d && (e = readdir(d));)
                if (strstr(e->d_name, ".tmp.")) {
                    char f[600];
                    snprintf(f, sizeof f, "%s/%s", dir, e->d_name);
                    unlink(f);
                }
            if (d) closedir(d);
        }
    }
    rmdir(dir);
    printf("test_signal_cleanup: %d rounds of one or two signals, %d with temporaries left (%d files)\n", rounds,
           bad_runs, left_total);
    ck_assert_msg(bad_runs == 0, "%d of %d rounds left %d temporary files", bad_runs, rounds, left_total);
}
END_TEST

/* abort() in a library (assimp's ai_assert, a failed glibc check) raises
 * SIGABRT: the temporaries go too, and the process still dies by SIGABRT. */
START_TEST(abort_removes_temporaries)
{
    char dir[] = "/tmp/shlab_sigtest_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    const pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        cli_signals_install();
        for (int k = 0; k < 5; k++) {
            char path[512], *tmp;
            snprintf(path, sizeof path, "%s/out%d.png", dir, k);
            if (sh__make_temp_path(path, &tmp)) _exit(3);
        }
        abort();
    }
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT, "status %d", status);
    const int left = count_temps(dir);
    rmdir(dir);
    ck_assert_msg(left == 0, "%d temporary files left after abort()", left);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("signal_cleanup");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, two_signals_in_a_row);
    tcase_add_test(tc, abort_removes_temporaries);
    suite_add_tcase(s, tc);
    return s;
}

SHLAB_TEST_MAIN(suite)

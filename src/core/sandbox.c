/* sandbox.c — untrusted code in a child process with limits (sandbox.h).
 *
 * An importer can abort (assimp's ai_assert), a user's kernel can crash,
 * loop forever or allocate without bound; none of that may take the calling
 * process down.  So the job runs in a child made by fork(2):
 *
 *  - before the fork every signal is blocked, so that no handler of the
 *    parent (the CLI's, which removes its temporary files) runs in the child;
 *    the child resets every signal to its default action, unblocks them, asks
 *    to be killed when its parent dies (Linux: PR_SET_PDEATHSIG), reads
 *    /dev/null as stdin, writes stdout to /dev/null and stderr to a pipe the
 *    parent reads (the first line names an assertion or a sanitizer report),
 *    and leaves by _exit(2): no atexit handler, no stdio flush of the
 *    parent's buffers, and so no LeakSanitizer report of what the job
 *    leaked;
 *  - limits (setrlimit): RLIMIT_CPU (soft at the budget, hard one second
 *    later: SIGXCPU then SIGKILL), RLIMIT_CORE 0 (an abort dumps nothing),
 *    RLIMIT_FSIZE 0 (it writes no file), and RLIMIT_AS at its address space
 *    at the fork plus the memory budget: an allocation beyond it fails.
 *    Under AddressSanitizer an address-space limit cannot be used: the
 *    shadow memory and allocator regions take terabytes of it (reserved at
 *    start-up), and even a limit relative to them fails badly — the
 *    allocator's out-of-memory report itself needs memory, fails, and the
 *    process hangs in the sanitizer's CHECK handler until killed.  There the
 *    child counts instead: a malloc hook
 *    (__sanitizer_install_malloc_and_free_hooks) reads the allocator's live
 *    bytes (__sanitizer_get_current_allocated_bytes) after every allocation
 *    and leaves with SH_SANDBOX_CHILD_OVER_MEMORY once they pass the budget
 *    (an allocation is only reserved address space until touched, so one
 *    huge request costs nothing before the hook sees it);
 *  - the parent polls both pipes until the wall-clock limit, hands the
 *    answer to the job's feed as it arrives, and kills the child (SIGKILL)
 *    at the limit or when the feed refuses the answer; it always reaps the
 *    child;
 *  - while it waits the parent also reads the child's resident memory
 *    (/proc/PID/statm) every 10 ms and kills it once it has grown by more
 *    than the budget over the parent's own at the fork (their pages are
 *    shared until written): the limit on real memory, which under
 *    AddressSanitizer also catches what the malloc hook cannot — one huge
 *    allocation, whose shadow the sanitizer fills (an eighth of its size)
 *    before the hook is called.
 *
 * The child is a copy of a process that may run threads (OpenMP, Embree):
 * only the forking thread exists in it.  glibc's malloc is safe after fork;
 * a job's child does nothing but its work and writing its pipe. */
#define _GNU_SOURCE
#include "core/sandbox.h"
#include "core/shlab_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#ifndef NSIG
#define NSIG 65
#endif

#ifdef SH_SANDBOX_ASAN
/* AddressSanitizer's allocator interface (sanitizer/allocator_interface.h,
 * which gcc does not install; libasan exports the functions) */
size_t __sanitizer_get_current_allocated_bytes(void);
int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void *, size_t),
                                              void (*free_hook)(const volatile void *));
static size_t asan_limit;
static void asan_free_hook(const volatile void *p) {} /* the interface takes both hooks or none */
static void asan_malloc_hook(const volatile void *p, size_t size)
{
    if (__sanitizer_get_current_allocated_bytes() > asan_limit) {
        static const char msg[] = "over the memory limit (AddressSanitizer's count of live bytes)\n";
        if (write(2, msg, sizeof msg - 1) < 0) {}
        _exit(SH_SANDBOX_CHILD_OVER_MEMORY);
    }
}
#endif

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Field k (0: size, 1: resident) of /proc/PID/statm in bytes (pid 0: this
 * process), or -1. */
static long long statm(pid_t pid, int k)
{
    char path[64], buf[128];
    if (pid) snprintf(path, sizeof path, "/proc/%d/statm", (int)pid);
    else snprintf(path, sizeof path, "/proc/self/statm");
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    const ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return -1;
    buf[n] = '\0';
    char *p = buf;
    for (int i = 0; i < k; i++) strtoll(p, &p, 10);
    return strtoll(p, NULL, 10) * (long long)sysconf(_SC_PAGESIZE);
}

/* setrlimit, failure ignored (a limit the system refuses is not ours to raise). */
static void set_limit(int which, rlim_t soft, rlim_t hard)
{
    struct rlimit rl = {soft, hard};
    setrlimit(which, &rl);
}

/* The child: never returns. */
static void child(const sh_sandbox_job *job, int wfd, int efd, int devnull, pid_t parent)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_DFL;
    for (int s = 1; s < NSIG; s++) sigaction(s, &sa, NULL); /* SIGKILL, SIGSTOP: refused, harmless */
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(SH_SANDBOX_CHILD_ORPHAN); /* the parent died before the request */
#endif
    if (devnull >= 0) {
        dup2(devnull, 0);
        dup2(devnull, 1);
    } else {
        close(0);
        close(1);
    }
    dup2(efd, 2);
    set_limit(RLIMIT_CORE, 0, 0);
    set_limit(RLIMIT_FSIZE, 0, 0);
    const rlim_t cpu = (rlim_t)ceil(job->cpu_seconds > 0 ? job->cpu_seconds : 1);
    set_limit(RLIMIT_CPU, cpu, cpu + 1);
    if (job->mem_bytes > 0) {
#ifdef SH_SANDBOX_ASAN
        asan_limit = __sanitizer_get_current_allocated_bytes() + (size_t)job->mem_bytes;
        __sanitizer_install_malloc_and_free_hooks(asan_malloc_hook, asan_free_hook);
#else
        const long long vm = statm(0, 0);
        if (vm > 0) set_limit(RLIMIT_AS, (rlim_t)(vm + job->mem_bytes), (rlim_t)(vm + job->mem_bytes));
#endif
    }
    _exit(job->child(job->arg, wfd));
}

/* Reap the child (its wait status and resource use); past the deadline
 * kill it first.  1 if the deadline killed it, else 0. */
static int reap(pid_t pid, double deadline, int *status, struct rusage *ru)
{
    double nap = 50e-6;
    memset(ru, 0, sizeof *ru);
    *status = 0;
    for (;;) {
        const pid_t r = wait4(pid, status, WNOHANG, ru);
        if (r == pid) return 0;
        if (r < 0 && errno != EINTR) {
            *status = -1;
            return 0;
        }
        if (now_s() > deadline) {
            kill(pid, SIGKILL);
            while (wait4(pid, status, 0, ru) < 0 && errno == EINTR) {}
            return 1;
        }
        struct timespec ts = {0, (long)(nap * 1e9)};
        nanosleep(&ts, NULL);
        if (nap < 5e-3) nap *= 2;
    }
}

/* The first line of what the child wrote to stderr, without a sanitizer's
 * "==PID==" prefix, into out ("" if none). */
static void first_line(char *err, size_t n, char *out, size_t cap)
{
    err[n] = '\0';
    char *s = err;
    while (*s == '\n' || *s == ' ') s++;
    if (s[0] == '=' && s[1] == '=') {
        char *e = strstr(s + 2, "==");
        if (e) s = e + 2;
    }
    char *nl = strchr(s, '\n');
    if (nl) *nl = '\0';
    if (strlen(s) > 200) strcpy(s + 197, "...");
    snprintf(out, cap, "%.200s", s);
}

/* Mark fd close-on-exec (a program another thread starts must not hold the pipes open). */
static int set_cloexec(int fd) { return fcntl(fd, F_SETFD, FD_CLOEXEC); }

/* The answer pipe and the stderr pipe, close-on-exec. */
static int open_pipes(const sh_sandbox_job *job, int res[2], int err[2])
{
    if (pipe(res) || pipe(err)) {
        const int e = errno;
        if (res[0] >= 0) close(res[0]), close(res[1]);
        return sh_error(SH_EIO, "cannot start %s: pipe: %s", job->what, strerror(e));
    }
    for (int k = 0; k < 2; k++) set_cloexec(res[k]), set_cloexec(err[k]);
    return SH_OK;
}

/* Fork the child with every signal blocked (see the top of this file); in
 * the parent keep the pipes' read ends.  *rss0: the parent's resident
 * memory at the fork (−1 without a memory budget), *t0: the time. */
static int start_child(const sh_sandbox_job *job, int res[2], int err[2], pid_t *pid, long long *rss0, double *t0)
{
    const int devnull = open("/dev/null", O_RDWR | O_CLOEXEC);
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    const pid_t parent = getpid();
    *rss0 = job->mem_bytes > 0 ? statm(0, 1) : -1;
    *t0 = now_s();
    *pid = fork();
    if (*pid == 0) child(job, res[1], err[1], devnull, parent);
    const int fork_errno = errno;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    close(res[1]);
    close(err[1]);
    if (devnull >= 0) close(devnull);
    if (*pid < 0) {
        close(res[0]);
        close(err[0]);
        return sh_error(SH_EIO, "cannot start %s: fork: %s", job->what, strerror(fork_errno));
    }
    return SH_OK;
}

/* What the parent saw of the running child. */
typedef struct {
    char errbuf[1024]; /* the start of what it wrote to stderr */
    size_t errlen;
    int fds[2];        /* answer and stderr pipes, −1 once closed */
    int bad, over;     /* the feed refused the answer; it outgrew its memory */
} child_watch;

/* Poll both pipes until both are closed, the deadline, a refused answer or
 * the child's resident memory more than its budget above rss0 (read every
 * 10 ms). */
static void watch_child(const sh_sandbox_job *job, pid_t pid, long long rss0, double deadline, child_watch *w)
{
    unsigned char chunk[1 << 16];
    while ((w->fds[0] >= 0 || w->fds[1] >= 0) && !w->bad && !w->over) {
        const double left = deadline - now_s();
        if (left <= 0) break;
        struct pollfd pf[2] = {{w->fds[0], POLLIN, 0}, {w->fds[1], POLLIN, 0}};
        const int k = poll(pf, 2, rss0 >= 0 && left > 0.01 ? 10 : (int)ceil(left * 1000));
        if (rss0 >= 0) {
            const long long r = statm(pid, 1);
            w->over = r > 0 && r - rss0 > job->mem_bytes;
        }
        if (k < 0 && errno == EINTR) continue;
        if (k < 0) break;
        for (int i = 0; i < 2; i++) {
            if (w->fds[i] < 0 || !(pf[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t r = read(w->fds[i], chunk, sizeof chunk);
            if (r < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (r <= 0) {
                close(w->fds[i]);
                w->fds[i] = -1;
            } else if (i == 0) {
                w->bad = job->feed(job->fctx, chunk, (size_t)r) != 0;
            } else {
                const size_t take = w->errlen + (size_t)r < sizeof w->errbuf - 1 ? (size_t)r
                                                                                  : sizeof w->errbuf - 1 - w->errlen;
                memcpy(w->errbuf + w->errlen, chunk, take);
                w->errlen += take;
            }
        }
    }
}

/* The outcome from what was watched and the child's wait status (−1 if it
 * could not be reaped) and resource use: the first cause that explains it. */
static void outcome(const sh_sandbox_job *job, child_watch *w, int unfinished, int late, int status,
                    const struct rusage *ru, sh_sandbox_result *res)
{
    res->cpu_seconds = (double)ru->ru_utime.tv_sec + 1e-6 * (double)ru->ru_utime.tv_usec +
                       (double)ru->ru_stime.tv_sec + 1e-6 * (double)ru->ru_stime.tv_usec;
    res->cpu_limit = ceil(job->cpu_seconds > 0 ? job->cpu_seconds : 1);
    first_line(w->errbuf, w->errlen, res->first_line, sizeof res->first_line);
    res->exit_status = status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (w->over || res->exit_status == SH_SANDBOX_CHILD_OVER_MEMORY) res->outcome = SH_SANDBOX_MEMORY;
    else if (unfinished || late) res->outcome = SH_SANDBOX_WALL;
    else if (w->bad) res->outcome = SH_SANDBOX_BROKEN;
    else if (status >= 0 && WIFSIGNALED(status)) {
        res->signal = WTERMSIG(status);
        const int cpu_kill = res->signal == SIGXCPU || (res->signal == SIGKILL && res->cpu_seconds >= res->cpu_limit - 0.05);
        res->outcome = cpu_kill ? SH_SANDBOX_CPU : SH_SANDBOX_SIGNAL;
    } else res->outcome = SH_SANDBOX_DONE;
}

int sh__sandbox_run(const sh_sandbox_job *job, sh_sandbox_result *res)
{
    memset(res, 0, sizeof *res);
    int ans[2] = {-1, -1}, err[2] = {-1, -1};
    int st = open_pipes(job, ans, err);
    if (st) return st;
    pid_t pid;
    long long rss0;
    double t0;
    if ((st = start_child(job, ans, err, &pid, &rss0, &t0))) return st;
    const double deadline = t0 + (job->wall_seconds > 0 ? job->wall_seconds : 1);
    child_watch w = {.errlen = 0, .fds = {ans[0], err[0]}, .bad = 0, .over = 0};
    watch_child(job, pid, rss0, deadline, &w);
    const int unfinished = w.fds[0] >= 0 && !w.bad && !w.over; /* the deadline came first */
    if (w.bad || unfinished || w.over) kill(pid, SIGKILL);
    for (int i = 0; i < 2; i++)
        if (w.fds[i] >= 0) close(w.fds[i]);
    int status;
    struct rusage ru;
    const int late = reap(pid, deadline, &status, &ru);
    outcome(job, &w, unfinished, late, status, &ru, res);
    return SH_OK;
}

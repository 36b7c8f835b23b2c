/* sandbox.h — running untrusted code (a mesh importer, a user's kernel) in a
 * child process with limits, so that a crash, a hang or a runaway
 * allocation never takes the calling process down (sandbox.c). */
#ifndef SHLAB_SANDBOX_H
#define SHLAB_SANDBOX_H

#include <stddef.h>

/* Built with AddressSanitizer (gcc's or clang's): the sandbox limits memory
 * another way there, and budgets allow for the sanitizer's own use. */
#if defined(__SANITIZE_ADDRESS__)
#define SH_SANDBOX_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SH_SANDBOX_ASAN 1
#endif
#endif

/* The child's exit statuses the sandbox itself uses (a job's child function
 * returns its own, from 8 up). */
enum { SH_SANDBOX_CHILD_ORPHAN = 3, SH_SANDBOX_CHILD_OVER_MEMORY = 5, SH_SANDBOX_CHILD_FIRST_FREE = 8 };

/* One job.  child(arg, fd) runs in the child, writes its answer to fd and
 * returns the child's exit status.  feed(fctx, bytes, n) runs in the parent
 * for each chunk of the answer as it arrives; non-zero: the answer broke its
 * protocol (the child is killed).  Limits: CPU seconds (RLIMIT_CPU, soft;
 * hard one second later), bytes the child may add to its memory (0: no
 * limit; RLIMIT_AS, or under AddressSanitizer a count of live bytes, and
 * always its resident memory read every 10 ms), wall seconds (then
 * SIGKILL).  what: "the importer" in messages. */
typedef struct {
    int (*child)(void *arg, int fd);
    int (*feed)(void *fctx, const unsigned char *bytes, size_t n);
    void *arg, *fctx;
    double cpu_seconds, wall_seconds;
    long long mem_bytes;
    const char *what;
} sh_sandbox_job;

typedef enum {
    SH_SANDBOX_DONE,    /* exited (status in exit_status) with a whole answer fed */
    SH_SANDBOX_SIGNAL,  /* killed by signal `signal` (not ours) */
    SH_SANDBOX_CPU,     /* over its CPU time */
    SH_SANDBOX_WALL,    /* past the wall-clock limit */
    SH_SANDBOX_MEMORY,  /* over its memory */
    SH_SANDBOX_BROKEN,  /* feed refused the answer */
} sh_sandbox_outcome;

typedef struct {
    sh_sandbox_outcome outcome;
    int exit_status;     /* SH_SANDBOX_DONE: the child's; −1 if it could not be reaped */
    int signal;          /* SH_SANDBOX_SIGNAL */
    double cpu_seconds;  /* the child's user + system time */
    double cpu_limit;    /* the whole seconds RLIMIT_CPU allowed */
    char first_line[256]; /* the first line it wrote to stderr (no sanitizer "==PID==") */
} sh_sandbox_result;

/* Run the job in a child made by fork(2) (every signal blocked across the
 * fork; the child resets all to default, reads /dev/null, writes stdout to
 * /dev/null and stderr to a pipe, dies with its parent, writes no file and
 * dumps no core, and leaves by _exit) and wait for it within the limits.
 * SH_OK and *res whatever happened to the child; SH_EIO if none could be
 * started. */
int sh__sandbox_run(const sh_sandbox_job *job, sh_sandbox_result *res);

#endif

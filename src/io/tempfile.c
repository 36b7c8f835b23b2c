/* tempfile.c — atomic output: every file the library (or the CLI) writes is
 * first written under a temporary name "<target>.tmp.XXXXXX" next to its
 * target and renamed onto the target only when it is complete, so a failure
 * never leaves a partial file and never truncates or removes an existing one.
 *
 * Live temporary names are kept in a small registry so that a signal handler
 * can remove them (sh__temp_files_unlink: only atomic loads and unlink(2),
 * both async-signal-safe).  A name is registered as the file is created
 * (signals held in between) and leaves the registry only after it has been
 * renamed or removed, so a signal at any point finds every temporary that
 * may exist.
 *
 * Threads.  A handler runs in one thread while the others go on, and a
 * writer may (re)create a name after the handler removed it: a library that
 * opens its temporary by name (OpenEXR, a FILE*), or the rename of a nested
 * temporary onto its parent (sh_exr_write into the CLI's temporary).  So
 * every operation that creates or renames a temporary name runs inside a
 * window (sh__temp_enter/leave: signals blocked in that thread, a counter of
 * open windows), and sh__temp_files_unlink first marks the process as dying,
 * waits for the open windows to close, then removes the names; a thread that
 * would open a window after that waits for the end instead.  The wait is
 * bounded (TEMP_WAIT_NS): a window that does not close (its thread waiting
 * for a lock held by the interrupted thread, say) costs at most that delay,
 * never a hang.  Nothing inside a window allocates in this file.
 */
#include "core/shlab_internal.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define TMP_SUFFIX ".tmp.XXXXXX"
#define NSLOTS 64

/* Each slot holds the registry's own copy of a live temporary name, so that
 * what callers do with their string (free it, or remove the file without
 * telling the registry, as older code did) never leaves the registry with a
 * dangling pointer: at worst a stale name, whose unlink fails harmlessly. */
static char *_Atomic slots[NSLOTS];

/* ---- windows (see above) */
#define TEMP_WAIT_NS 200000000L
static atomic_int open_windows, dying;

void sh__temp_enter(sigset_t *old)
{
    sigset_t all;
    sigfillset(&all);
    for (;;) {
        pthread_sigmask(SIG_BLOCK, &all, old);
        atomic_fetch_add(&open_windows, 1);
        if (!atomic_load(&dying)) return;
        atomic_fetch_sub(&open_windows, 1);
        pthread_sigmask(SIG_SETMASK, old, NULL);
        for (;;) pause(); /* the process is being stopped: no new name */
    }
}

void sh__temp_leave(const sigset_t *old)
{
    atomic_fetch_sub(&open_windows, 1);
    pthread_sigmask(SIG_SETMASK, old, NULL);
}

/* (copy: the registry's own copy of the name, made outside the window) */
static void reg_add(char *copy)
{
    if (!copy) return; /* still written atomically, only not removed by a signal handler */
    for (int k = 0; k < NSLOTS; k++) {
        char *expect = NULL;
        if (atomic_compare_exchange_strong(&slots[k], &expect, copy)) return;
    }
    free(copy); /* registry full (more than 64 temporaries at once) */
}

static void reg_remove(const char *p)
{
    for (int k = 0; k < NSLOTS; k++) {
        char *cur = atomic_load(&slots[k]);
        if (cur && !strcmp(cur, p) && atomic_compare_exchange_strong(&slots[k], &cur, NULL)) {
            free(cur);
            return;
        }
    }
}

void sh__temp_files_unlink(void)
{
    /* no new name from now on; let the open windows close (bounded) */
    atomic_store(&dying, 1);
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    while (atomic_load(&open_windows) > 0) {
        clock_gettime(CLOCK_MONOTONIC, &t);
        if ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) > TEMP_WAIT_NS) break;
    }
    /* unlink only: the names stay registered (and reachable), nothing is
     * freed, so this is safe in a signal handler and at exit */
    for (int k = 0; k < NSLOTS; k++) {
        const char *p = atomic_load(&slots[k]);
        if (p) unlink(p);
    }
}

int sh__make_temp_path(const char *path, char **tmp_out)
{
    *tmp_out = NULL;
    if (!path || !*path) return sh_error(SH_EINVAL, "empty output path");
    /* The file really written is the link's target when path is a symbolic
     * link (the link stays a link), and an existing target must be a regular
     * file: renaming over /dev/null or a FIFO would replace the node itself. */
    struct stat sb;
    char *target = NULL;
    if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode)) {
        target = realpath(path, NULL);
        if (!target) return sh_error(SH_EIO, "cannot write '%s': it is a symbolic link to nowhere", path);
    } else {
        target = strdup(path);
        if (!target) return sh_error(SH_ENOMEM, "out of memory");
    }
    if (stat(target, &sb) == 0 && !S_ISREG(sb.st_mode)) {
        free(target);
        return sh_error(SH_EIO, "cannot write '%s': %s", path,
                        S_ISDIR(sb.st_mode) ? "it is a directory" : "not a regular file");
    }
    const size_t n = strlen(target) + sizeof TMP_SUFFIX;
    char *tmp = malloc(n);
    if (!tmp) {
        free(target);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    snprintf(tmp, n, "%s" TMP_SUFFIX, target);
    free(target);
    /* mkstemp picks the name and creates the file inside a window, so a
     * handler never misses this file; the registry's copy is allocated
     * first (mkstemp only fills in the X's) */
    char *copy = strdup(tmp);
    sigset_t old;
    sh__temp_enter(&old);
    int fd = mkstemp(tmp);
    const int e = errno;
    if (fd >= 0 && copy) memcpy(copy, tmp, strlen(tmp) + 1);
    if (fd >= 0) reg_add(copy);
    sh__temp_leave(&old);
    if (fd < 0 || !copy) {
        if (fd >= 0) sh__discard_temp(tmp), close(fd);
        free(copy);
        free(tmp);
        return sh_error(fd < 0 ? SH_EIO : SH_ENOMEM, "cannot write '%s': %s", path, fd < 0 ? strerror(e) : "out of memory");
    }
    close(fd);
    *tmp_out = tmp;
    return SH_OK;
}

int sh__commit_temp(const char *tmp, const char *path)
{
    if (!tmp) return sh_error(SH_EINVAL, "no temporary file to commit");
    /* the target is the temporary name without its suffix (see above) */
    const size_t n = strlen(tmp) - (sizeof TMP_SUFFIX - 1);
    char *target = strndup(tmp, n);
    if (!target) {
        sh__discard_temp(tmp);
        return sh_error(SH_ENOMEM, "out of memory");
    }
    /* mkstemp makes the file 0600; give it the usual 0666 & ~umask */
    mode_t um = umask(0);
    umask(um);
    chmod(tmp, 0666 & ~um);
    sigset_t old;
    sh__temp_enter(&old);
    int rc = rename(tmp, target);
    int e = errno;
    sh__temp_leave(&old);
    free(target);
    if (rc != 0) {
        sh__discard_temp(tmp);
        return sh_error(SH_EIO, "cannot write '%s': %s", path, strerror(e));
    }
    reg_remove(tmp); /* after the rename: a signal before it still removes tmp */
    return SH_OK;
}

void sh__discard_temp(const char *tmp)
{
    if (!tmp) return;
    unlink(tmp);
    reg_remove(tmp);
}

FILE *sh__temp_fopen(const char *tmp, const char *mode)
{
    /* open(2) inside the window (no allocation), fdopen after it */
    sigset_t old;
    sh__temp_enter(&old);
    const int fd = open(tmp, O_WRONLY | O_TRUNC | O_CLOEXEC);
    sh__temp_leave(&old);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, mode);
    if (!f) close(fd);
    return f;
}

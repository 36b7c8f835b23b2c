/* tempfile.c — atomic output: every file the library (or the CLI) writes is
 * first written under a temporary name "<target>.tmp.XXXXXX" next to its
 * target and renamed onto the target only when it is complete, so a failure
 * never leaves a partial file and never truncates or removes an existing one.
 *
 * Live temporary names are kept in a small registry so that a signal handler
 * can remove them (sh_temp_files_unlink: only atomic loads and unlink(2),
 * both async-signal-safe).  A name is registered as the file is created
 * (signals held in between) and leaves the registry only after it has been
 * renamed or removed, so a signal at any point finds every temporary that
 * may exist.
 */
#include "core/shlab_internal.h"

#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define TMP_SUFFIX ".tmp.XXXXXX"
#define NSLOTS 64

/* Each slot holds the registry's own copy of a live temporary name, so that
 * what callers do with their string (free it, or remove the file without
 * telling the registry, as older code did) never leaves the registry with a
 * dangling pointer: at worst a stale name, whose unlink fails harmlessly. */
static char *_Atomic slots[NSLOTS];

static void reg_add(const char *p)
{
    char *copy = strdup(p);
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

void sh_temp_files_unlink(void)
{
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
    /* mkstemp picks the name and creates the file; signals are held until
     * the name is registered, so a handler never misses this file */
    sigset_t all, old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old);
    int fd = mkstemp(tmp);
    const int e = errno;
    if (fd >= 0) reg_add(tmp);
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (fd < 0) {
        free(tmp);
        return sh_error(SH_EIO, "cannot write '%s': %s", path, strerror(e));
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
    int rc = rename(tmp, target);
    int e = errno;
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

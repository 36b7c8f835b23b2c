/* input_file.c — the one policy every reader of the library and of the CLI
 * applies to an input file (meshes, EXR images, fixtures, candidates,
 * coefficient files, shard files):
 *
 *  - it is opened with O_NONBLOCK, so that a FIFO or a device with no writer
 *    never blocks the open, and refused unless it is a regular file (a FIFO,
 *    a directory, a device, a socket each named in the message);
 *  - its size is checked against the reader's limit before a byte is read
 *    (so /dev/zero or a huge file costs nothing);
 *  - messages are the same for every reader:
 *        cannot open WHAT 'PATH': <strerror>
 *        cannot read WHAT 'PATH': it is a directory | not a regular file (a FIFO) ...
 *        WHAT 'PATH' has N bytes, more than the M a WHAT may have
 *
 * The descriptor is returned blocking again (O_NONBLOCK cleared), ready for
 * read(2), fdopen(3) or mmap(2). */
#include "core/shlab_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind_of(mode_t m)
{
    return S_ISDIR(m) ? "it is a directory" : S_ISFIFO(m) ? "not a regular file (a FIFO)"
           : S_ISCHR(m) ? "not a regular file (a character device)" : S_ISBLK(m) ? "not a regular file (a block device)"
           : S_ISSOCK(m) ? "not a regular file (a socket)" : "not a regular file";
}

int sh_input_open(const char *what, const char *path, long long max_bytes, sh_input *in)
{
    if (!in) return sh_error(SH_EINVAL, "sh_input_open: no output");
    memset(in, 0, sizeof *in);
    in->fd = -1;
    if (!what) what = "file";
    if (!path || !*path) return sh_error(SH_EINVAL, "no %s given (empty path)", what);
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return sh_error(SH_EIO, "cannot open %s '%s': %s", what, path, strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        const int e = errno;
        close(fd);
        return sh_error(SH_EIO, "cannot read %s '%s': %s", what, path, strerror(e));
    }
    if (!S_ISREG(sb.st_mode)) {
        close(fd);
        return sh_error(SH_EIO, "cannot read %s '%s': %s", what, path, kind_of(sb.st_mode));
    }
    if (max_bytes >= 0 && (long long)sb.st_size > max_bytes) {
        char a[32], b[32];
        close(fd);
        return sh_error(SH_EFORMAT, "%s '%s' has %s, more than the %s a %s may have", what, path,
                        sh__bytes_str((double)sb.st_size, a, sizeof a), sh__bytes_str((double)max_bytes, b, sizeof b),
                        what);
    }
    const int fl = fcntl(fd, F_GETFL);
    if (fl != -1) fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    in->fd = fd;
    in->size = (long long)sb.st_size;
    in->dev = (unsigned long long)sb.st_dev;
    in->ino = (unsigned long long)sb.st_ino;
    return SH_OK;
}

void sh_input_close(sh_input *in)
{
    if (in && in->fd >= 0) close(in->fd);
    if (in) in->fd = -1;
}

int sh_input_read_all(const char *what, const char *path, long long max_bytes, char **buf, size_t *n)
{
    *buf = NULL;
    *n = 0;
    sh_input in;
    int st = sh_input_open(what, path, max_bytes, &in);
    if (st) return st;
    /* the size was read by fstat; a file that grows meanwhile is cut at the limit + 1 and refused */
    const size_t cap = (size_t)in.size + 1;
    char *b = malloc(cap + 1);
    if (!b) {
        sh_input_close(&in);
        return sh_error(SH_ENOMEM, "out of memory reading %s '%s' (%lld bytes)", what, path, in.size);
    }
    size_t got = 0;
    while (got < cap) {
        const ssize_t r = read(in.fd, b + got, cap - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) {
            const int e = errno;
            free(b);
            sh_input_close(&in);
            return sh_error(SH_EIO, "cannot read %s '%s': %s", what, path, strerror(e));
        }
        if (r == 0) break;
        got += (size_t)r;
    }
    sh_input_close(&in);
    if (max_bytes >= 0 && (long long)got > max_bytes) {
        free(b);
        return sh_error(SH_EFORMAT, "%s '%s' grew past %lld bytes while it was read", what, path, max_bytes);
    }
    b[got] = '\0';
    *buf = b;
    *n = got;
    return SH_OK;
}

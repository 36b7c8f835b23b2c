/* memory.c — how much memory a job may take: the sizes of big allocations are
 * checked against what the machine has before anything is allocated, so a
 * request that cannot fit is refused with one line naming its size instead of
 * being overcommitted and killed later. */
#include "core/shlab_internal.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

size_t sh__mem_available(void)
{
    /* MemAvailable (Linux ≥ 3.14): free memory plus what the page cache
     * would give back; else the free pages */
    size_t avail = SIZE_MAX;
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        char line[256];
        unsigned long long kb = 0;
        int found = 0;
        while (!found && fgets(line, sizeof line, f))
            found = sscanf(line, "MemAvailable: %llu kB", &kb) == 1;
        fclose(f);
        if (found) avail = (size_t)kb * 1024;
    }
    if (avail == SIZE_MAX) {
        const long pages = sysconf(_SC_AVPHYS_PAGES), psz = sysconf(_SC_PAGESIZE);
        if (pages > 0 && psz > 0) avail = (size_t)pages * (size_t)psz;
    }
    /* an address-space limit (ulimit -v) binds first */
    struct rlimit rl;
    if (!getrlimit(RLIMIT_AS, &rl) && rl.rlim_cur != RLIM_INFINITY && (size_t)rl.rlim_cur < avail)
        avail = (size_t)rl.rlim_cur;
    return avail;
}

const char *sh__bytes_str(double bytes, char *buf, size_t n)
{
    if (bytes >= 1e9) snprintf(buf, n, "%.1f GB", bytes / 1e9);
    else if (bytes >= 1e6) snprintf(buf, n, "%.1f MB", bytes / 1e6);
    else snprintf(buf, n, "%.0f kB", bytes / 1e3);
    return buf;
}

int sh__mem_check(double bytes, const char *what)
{
    /* below 64 MiB the answer is yes on any machine that runs us at all (a
     * failing malloc is still reported), and a small rotator, made once per
     * rotation by some callers, must not read a file each time */
    if (bytes < SH__MEM_CHECK_FROM) return SH_OK;
    /* an eighth of what is available is left to everything else running */
    const size_t avail = sh__mem_available();
    const double usable = (double)avail - (double)(avail / 8);
    if (bytes <= usable) return SH_OK;
    char a[32], b[32];
    return sh_error(SH_ENOMEM, "%s needs %s of memory; %s is available", what,
                    sh__bytes_str(bytes, a, sizeof a), sh__bytes_str((double)avail, b, sizeof b));
}

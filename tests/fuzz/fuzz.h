/* fuzz.h — shared by the fuzz harnesses (tests/fuzz/fuzz_*.c).
 *
 * Each harness defines LLVMFuzzerTestOneInput for one kind of input and is
 * linked two ways: with clang's libFuzzer (make fuzz) and with replay.c, a
 * main that feeds it every file of a corpus (make check, with ASan/UBSan
 * under SANITIZE=1).  A harness checks the contract of what it calls: a
 * status, and on failure exactly one line of reason and nothing allocated;
 * a broken contract aborts, which both drivers report. */
#ifndef SHLAB_FUZZ_H
#define SHLAB_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* abort with a message when the contract is broken */
#define FUZZ_CHECK(cond, ...)                                                          \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "fuzz contract broken at %s:%d: ", __FILE__, __LINE__);    \
            fprintf(stderr, __VA_ARGS__);                                              \
            fputc('\n', stderr);                                                       \
            abort();                                                                   \
        }                                                                              \
    } while (0)

/* a NUL-terminated copy of the input (malloc'd) */
static inline char *fuzz_cstr(const uint8_t *data, size_t size)
{
    char *s = malloc(size + 1);
    if (!s) abort();
    if (size) memcpy(s, data, size);
    s[size] = '\0';
    return s;
}

/* the library's reason after a failure: one printable line */
static inline void fuzz_check_reason(void)
{
    const char *why = sh_last_error();
    FUZZ_CHECK(why && why[0], "empty reason");
    for (const char *p = why; *p; p++)
        FUZZ_CHECK((unsigned char)*p >= 0x20 && *p != 0x7f, "control character in reason: %s", why);
}

#endif

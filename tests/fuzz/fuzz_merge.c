/* fuzz_merge.c — shard files (cli_merge_mem: `shlab merge`'s reader and
 * join, from memory): the input is one or more shard files separated by the
 * byte 0x1e (ASCII record separator), given to merge in that order.  Every
 * line is checked before merge keeps it; a merge that succeeds gives a
 * result object with finite numbers and an exit status of 0 or 1 (plan's
 * result is its checked rows: its finish would time the methods). */
#include "fuzz.h"

#define FUZZ_MERGE_MAX_FILES 8

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *buf[FUZZ_MERGE_MAX_FILES], *name[FUZZ_MERGE_MAX_FILES];
    size_t len[FUZZ_MERGE_MAX_FILES];
    static const char *const names[FUZZ_MERGE_MAX_FILES] = {"s0.jsonl", "s1.jsonl", "s2.jsonl", "s3.jsonl",
                                                            "s4.jsonl", "s5.jsonl", "s6.jsonl", "s7.jsonl"};
    char *s = fuzz_cstr(data, size);
    int nf = 0;
    size_t start = 0;
    for (size_t i = 0; i <= size && nf < FUZZ_MERGE_MAX_FILES; i++)
        if (i == size || s[i] == 0x1e) {
            buf[nf] = s + start;
            len[nf] = i - start;
            name[nf] = names[nf];
            nf++;
            start = i + 1;
        }
    json_t *result = (json_t *)1;
    int code = -1;
    /* plan's finish times the methods (a second): its rows are checked and
     * joined, not timed */
    const int rc = cli_merge_mem(nf, buf, len, name, 0, &result, &code);
    if (rc == 0) {
        FUZZ_CHECK(json_is_object(result), "no result after success");
        FUZZ_CHECK(code == CLI_EXIT_OK || code == CLI_EXIT_CHECK, "exit status %d", code);
        FUZZ_CHECK(!cli_json_bad(result), "a non-finite number in the result");
        json_decref(result);
    } else {
        FUZZ_CHECK(rc == CLI_EXIT_USAGE && result == NULL, "exit code %d, result %p", rc, (void *)result);
    }
    free(s);
    return 0;
}
